"""Design checks (beltstudy.engine.checks, docs/checks.md): each against a hand calculation
from its formula, with the source cited, and the fields and warnings of a static run."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest
import yaml

from beltstudy.engine import checks as C
from beltstudy.engine.conveyor import Conveyor
from beltstudy.engine.loop import G, build_loop
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict

EXE = [sys.executable, "-m", "beltstudy.service.cli"]


# ----------------------------------------------------------- DIN 22101 pulley diameters
@pytest.mark.parametrize(("utilisation", "group", "d_min_m"), [
    # steel cord, cord diameter 5.85 mm (ST2000, carcass.csv [BVH]):
    # D_A = C_Tr d_Gk = 145 x 5.85 mm = 848.25 mm -> next table row 1000 mm (DIN 22101 table,
    # pulleys.csv): over 60 % A 1000 mm; over 30 % to 60 % one step down, A 800 mm;
    # up to 30 %, group B 630 mm, group C 500 mm
    (0.80, "A", 1.000),
    (0.50, "A", 0.800),
    (0.20, "B", 0.630),
    (0.20, "C", 0.500),
])
def test_pulley_diameter_steel_cord_by_din_22101(utilisation, group, d_min_m):
    assert 145.0 * 5.85 == pytest.approx(848.25)
    assert C.pulley_diameter_min_m("steel", 5.85e-3, group, utilisation) == pytest.approx(
        d_min_m, abs=1e-12)


@pytest.mark.parametrize(("utilisation", "group", "d_min_m"), [
    # fabric (polyester warp), carcass 4.6 mm (EP630/4, carcass.csv [EST]):
    # D_A = 108 x 4.6 mm = 496.8 mm -> row 500 mm: over 60 % A 500 mm, B 400 mm;
    # over 30 % to 60 % A 400 mm; up to 30 % A 315 mm
    (0.90, "A", 0.500),
    (0.90, "B", 0.400),
    (0.45, "A", 0.400),
    (0.10, "A", 0.315),
])
def test_pulley_diameter_fabric_by_din_22101(utilisation, group, d_min_m):
    assert 108.0 * 4.6 == pytest.approx(496.8)
    assert C.pulley_diameter_min_m("fabric", 4.6e-3, group, utilisation) == pytest.approx(
        d_min_m, abs=1e-12)


def test_every_catalogue_belt_has_a_carcass_thickness():
    """The minimum pulley diameter needs the carcass thickness: every belt of the catalogue
    (engine/data/belts.csv) has one in carcass.csv, so only a custom belt goes without."""
    belts = {r["id"] for r in C._rows("belts.csv")}
    missing = belts - set(C._carcass_mm())
    assert not missing, f"carcass.csv lacks {sorted(missing)}"


def test_the_incline_s_ep1250_belt_gets_its_minimum_pulley_by_hand():
    """EP1250/5, five EP250 plies of 1.25 mm (carcass.csv [MON]): d_Gk = 6.25 mm, D_A = 108 x
    6.25 = 675 mm -> row 800 mm: over 60 % group A 800 mm; over 30 % to 60 % 630 mm."""
    d = C._carcass_mm()["EP1250/5"]
    assert d == pytest.approx(5 * 1.25)
    assert C.pulley_diameter_min_m("fabric", d * 1e-3, "A", 0.8) == pytest.approx(0.8)
    assert C.pulley_diameter_min_m("fabric", d * 1e-3, "A", 0.5) == pytest.approx(0.63)


def test_pulley_diameter_band_edges_and_beyond_the_table():
    # the bands are "over 30 % to 60 %" and "over 60 % to 100 %": exactly 60 % is the middle
    # band, just above it the full one (steel 5.85 mm, group A: 800 and 1000 mm)
    assert C.pulley_diameter_min_m("steel", 5.85e-3, "A", 0.60) == pytest.approx(0.8)
    assert C.pulley_diameter_min_m("steel", 5.85e-3, "A", 0.6001) == pytest.approx(1.0)
    # D_A = 145 x 15 mm = 2175 mm, past the table's 2000 mm: group A is D_A itself, group B
    # keeps the last row's ratio 1600 / 2000
    assert C.pulley_diameter_min_m("steel", 15e-3, "A", 1.0) == pytest.approx(2.175)
    assert C.pulley_diameter_min_m("steel", 15e-3, "B", 1.0) == pytest.approx(2.175 * 0.8)


def test_pulley_groups_by_din_22101():
    # C: wrap under 30 deg; A: a drive, or a plain pulley in the upper half of the tension
    # range (here 100-500 kN: from 300 kN); B: the rest
    assert C.pulley_group(20.0, False, 400e3, 100e3, 500e3) == "C"
    assert C.pulley_group(180.0, True, 120e3, 100e3, 500e3) == "A"
    assert C.pulley_group(180.0, False, 300e3, 100e3, 500e3) == "A"
    assert C.pulley_group(180.0, False, 299e3, 100e3, 500e3) == "B"


# ----------------------------------------------------------- CEMA transition lengths
def test_transition_lengths_by_cema_table_7_29():
    # CEMA 7th ed. Table 7.29, full trough: steel cord, 35 deg, over 90 % of the rated tension:
    # 6.8 x B; B = 1.2 m -> 8.16 m
    assert C.transition_length_m("steel", 35.0, 1.2, 0.95) == pytest.approx(6.8 * 1.2)
    # fabric, 20 deg, 60 % to 90 %: 1.6 x B; B = 1.0 m -> 1.6 m
    assert C.transition_length_m("fabric", 20.0, 1.0, 0.70) == pytest.approx(1.6)
    # steel, 27.5 deg, under 60 %: halfway between 20 deg (2.8) and 35 deg (3.6) -> 3.2 x B
    assert C.transition_length_m("steel", 27.5, 1.0, 0.30) == pytest.approx(3.2)
    # a flat belt needs no transition
    assert C.transition_length_m("fabric", 0.0, 1.0, 0.95) == 0.0


# ----------------------------------------------------------- pulley resultant
def test_pulley_resultant_at_180_and_90_degrees():
    # R = sqrt(T_in^2 + T_out^2 - 2 T_in T_out cos(wrap)) (law of cosines, DIN 22101)
    # 180 deg: cos = -1, R = T_in + T_out = 100 + 60 = 160 kN
    assert C.pulley_resultant_n(100e3, 60e3, 180.0) == pytest.approx(160e3, rel=1e-12)
    # 90 deg: cos = 0, R = sqrt(100^2 + 60^2) = 116.619 kN
    assert C.pulley_resultant_n(100e3, 60e3, 90.0) == pytest.approx(
        math.sqrt(100e3**2 + 60e3**2), rel=1e-12)
    assert math.sqrt(100**2 + 60**2) == pytest.approx(116.619, abs=1e-3)


def test_transient_resultant_from_the_envelope():
    # a loop of slope-5pct: pulley 1 the head drive (210 deg), pulley 2 the tail take-up
    # pulley (180 deg); the envelope's highest tensions either side of each pulley give
    # R = sqrt(a^2 + b^2 - 2 a b cos(wrap)): at the tail 50 + 45 = 95 kN (180 deg)
    conv = Conveyor.model_validate(yaml.safe_load((CONVEYORS / "slope-5pct.yaml").read_text()))
    loop = build_loop(conv, [1.0], n_elements=40)
    t_max = np.full(loop.n, 100e3)
    head, tail = loop.pulleys
    t_max[head.element - 1], t_max[head.element] = 400e3, 150e3
    t_max[tail.element - 1], t_max[tail.element] = 50e3, 45e3
    out = C.transient_checks(loop, t_max)
    c210 = math.cos(math.radians(210.0))
    assert out["pulley1_resultant_dyn_kn"] == pytest.approx(
        math.sqrt(400**2 + 150**2 - 2 * 400 * 150 * c210), rel=1e-12)
    assert out["pulley2_resultant_dyn_kn"] == pytest.approx(95.0, rel=1e-12)
    # per envelope segment (start; stop): the head's tight side peaks at 400 kN in the start
    # with 100 kN slack, its slack side at 150 kN in the stop with 200 kN tight: the bound is
    # max(R(400, 100), R(200, 150)) = R(400, 100), below the whole cycle's R(400, 150)
    seg = np.vstack([t_max, t_max])
    seg[0, head.element] = 100e3
    seg[1, head.element - 1] = 200e3
    out = C.transient_checks(loop, seg)
    r_400_100 = math.sqrt(400**2 + 100**2 - 2 * 400 * 100 * c210)
    assert r_400_100 > math.sqrt(200**2 + 150**2 - 2 * 200 * 150 * c210)
    assert out["pulley1_resultant_dyn_kn"] == pytest.approx(r_400_100, rel=1e-12)


# ----------------------------------------------------------- idler load and L10
def test_idler_load_per_set_and_roll_and_l10():
    # DIN 22101 / ISO 5048: F = g (m'_G + m'_L) S = 9.81 x (40 + 120) x 1.5 = 2354.4 N
    f_set = C.idler_load_set_n(40.0, 120.0, 1.5)
    assert f_set == pytest.approx(9.81 * 160 * 1.5) and f_set == pytest.approx(2354.4)
    # middle roll of a 35 deg three-roll set: 0.67 of the set (makers' participation factor)
    f_roll = C.middle_roll_share(3, 35.0) * f_set
    assert f_roll == pytest.approx(0.67 * 2354.4)
    # ISO 281: each of the roll's two bearings takes P = F_roll / 2 = 788.72 N; a 6205, C =
    # 14 800 N; roll 0.152 m at 4.5 m/s: n = 60 x 4.5 / (pi x 0.152) = 565.4 rpm;
    # L10 = (C / P)^3 x 10^6 / (60 n) = (18.765)^3 x 10^6 / 33 925 = 194 800 h
    p = f_roll / 2
    n = 60 * 4.5 / (math.pi * 0.152)
    assert n == pytest.approx(565.4, abs=0.1)
    l10 = C.bearing_l10_h(14800.0, p, 4.5, 0.152)
    assert l10 == pytest.approx((14800 / p) ** 3 * 1e6 / (60 * n), rel=1e-12)
    assert l10 == pytest.approx(1.948e5, rel=1e-3)


def test_roll_shares():
    assert C.middle_roll_share(1, 0.0) == 1.0
    assert C.middle_roll_share(2, 10.0) == 0.5
    assert C.middle_roll_share(3, 20.0) == pytest.approx(0.60)
    assert C.middle_roll_share(3, 40.0) == pytest.approx(0.695)  # halfway 0.67 - 0.72


# ----------------------------------------------------------- holdback
def test_holdback_torque_of_a_simple_incline():
    # CEMA's rule: lift less half the friction, at the pulley radius. 1 km rising 50 m with
    # m'_L = 100 kg/m: pull = 100 x 9.81 x 50 = 49 050 N; friction 30 kN; D = 1.0 m:
    # M = (49 050 - 15 000) x 0.5 = 17 025 N m
    assert C.holdback_torque_nm(100 * 9.81 * 50, 30e3, 1.0) == pytest.approx(17025.0)
    # friction twice the pull or more: the belt cannot run back
    assert C.holdback_torque_nm(10e3, 20e3, 1.0) == 0.0
    assert C.holdback_torque_nm(-5e3, 1e3, 1.0) == 0.0


def test_holdback_torque_of_the_hand_conveyor():
    # hand conveyor (tests/conftest.py): 1 km rising 50 m, m'_L = 50 kg/m, head pulley 1.0 m:
    # the belt's own lift cancels round the loop, pull = m'_L g H = 50 x 9.81 x 50 = 24 525 N;
    # friction = Te less lift and feed (the model's running resistances)
    res = solve_steady(Conveyor.model_validate(hand_conveyor_dict()), model="din")
    s = res.summary
    pull = 50 * G * 50
    assert s["te_components_kn"]["lift"] * 1e3 == pytest.approx(pull, rel=1e-9)
    friction = (s["te_kn"] - s["te_components_kn"]["lift"]
                - s["te_components_kn"]["feed"]) * 1e3
    assert s["holdback_torque_knm"] * 1e3 == pytest.approx(
        max(pull - 0.5 * friction, 0.0) * 1.0 / 2, rel=1e-9)
    assert s["holdback_torque_knm"] > 0.0
    # a custom belt has no carcass thickness in the catalogue: no minimum diameter
    assert s["pulley1_diameter_min_m"] is None and s["pulley1_diameter_min_ok"] is None


# ----------------------------------------------------------- a static run
def _static(path) -> dict:
    p = subprocess.run([*EXE, "static", str(path), "--model", "din", "--json"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)


def test_static_json_carries_the_checks_and_a_small_pulley_warns(tmp_path):
    d = yaml.safe_load((CONVEYORS / "slope-5pct.yaml").read_text())
    out = _static(CONVEYORS / "slope-5pct.yaml")
    for key in ("pulley1_name", "pulley1_diameter_min_m", "pulley1_diameter_min_ok",
                "pulley1_resultant_kn", "pulley2_resultant_kn", "transition_head_m",
                "transition_tail_m", "idler_load_carry_n", "idler_load_roll_n", "idler_l10_h",
                "holdback_torque_knm"):
        assert key in out, key
    assert "pulley3_name" not in out  # two pulleys: the head drive and the tail take-up
    assert out["pulley1_name"] == "drive 1 (head), group A"
    assert out["pulley1_diameter_min_ok"] is True
    assert "DIN 22101 minimum" not in out["message"]
    # ST2000 (cord 5.85 mm -> D_A 1000 mm): the head drive at over 60 % of the admissible
    # tension needs 1.0 m; a 0.63 m drive pulley is too small and the run says where
    assert out["t1_kn"] * 6.7 / out["belt_rating_kn"] > 0.6
    d["drives"][0]["pulley_diameter_m"] = 0.63
    small = tmp_path / "small.yaml"
    small.write_text(yaml.safe_dump(d))
    out = _static(small)
    assert out["pulley1_diameter_min_m"] == pytest.approx(1.0)
    assert out["pulley1_diameter_min_ok"] is False
    assert out["status"] == "warning"
    assert ("pulley 1 (drive 1 (head), group A) diameter 0.63 m is below the DIN 22101 "
            "minimum 1 m") in out["message"]


def test_idler_rating_and_l10_warn(tmp_path):
    # slope-5pct's carry set: g (m'_G + m'_L) S with m'_G = 1.2 x (12.6 + 14 x 1.15) = 34.44
    # kg/m, m'_L = 2000 / (3.6 x 4.5) = 123.46 kg/m, S = 1.5 m: 9.81 x 157.90 x 1.5 = 2323.5 N,
    # above the CEMA B rating of 410 lbf = 1824 N
    d = yaml.safe_load((CONVEYORS / "slope-5pct.yaml").read_text())
    d["idlers"]["carry"]["cema_class"] = "B"
    path = tmp_path / "b.yaml"
    path.write_text(yaml.safe_dump(d))
    out = _static(path)
    m_g = 1.2 * (12.6 + 14 * 1.15)
    m_l = 2000 / (3.6 * 4.5)
    assert out["idler_load_carry_n"] == pytest.approx(9.81 * (m_g + m_l) * 1.5, rel=1e-9)
    assert "exceeds the CEMA B rating 1824 N" in out["message"]
    # 6203 (C = 9950 N) under half the middle roll's 0.67 x 2323.5 N, 0.152 m rolls at
    # 4.5 m/s: (9950 / 778.4)^3 x 10^6 / (60 x 565.4) = 61 600 h, above CEMA's 30 000 h
    p = 0.67 * out["idler_load_carry_n"] / 2
    assert out["idler_l10_h"] == pytest.approx(
        (9950 / p) ** 3 * 1e6 / (60 * 60 * 4.5 / (math.pi * 0.152)), rel=1e-9)
    assert "bearing life" not in out["message"]
    # twice the pitch, 3.0 m: twice the load, P = 0.67 x 4647 N / 2 = 1557 N and
    # L10 = (9950 / 1557)^3 x 10^6 / (60 x 565.4) = 7 700 h, below CEMA's 30 000 h: a warning
    d["idlers"]["carry"]["spacing_m"] = 3.0
    path.write_text(yaml.safe_dump(d))
    out = _static(path)
    p = 0.67 * out["idler_load_carry_n"] / 2
    assert p == pytest.approx(0.67 * 9.81 * (m_g + m_l) * 3.0 / 2, rel=1e-9)
    l10 = (9950 / p) ** 3 * 1e6 / (60 * 60 * 4.5 / (math.pi * 0.152))
    assert l10 == pytest.approx(7.7e3, rel=0.01)
    assert out["idler_l10_h"] == pytest.approx(l10, rel=1e-9)
    assert "is below the CEMA B basis 30000 h" in out["message"]


def test_the_closer_pitch_named_for_the_rating_meets_it_when_applied():
    """Hand conveyor (m'_G 20, m'_L 50 kg/m) with CEMA B sets 3 m apart: 9.81 x 70 x 3 =
    2060.1 N per set, above the 1824 N rating; the pitch that meets it is 3 x 1824 / 2060.1 =
    2.6562 m. Rounded to the nearest the warning named 2.66 m, at which a set carries
    9.81 x 70 x 2.66 = 1826.6 N, still above the rating (and the rerun named 2.66 m again);
    rounded down it names 2.65 m: 1819.8 N, and the rerun has no idler warning."""
    def run(pitch):
        d = hand_conveyor_dict()
        d["idlers"]["carry"].update(cema_class="B", spacing_m=pitch)
        return solve_steady(Conveyor.model_validate(d), model="din", n_elements=100)

    st = run(3.0)
    assert st.summary["idler_load_carry_n"] == pytest.approx(9.81 * 70 * 3.0, rel=1e-12)
    assert 3.0 * 1824.0 / (9.81 * 70 * 3.0) == pytest.approx(2.6562, abs=1e-4)
    assert "a heavier class or a closer pitch (2.65 m)" in st.message
    assert C.pitch_within_m(3.0, 1824.0, 9.81 * 70 * 3.0) == 2.65
    assert C.pitch_within_m(1.5, 1000.0, 1000.0) == 1.5  # exactly at it: kept
    applied = run(2.65)
    assert applied.summary["idler_load_carry_n"] == pytest.approx(9.81 * 70 * 2.65, rel=1e-12)
    assert applied.summary["idler_load_carry_n"] < 1824.0
    assert "carry idler load" not in applied.message


def test_the_closer_pitch_named_for_the_bearing_life_meets_it_when_applied():
    """slope-5pct with CEMA B sets 3 m apart: L10 = (9950 / 1556.7)^3 x 10^6 / (60 x 565.4)
    = 7 697 h, below CEMA's 30 000 h. L10 goes as 1 / P^3 and P as the pitch, so the pitch
    with the basis life is 3 x (7697 / 30000)^(1/3) = 1.906 m, named rounded down, 1.90 m
    (the warning named no pitch before); at 1.90 m L10 = 7697 x (3 / 1.9)^3 = 30 300 h and
    the rerun has no bearing-life warning."""
    d = yaml.safe_load((CONVEYORS / "slope-5pct.yaml").read_text())

    def run(pitch):
        d["idlers"]["carry"].update(cema_class="B", spacing_m=pitch)
        return solve_steady(Conveyor.model_validate(d), model="din", n_elements=100)

    m = 1.2 * (12.6 + 14 * 1.15) + 2000 / (3.6 * 4.5)
    n_rpm = 60 * 4.5 / (math.pi * 0.152)
    l10 = (9950 / (0.67 * 9.81 * m * 3.0 / 2)) ** 3 * 1e6 / (60 * n_rpm)
    assert l10 == pytest.approx(7697, abs=1)
    st = run(3.0)
    assert st.summary["idler_l10_h"] == pytest.approx(l10, rel=1e-9)
    assert 3.0 * (l10 / 30000) ** (1 / 3) == pytest.approx(1.906, abs=1e-3)
    assert ("is below the CEMA B basis 30000 h: a heavier class, larger rolls or a closer "
            "pitch (1.90 m)") in st.message
    applied = run(1.90)
    assert applied.summary["idler_l10_h"] == pytest.approx(l10 * (3.0 / 1.9) ** 3, rel=1e-9)
    assert applied.summary["idler_l10_h"] > 30000
    assert "bearing life" not in applied.message


def test_transient_resultant_bounds_the_sampled_head_resultant():
    # the envelope is kept every step, so R(max T_in, max T_out) per segment is at least the
    # resultant of every recorded pair (t_head_in_kn, t_head_out_kn) of the first head pulley,
    # and at least the steady one; a steady-only run has no transient field
    from beltstudy.engine.conveyor import Scenario
    from beltstudy.engine.run import run_one
    from tests.conftest import WARM_UP_SCENARIO

    conv = Conveyor.model_validate(hand_conveyor_dict())
    r = run_one(conv, Scenario(**WARM_UP_SCENARIO), model="din")
    s, ts = r.summary, r.transient.series
    sampled = C.pulley_resultant_n(ts["t_head_in_kn"], ts["t_head_out_kn"], 200.0).max()
    assert s["pulley1_resultant_dyn_kn"] >= sampled * (1 - 1e-9)
    assert s["pulley1_resultant_dyn_kn"] >= s["pulley1_resultant_kn"] * (1 - 1e-6)
    assert s["pulley2_resultant_dyn_kn"] >= s["pulley2_resultant_kn"] * (1 - 1e-6)
    steady_only = run_one(conv, Scenario(**WARM_UP_SCENARIO), model="din", dynamics=False)
    assert "pulley1_resultant_dyn_kn" not in steady_only.summary


def test_band_edges_up_to_float_noise_are_at_the_edge():
    """A tension of exactly 90 % of an ST1000 belt's rated tension (1.0 m: 1000 kN / 6.7 =
    149.25 kN, 90 % = 134.33 kN) is in CEMA Table 7.29's "60 % to 90 %" row: 5.2 B = 5.2 m at
    35 deg steel cord. Formed as the run forms it, T x S_min / rating, it reads
    0.9000000000000001, and the transition was the "over 90 %" row's 6.8 m. Likewise a
    utilisation of 60 % up to float noise is DIN 22101's "over 30 % to 60 %" band: ST1600
    (5.85 mm cord, D_A = 145 x 5.85 = 848 -> 1000 mm), group A one step down, 0.8 m."""
    rating_n, sf = 1000e3, 6.7
    t = 0.9 * (rating_n / sf)  # 90 % of the rated tension
    u = t * sf / rating_n  # as checks.steady_checks forms it
    assert u > 0.9  # the float noise the band must not read
    assert C.transition_length_m("steel", 35.0, 1.0, u) == pytest.approx(5.2, abs=1e-12)
    assert C.transition_length_m("steel", 35.0, 1.0, 0.9 + 1e-6) == pytest.approx(6.8,
                                                                                  abs=1e-12)
    assert C.transition_length_m("steel", 35.0, 1.0, 0.6 * (1 - 1e-12)) == pytest.approx(
        5.2, abs=1e-12)
    assert C.pulley_diameter_min_m("steel", 5.85e-3, "A", 0.6 * (1 + 1e-12)) == pytest.approx(
        0.8, abs=1e-12)
    assert C.pulley_diameter_min_m("steel", 5.85e-3, "A", 0.6 + 1e-6) == pytest.approx(
        1.0, abs=1e-12)


def test_a_pulley_just_over_a_band_edge_is_not_said_at_the_edge(tmp_path):
    """slope-5pct (ST2000, 1.2 m, 2400 kN) with its head drive pulley 0.63 m and
    ``safety_factor_min`` set so that the drive's tension T1 is 60.04 % of the admissible
    tension (S = 0.6004 x 2400 / T1 kN): DIN 22101's "over 60 %" band, D_A 1000 mm, group A
    1.0 m, so the 0.63 m pulley is too small. The warning said "at 60 % of the admissible
    tension: a pulley of at least 1 m", where the table's 60 % row asks 0.8 m; it says
    60.04 %."""
    d = yaml.safe_load((CONVEYORS / "slope-5pct.yaml").read_text())
    d["drives"][0]["pulley_diameter_m"] = 0.63
    t1 = solve_steady(Conveyor.model_validate(d), model="din").summary["t1_kn"]
    d["safety_factor_min"] = 0.6004 * 2400.0 / t1
    st = solve_steady(Conveyor.model_validate(d), model="din")
    assert st.summary["t1_kn"] == pytest.approx(t1, rel=1e-12)  # S_min sizes nothing here
    assert st.summary["pulley1_diameter_min_m"] == pytest.approx(1.0)
    assert st.summary["pulley1_diameter_min_ok"] is False
    assert "for ST2000 at 60.04 % of the admissible tension: a pulley of at least 1 m" in (
        st.message)
