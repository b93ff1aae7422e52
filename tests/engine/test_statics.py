"""Tension walk closure, take-up sizing and the checks flipping at their thresholds."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.loop import G
from beltstudy.engine.statics import STARTUP_FACTOR, solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict


@pytest.mark.parametrize("model", ["din", "cema"])
@pytest.mark.parametrize("name", sorted(p.name for p in CONVEYORS.glob("*.yaml")))
def test_walk_closes(name, model):
    from beltstudy.engine.conveyor import load_conveyor

    res = solve_steady(load_conveyor(CONVEYORS / name), model=model, n_elements=300)
    T = res.tension_n
    dF = res.resistance_n + res.loop.gravity_n
    # Te is the sum of all element forces; the drives take it all
    assert_allclose(dF.sum(), res.te_n, rtol=1e-12)
    assert_allclose(res.drive_force_n.sum(), res.te_n, rtol=1e-12)
    # every step of the walk: T[j] - T[j-1] = R_j + G_j - D_j, round the closed loop
    assert_allclose(T - np.roll(T, 1), dF - res.drive_force_n, atol=1e-6 * np.abs(T).max())
    # the parts of Te add up to Te
    assert_allclose(sum(res.summary["te_components_kn"].values()), res.te_n / 1e3, rtol=1e-9)


def _euler(wrap_deg=200, mu=0.35):
    return math.exp(mu * math.radians(wrap_deg))


def shell_kg(diameter_m, width_m=1.0):
    """The pulley shell estimate by hand: 1.3 x 7850 x pi D (B + 0.2) (0.012 + 0.01 D) [kg]."""
    return 1.3 * 7850.0 * math.pi * diameter_m * (width_m + 0.2) * (0.012 + 0.01 * diameter_m)


def startup_t2_by_hand(te):
    """Slack side of the hand conveyor's head drive running, when start-up slip sets the
    take-up (DIN 22101 start-up: 1.5 Te accelerates every moving mass rigidly) [N].

    a = 0.5 Te / M, M = carry 1000 x (20 + 50 + 10) + return 1000 x (20 + 3) + the belt on the
    head pulley (200 deg of a 1 m pulley, 20 kg/m) and on the tail pulley (180 deg of 0.8 m),
    the tail pulley's shell and the drive's rotating parts (no inertia given: its shell). At
    start-up the drive gives 1.5 Te less its own inertia force, the belt on its pulley takes
    its own inertia force, and the slack side needs T2_start (e^(mu theta) - 1) = the rest. The tail take-up holds the same mean tension at
    start-up as running, so running T2 = T2_start + a x (the return strand's mass + half the
    tail pulley element's): the inertia force between the drive and the take-up."""
    head_arc = math.radians(200.0) * 0.5 * 20.0
    tail_element = math.pi * 0.4 * 20.0 + shell_kg(0.8)
    shaft = shell_kg(1.0)
    m_total = 1000 * 80.0 + 1000 * 23.0 + head_arc + tail_element + shaft
    a = (STARTUP_FACTOR - 1.0) * te / m_total
    t2_start = (STARTUP_FACTOR * te - (shaft + head_arc) * a) / (_euler() - 1.0)
    return t2_start + a * (1000 * 23.0 + 0.5 * tail_element)


def test_auto_takeup_meets_startup_slip_by_hand(hand_conveyor):
    res = solve_steady(hand_conveyor, model="din")
    te = res.te_n
    assert res.takeup_governed_by == "slip_start"
    assert_allclose(res.summary["t2_kn"] * 1e3, startup_t2_by_hand(te), rtol=1e-6)
    assert_allclose(res.summary["t1_kn"] - res.summary["t2_kn"], te / 1e3, rtol=1e-9)
    assert res.summary["slip_margin_start"] == pytest.approx(1.0, abs=1e-9)
    # gravity take-up: both strands at the tail carry m g / 2
    loop = res.loop
    k = loop.i_takeup
    assert_allclose(res.tension_n[k - 1] + res.tension_n[k],
                    res.summary["takeup_mass_kg"] * G, rtol=1e-9)
    assert res.status == "ok"


def test_slip_check_flips_at_threshold(hand_dict):
    auto = solve_steady(parse_conveyor(hand_dict), model="din")
    m_auto = auto.summary["takeup_mass_kg"]
    for factor, expect_slip in ((1.01, False), (0.99, True)):
        d = hand_conveyor_dict(takeup={"type": "gravity", "position": "tail",
                                       "mass_kg": m_auto * factor})
        res = solve_steady(parse_conveyor(d), model="din")
        slip = any("slip" in w for w in res.warnings)
        assert slip is expect_slip, res.warnings
        if expect_slip:
            assert res.status == "warning"
            assert "kg needed" in res.message  # names the limit and the fix


def test_impossible_fixed_takeup_warns_with_limit(hand_dict):
    hand_dict["takeup"] = {"type": "fixed", "position": "tail", "pretension_kn": 5.0}
    res = solve_steady(parse_conveyor(hand_dict), model="din")
    assert res.status == "warning"
    assert "slip" in res.message and "kN needed" in res.message


def test_sag_check_flips_at_threshold(hand_dict):
    base = solve_steady(parse_conveyor(hand_dict), model="din")
    loop, T = base.loop, base.tension_n
    Tm = 0.5 * (np.roll(T, 1) + T)
    carry = loop.strand == 0
    # sag h/S = g (m'_G + m'_L) cos S / (8 T) at the lowest carry tension, by hand
    jmin = np.argmin(np.where(carry, Tm, np.inf))
    sag = G * (20 + 50) * loop.cos_a[jmin] * 1.25 / (8 * Tm[jmin])
    carry_sag = 100 * np.max(np.where(carry, loop.sag_w_n / Tm, 0))
    assert_allclose(carry_sag, 100 * sag, rtol=1e-9)
    mass = base.summary["takeup_mass_kg"]
    for limit, expect in ((carry_sag * 1.01, False), (carry_sag * 0.99, True)):
        hand_dict["sag_limit_pct"] = {"carry": limit, "return": 50.0}
        hand_dict["takeup"] = {"type": "gravity", "position": "tail", "mass_kg": mass}
        res = solve_steady(parse_conveyor(hand_dict), model="din")
        flagged = any("sag on the carry strand" in w for w in res.warnings)
        assert flagged is expect


def test_auto_takeup_meets_sag_when_sag_governs(hand_dict):
    """Sag governs, and it governs held at rest: with no running resistance the carry strand
    just after the tail take-up is at its lowest. By hand: at rest the free tail pulley passes
    the counterweight's m g / 2 onto the carry strand, and that is the sag minimum
    g (m'_G + m'_L) cos(a) S / (8 h/S)."""
    hand_dict["sag_limit_pct"] = {"carry": 0.2, "return": 5.0}
    res = solve_steady(parse_conveyor(hand_dict), model="din")
    loop = res.loop
    sin_a = 50.0 / 1000.0
    cos_a = math.sqrt(1.0 - sin_a**2)
    t_min_sag = G * (20 + 50) * cos_a * 1.25 / (8 * 0.002)
    assert loop.strand[0] == 0 and loop.i_takeup == loop.n - 1  # carry starts after the tail
    assert_allclose(res.summary["takeup_mass_kg"] * G / 2, t_min_sag, rtol=1e-6)
    # running, the resistances only add tension: the sag stays under the limit
    assert 0.19 < res.summary["sag_max_pct"] <= 0.2
    assert res.summary["slip_margin_start"] > 1.0
    assert not res.warnings


def test_auto_takeup_is_the_full_load_one_for_every_load_case(hand_dict):
    """The counterweight is installed once: an empty run keeps the full-load mass (sized here
    by start-up slip, T2 = 1.5 Te_full / (e^{mu theta} - 1)), which is heavier than what the
    empty belt alone would need."""
    conv = parse_conveyor(hand_dict)
    full = solve_steady(conv, model="din", load="full").summary
    empty = solve_steady(conv, model="din", load="empty").summary
    assert empty["te_kn"] < 0.5 * full["te_kn"]
    assert_allclose(empty["takeup_mass_kg"], full["takeup_mass_kg"], rtol=1e-9)
    hand_dict["takeup"] = {"type": "gravity", "position": "tail",
                           "mass_kg": 0.5 * full["takeup_mass_kg"]}
    light = solve_steady(parse_conveyor(hand_dict), model="din", load="empty").summary
    assert light["slip_margin_start"] > 1.0  # half the mass would do for the empty belt


def test_safety_factor_flips_at_threshold(hand_dict):
    res = solve_steady(parse_conveyor(hand_dict), model="din")
    sf = res.summary["safety_factor"]
    # safety factor = rating x width / T_max = 1000 kN/m * 1 m / t_max
    assert_allclose(sf, 1000.0 / res.summary["t_max_kn"], rtol=1e-12)
    for sf_min, expect in ((sf * 0.99, False), (sf * 1.01, True)):
        hand_dict["safety_factor_min"] = sf_min
        r = solve_steady(parse_conveyor(hand_dict), model="din")
        assert any("safety factor" in w for w in r.warnings) is expect


def test_regenerating_drive_tight_side_outgoing():
    from beltstudy.engine.conveyor import load_conveyor

    res = solve_steady(load_conveyor(CONVEYORS / "downhill-regen.yaml"), model="din")
    assert res.te_n < 0  # the drive brakes the belt
    i = res.loop.i_head
    t_in, t_out = res.tension_n[i - 1], res.tension_n[i]
    assert t_out > t_in
    assert res.summary["t1_kn"] == pytest.approx(t_out / 1e3)


def test_elements_do_not_change_din(hand_conveyor):
    a = solve_steady(hand_conveyor, model="din", n_elements=20).summary
    b = solve_steady(hand_conveyor, model="din", n_elements=2000).summary
    assert_allclose(a["te_kn"], b["te_kn"], rtol=1e-9)
    assert_allclose(a["t_max_kn"], b["t_max_kn"], rtol=1e-9)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_a_steady_state_past_float_range_fails_naming_it(hand_conveyor):
    """CEMA's ky at 1e308 overflows every tension: the run is failed and says why, not a
    warning row of nulls."""
    res = solve_steady(hand_conveyor, model="cema", params={"ky": 1e308})
    assert res.status == "failed"
    assert res.message.startswith("the steady state is not finite (te_kn")
    assert "models.*" in res.message
    ok = solve_steady(hand_conveyor, model="cema")
    assert ok.status in ("ok", "warning") and math.isfinite(ok.summary["te_kn"])


def test_friction_factor_and_sag_limit_bounds(hand_dict):
    """f above 1 (resistance past the moving weight) and a sag limit below 0.1 % are refused
    naming the field; the bounds themselves are accepted."""
    from beltstudy.engine.conveyor import InputError

    conv = parse_conveyor(hand_dict)
    with pytest.raises(InputError, match=r"^models.din.f_return: a friction factor between 0"):
        solve_steady(conv, model="din", params={"f_return": 1.5})
    assert solve_steady(conv, model="din", params={"f_carry": 1.0}).status in (
        "ok", "warning", "failed")
    with pytest.raises(ValueError, match=r"sag_limit_pct.carry"):
        parse_conveyor({**hand_dict, "sag_limit_pct": {"carry": 0.05, "return": 3.0}})
    parse_conveyor({**hand_dict, "sag_limit_pct": {"carry": 0.1, "return": 3.0}})
