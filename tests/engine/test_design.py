"""Auto sizes and what set them (engine/design.py, engine/statics.py), by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, load_conveyor, parse_conveyor
from beltstudy.engine.design import RATED_POWER_FACTOR, auto_sizes, moving_mass_kg
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.loop import CARRY, G
from beltstudy.engine.statics import TAKEUP_CONSTRAINTS, solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict
from tests.engine.test_statics import startup_t2_by_hand


def _euler(wrap_deg=200, mu=0.35):
    return math.exp(mu * math.radians(wrap_deg))


def test_start_up_slip_governs_the_hand_conveyor():
    res = solve_steady(parse_conveyor(hand_conveyor_dict()), model="din")
    assert res.summary["takeup_governed_by"] == "slip_start"
    assert_allclose(res.summary["t2_kn"] * 1e3, startup_t2_by_hand(res.te_n), rtol=1e-6)


def test_sag_at_rest_governs_and_the_switch_turns_it_off():
    """Carry sag limit 0.2 %: held at rest the counterweight's m g / 2 is the sag minimum
    g (m'_G + m'_L) cos(a) S / (8 h/S) (governs: ``sag_at_rest``). With the rule off, the
    lowest running carry tension (the low end of the first carry span) is that minimum instead
    (``sag_running``), and the counterweight is lighter."""
    d = hand_conveyor_dict(sag_limit_pct={"carry": 0.2, "return": 5.0})
    cos_a = math.sqrt(1.0 - (50.0 / 1000.0) ** 2)
    t_min_sag = G * (20 + 50) * cos_a * 1.25 / (8 * 0.002)
    rest = solve_steady(parse_conveyor(d), model="din")
    assert rest.summary["takeup_governed_by"] == "sag_at_rest"
    assert_allclose(rest.summary["takeup_mass_kg"] * G / 2, t_min_sag, rtol=1e-6)

    d["takeup"] = {**d["takeup"], "sag_at_rest": False}
    run = solve_steady(parse_conveyor(d), model="din")
    assert run.summary["takeup_governed_by"] == "sag_running"
    T = run.tension_n
    low = np.minimum(np.roll(T, 1), T)
    carry = run.loop.strand == CARRY
    assert_allclose(low[carry].min(), t_min_sag, rtol=1e-6)
    assert run.summary["takeup_mass_kg"] < rest.summary["takeup_mass_kg"]
    assert not run.warnings


def test_a_given_takeup_is_reported_as_given():
    d = hand_conveyor_dict(takeup={"type": "gravity", "position": "tail", "mass_kg": 9000})
    s = solve_steady(parse_conveyor(d), model="din").summary
    assert s["takeup_governed_by"] == "given" and s["takeup_mass_kg"] == pytest.approx(9000)
    assert set(TAKEUP_CONSTRAINTS) >= {"slip_start", "slip_running", "sag_running",
                                       "sag_at_rest"}


def test_rated_power_by_hand():
    """1.25 x share x Te x v for a lifting conveyor without a given rated power."""
    conv = parse_conveyor(hand_conveyor_dict())
    scn = Scenario()
    sizes = auto_sizes(conv, scn, model="din")
    st = solve_steady(conv, model="din")
    assert sizes["drive_rated_power_kw"] == pytest.approx(
        [RATED_POWER_FACTOR * 1.0 * st.te_n * 4.0 / 1e3], rel=1e-9)
    assert sizes["drive_rated_power_governed_by"] == ["peripheral_force"]
    assert sizes["takeup_governed_by"] == "slip_start"
    assert sizes["takeup_mass_kg"] == pytest.approx(st.summary["takeup_mass_kg"], rel=1e-12)


def test_brake_sized_by_the_stop_time_or_held_by_the_holding_floor():
    """Rigid body: M v_1 = Te t_b + F_b (t_b - r / 2), t_b = t_stop - t_delay, v_1 = v - Te
    t_delay / M, r the ramp (1 s by default); at least 1.2 x the net pull of the loaded belt.
    A coast run uses no stop time: holding size."""
    d = hand_conveyor_dict(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])
    conv = parse_conveyor(d)
    st = solve_steady(conv, model="din")
    m = moving_mass_kg(conv, st)
    v1 = 4.0 - st.te_n * 0.5 / m
    pull = G * 50.0 * 50.0  # m'_L g H: the loaded lift
    short = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 3.0}), model="din")
    f_stop = (m * v1 - st.te_n * 2.5) / (2.5 - 0.5 * 1.0)
    assert f_stop > 1.2 * pull
    assert short["brake_force_kn"] == pytest.approx([f_stop / 1e3], rel=1e-9)
    assert short["brake_governed_by"] == ["stop_time"]
    long = auto_sizes(conv, Scenario(stop={"mode": "brake", "time_s": 60.0}), model="din")
    assert long["brake_force_kn"] == pytest.approx([1.2 * pull / 1e3], rel=1e-9)
    assert long["brake_governed_by"] == ["holding"]
    coast = auto_sizes(conv, Scenario(stop={"mode": "coast", "time_s": 3.0}), model="din")
    assert coast["brake_force_kn"] == long["brake_force_kn"]


@pytest.mark.parametrize("name", ["downhill-regen.yaml", "fabric-1km.yaml"])
def test_auto_sizes_are_what_the_transient_model_uses(name):
    """The design module and the transient model agree on the rated force and brake force
    (the study service substitutes the design module's numbers)."""
    data = load_conveyor(CONVEYORS / name).model_dump(by_alias=True)
    for drive in data["drives"]:
        drive["rated_power_kw"] = None
    data["brakes"] = [{"position": "head", "force_kn": "auto", "delay_s": 0.5}]
    conv = parse_conveyor(data)
    scn = Scenario(elements=60, stop={"mode": "brake", "time_s": 15.0})
    st = solve_steady(conv, model="din", n_elements=60)
    sizes = auto_sizes(conv, scn, model="din", steady=st)
    sys = build_system(conv, scn, st)
    assert_allclose(sys.model.control.m_tot, moving_mass_kg(conv, st), rtol=1e-12)
    assert_allclose(np.sum(sys.model.drives.rated) * conv.speed_m_s / 1e3,
                    sum(sizes["drive_rated_power_kw"]), rtol=1e-6)
    assert_allclose(sys.model.brakes.force / 1e3, sizes["brake_force_kn"], rtol=1e-9)
