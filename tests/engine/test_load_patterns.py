"""Load patterns and surge (SPEC 6.2): per-section material in the loop, the statics of a
two-section profile by hand, the transient model following the same per-element arrays."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import (
    InputError,
    Scenario,
    parse_conveyor,
    parse_scenario,
    section_loads,
)
from beltstudy.engine.dynamics import build_system, simulate
from beltstudy.engine.loop import CARRY, G, build_loop
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

#: Hand numbers of the two-section conveyor (tests/conftest.py: hand_conveyor_dict):
#: m'_G = 20, m'_L = 50 (design), m'_R = 10 carry, 3 return [kg/m]; f = 0.020 both strands.
MG, ML, MRC, MRR, F = 20.0, 50.0, 10.0, 3.0, 0.020
L1, H1, L2, H2 = 500.0, 25.0, 500.0, -20.0


def two_sections(**over):
    """The hand conveyor over a rise then a fall, secondary resistances and accessories off
    (C = 1 is passed to the model), so Te is main resistances plus material lift."""
    d = hand_conveyor_dict(profile=[{"length_m": L1, "lift_m": H1},
                                    {"length_m": L2, "lift_m": H2}],
                           accessories={"head_kn": 0.0, "tail_kn": 0.0})
    d.update(over)
    return parse_conveyor(d)


DIN = {"f_carry": F, "f_return": F, "c": 1.0}


def te_by_hand(m1: float, m2: float) -> dict:
    """DIN 22101 Te of the two-section conveyor with material m1, m2 [kg/m] per section,
    term by term [N]: F_H = f g L [m'_R + (m'_G + m'_L) cos a] per strand, lift g m'_L H."""
    c1 = math.sqrt(1.0 - (H1 / L1) ** 2)
    c2 = math.sqrt(1.0 - (H2 / L2) ** 2)
    carry = F * G * (L1 * (MRC + (MG + m1) * c1) + L2 * (MRC + (MG + m2) * c2))
    ret = F * G * ((L1 + L2) * MRR + MG * (L1 * c1 + L2 * c2))
    lift = G * (m1 * H1 + m2 * H2)  # the belt's own lift cancels round the loop
    return {"main_carry": carry, "main_return": ret, "lift": lift, "te": carry + ret + lift}


def test_section_loads_of_each_pattern():
    conv = two_sections()
    assert section_loads("full", conv) == (1.0, 1.0)
    assert section_loads("empty", conv) == (0.0, 0.0)
    assert section_loads("inclines", conv) == (1.0, 0.0)
    assert section_loads("declines", conv) == (0.0, 1.0)
    assert section_loads([0.5, 1.2], conv) == (0.5, 1.2)
    assert section_loads(1.2, conv) == (1.2, 1.2)
    with pytest.raises(InputError, match=r"scenario.load: 3 fractions for 2 profile sections"):
        section_loads([1, 1, 1], conv)
    with pytest.raises(InputError, match=r"less than or equal to 1.3"):
        parse_scenario({"load": 1.4})
    assert parse_scenario({"load": "inclines"}).load == "inclines"
    assert parse_scenario({"load": [0, 1]}).load == [0.0, 1.0]


@pytest.mark.parametrize("load, m1, m2", [
    ("full", ML, ML),
    ("inclines", ML, 0.0),
    ("declines", 0.0, ML),
    ([0.5, 1.0], 0.5 * ML, ML),
])
def test_two_section_statics_by_hand(load, m1, m2):
    conv = two_sections()
    res = solve_steady(conv, model="din", params=DIN, load=load, n_elements=100)
    loop = res.loop
    carry = loop.strand == CARRY
    first = carry & (loop.s_m < L1)
    assert_allclose(loop.mL_kg_m[first], m1, rtol=1e-12)
    assert_allclose(loop.mL_kg_m[carry & ~first], m2, rtol=1e-12)
    assert_allclose(loop.mL_kg_m[~carry], 0.0)
    hand = te_by_hand(m1, m2)
    parts = res.summary["te_components_kn"]
    for name in ("main_carry", "main_return", "lift"):
        assert_allclose(parts[name] * 1e3, hand[name], rtol=1e-9)
    assert_allclose(res.te_n, hand["te"], rtol=1e-9)
    assert_allclose(res.summary["t1_kn"] - res.summary["t2_kn"], hand["te"] / 1e3, rtol=1e-9)
    assert res.summary["load_mass_kg_m"] == pytest.approx(max(m1, m2))


def test_the_counterweight_of_a_pattern_is_at_least_the_full_load_one():
    conv = two_sections()
    full = solve_steady(conv, model="din", params=DIN, load="full").summary
    for load in ("inclines", "declines", [0.5, 1.0]):
        s = solve_steady(conv, model="din", params=DIN, load=load).summary
        assert s["takeup_mass_kg"] >= full["takeup_mass_kg"] * (1 - 1e-9)


def test_surge_above_the_design_load_warns():
    conv = two_sections()
    ok = solve_steady(conv, model="din", params=DIN, load=1.0)
    assert not any("surge" in w for w in ok.warnings)
    surge = solve_steady(conv, model="din", params=DIN, load=1.2)
    assert surge.status == "warning" and "surge: load 1.2" in surge.message
    hand = te_by_hand(1.2 * ML, 1.2 * ML)
    assert_allclose(surge.te_n, hand["te"], rtol=1e-9)
    per_section = solve_steady(conv, model="din", params=DIN, load=[1.0, 1.2])
    assert "surge" in per_section.message


@pytest.mark.parametrize("load", ["inclines", "declines", [0.5, 1.0]])
def test_transient_model_runs_on_the_same_per_element_masses(load):
    """The transient model reads the loop's per-element arrays: its gravity and masses are the
    pattern's, and the running phase settles onto the pattern's steady tensions (1 %)."""
    conv = two_sections()
    st = solve_steady(conv, model="din", params=DIN, load=load, n_elements=60)
    scn = Scenario(load=load, elements=60, start={"time_s": 20}, run_s=40)
    sys = build_system(conv, scn, st)
    loop = st.loop
    assert_allclose(sys.model.nodes.gravity, loop.gravity_n, rtol=1e-12)
    assert_allclose(sys.model.nodes.w_mean, loop.mass_kg, rtol=1e-12)
    res = simulate(sys, t_end_s=sys.stop_command_s - sys.dt_s)
    assert res.status != "failed", res.message
    T = res.raw["tension"]
    assert np.max(np.abs(T - st.tension_n) / st.tension_n) < 0.01


@pytest.mark.parametrize("load", ["inclines", "declines", [0.5, 1.0], 1.2])
def test_a_transient_run_with_each_pattern(load):
    conv = two_sections()
    scn = Scenario(load=load, elements=40, start={"time_s": 15}, run_s=5,
                   stop={"mode": "coast"})
    r = run_one(conv, scn, model="din", params=DIN)
    assert r.summary["status"] in ("ok", "warning"), r.summary["message"]
    assert r.summary["t_max_dyn_kn"] >= r.summary["t_max_kn"] * 0.99
    assert ("surge" in r.summary["message"]) is (load == 1.2)


def test_loop_where_names_the_strand_and_the_distance_from_the_tail():
    loop = build_loop(two_sections(), 1.0, n_elements=40)
    assert loop.where(100.0) == ("carry", 100.0)
    head_end = float(loop.s_end_m[loop.i_head])
    strand, x = loop.where(head_end + 250.0)
    assert strand == "return" and x == pytest.approx(1000.0 - 250.0)
    assert loop.where(float(loop.s_end_m[-1]) - 1e-6)[0] == "tail"
