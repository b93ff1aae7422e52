"""Booster drives and a take-up along the return in the transient engine (SPEC 7.1, issue 28
item 2): the booster's pulley slips by the capstan law as a head drive's does, and the running
phase settles onto the steady tensions with a booster and a take-up along the strands.

The hand conveyor (tests/conftest.py): 1000 m rising 50 m, 4 m/s, m'_G = 20 kg/m,
m'_L = 50 kg/m."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
from beltstudy.engine.dynamics.model import with_probes
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict
from tests.engine.conftest import assert_settles_to_statics


def conveyor(booster: dict, takeup: dict, head_share: float = 0.6, head_wrap: float = 200.0):
    d = hand_conveyor_dict(drives=[
        {"position": "head", "wrap_deg": head_wrap, "friction": 0.35, "share": head_share,
         "pulley_diameter_m": 1.0},
        {"wrap_deg": 200, "friction": 0.35, "share": round(1.0 - head_share, 6),
         "pulley_diameter_m": 1.0, **booster}])
    d["takeup"] = takeup
    return parse_conveyor(d)


def test_a_slipping_booster_passes_the_capstan_limit():
    """An open-loop drive force far above the grip of a booster at mid-carry with 90 deg of
    wrap: its pulley slips and passes T_slack (e^(mu_k theta) - 1) to the belt, T_slack its
    outgoing side (1 %), as tests/engine/integration/test_dynamics_drives_brakes.py checks for
    a head drive."""
    conv = conveyor({"position": "carry", "at_m": 500, "wrap_deg": 90, "friction_kinetic": 0.25},
                    {"type": "gravity", "position": "tail", "mass_kg": 3000}, head_share=0.5)
    st = solve_steady(conv, model="din", n_elements=60)
    b = st.loop.drive_elements[1]
    sysm = build_system(conv, Scenario(run_s=30), st, DynamicsOptions(force_start_n=150e3))
    sysm = with_probes(sysm, [b])
    r = simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 6.0)
    ts = r.timeseries
    t_out = r.traces.iloc[:, 1].to_numpy()
    slipping = (ts["v_drive2_m_s"] - ts["v_mean_m_s"] > 0.05).to_numpy()  # shaft runs ahead
    assert slipping.sum() > 10
    capstan = t_out * (math.exp(0.25 * math.radians(90.0)) - 1.0)
    assert_allclose(ts["f_belt2_kn"].to_numpy()[slipping], capstan[slipping], rtol=0.01)
    assert r.summary["drive2_slip_s"] > 1.0


@pytest.mark.parametrize("elements,dt_safety", [("auto", 0.5), (400, 0.5), ("auto", 0.25)])
def test_a_booster_whose_slack_side_cannot_carry_its_share_slips_in_a_start(elements,
                                                                            dt_safety):
    """A booster at 500 m with half of Te on 60 deg of wrap: its steady slip margin
    (e^(mu theta) - 1) T_slack / F is below 1 (statics says so), and the start slips it, named
    by where it sits; the head drive (210 deg, margin above 1.5) holds. The verdict is the same
    at the automatic mesh and twice as fine, and at half the automatic step."""
    conv = conveyor({"position": "carry", "at_m": 500, "wrap_deg": 60},
                    {"type": "gravity", "position": "tail", "mass_kg": 5000}, head_share=0.5,
                    head_wrap=210)
    st = solve_steady(conv, model="din")
    assert st.summary["drive2_slip_margin"] < 1.0 < 1.5 < st.summary["drive1_slip_margin"]
    r = run_one(conv, Scenario(start={"time_s": 60}, run_s=30, elements=elements),
                model="din", options=DynamicsOptions(dt_safety=dt_safety))
    s = r.summary
    assert s["drive2_slip_s"] > 10.0 and s["drive1_slip_s"] == 0.0
    assert "drive 2 (carry at 500 m) slipped on its pulley" in s["message"]


@pytest.mark.parametrize("model,booster,takeup", [
    ("din", {"position": "carry", "at_m": 500},
     {"type": "gravity", "position": "return", "at_m": 800, "mass_kg": "auto"}),
    ("nonlin", {"position": "return", "at_m": 300},
     {"type": "gravity", "position": "tail", "mass_kg": "auto"}),
])
def test_running_tensions_settle_to_statics_with_a_booster(model, booster, takeup):
    """As tests/engine/integration/test_dynamics_physics.py::test_running_tensions_settle_to_
    statics with a booster (0.4 of Te) and a take-up along the strands: after a 60 s start
    and 120 s of running every tension is the steady one within 1 %, no drive slipped, and
    the booster passes its share of the steady Te (1 %)."""
    conv = conveyor(booster, takeup)
    st = solve_steady(conv, model=model, n_elements=80)
    _, res = assert_settles_to_statics(conv, st, start_s=60.0)
    assert res.summary["drive1_slip_s"] == 0.0 and res.summary["drive2_slip_s"] == 0.0
    f2 = res.timeseries["f_drive2_kn"].iloc[-1] * 1e3
    assert f2 == pytest.approx(0.4 * st.te_n, rel=0.01)


@pytest.mark.parametrize("elements", ["auto", 400])
def test_a_remote_followers_force_limit_cycle_is_named_and_a_slower_loop_settles_it(elements):
    """docs/routes.md, *Remote followers and the speed loop*: a booster at mid-carry following
    the head's torque (each half of Te, a 5 t take-up at the tail, a 60 s start, 120 s of
    running). Under the default speed loop the two forces swing in a limit cycle while the mean
    speed holds within 2 %: the run says `not settled while running` with each drive's
    swing, beyond +-25 % of its rated force (SETTLE_FORCE); at 0.5 rad/s they swing by less
    than a fifth of that about their share of the steady Te (1 %) and the run does not say so.
    Alike at the automatic mesh and at 400 elements."""
    from beltstudy.engine.dynamics.simulate import SETTLE_FORCE

    def conv(loop):
        head = {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.5,
                "pulley_diameter_m": 1.0}
        if loop:
            head["speed_loop_rad_s"] = loop
        d = hand_conveyor_dict(drives=[head, {
            "position": "carry", "at_m": 500, "wrap_deg": 200, "friction": 0.35, "share": 0.5,
            "pulley_diameter_m": 1.0}])
        d["takeup"] = {"type": "gravity", "position": "tail", "mass_kg": 5000}
        return parse_conveyor(d)

    def run(loop):
        return run_one(conv(loop), Scenario(start={"time_s": 60}, run_s=120,
                                            elements=elements), model="din")

    fast = run(None)
    msg = fast.summary["message"]
    assert "not settled while running: the mean belt speed holds" in msg
    rated = fast.transient.system.model.drives.rated
    ts = fast.timeseries
    t_cmd = fast.transient.system.stop_command_s
    tail = ((ts["t_s"] > t_cmd - 30.0) & (ts["t_s"] <= t_cmd)).to_numpy()
    for k, where in ((1, "head"), (2, "carry at 500 m")):
        f = ts[f"f_drive{k}_kn"].to_numpy()[tail] * 1e3
        assert 0.5 * (f.max() - f.min()) > SETTLE_FORCE * rated[k - 1]  # a swing indeed
        assert f"the force of drive {k} ({where}) swings between" in msg
    v = ts["v_mean_m_s"].to_numpy()[tail]
    assert v.max() - v.min() < 0.02 * 4.0
    slow = run(0.5)
    assert "not settled" not in slow.summary["message"]
    sysm = slow.transient.system
    st = solve_steady(conv(0.5), model="din", n_elements=sysm.n)
    ts = slow.timeseries
    t_cmd = sysm.stop_command_s
    tail = ((ts["t_s"] > t_cmd - 30.0) & (ts["t_s"] <= t_cmd)).to_numpy()
    for k in (1, 2):
        f = ts[f"f_drive{k}_kn"].to_numpy()[tail] * 1e3
        assert 0.5 * (f.max() - f.min()) < 0.2 * SETTLE_FORCE * rated[k - 1]
        assert f.mean() == pytest.approx(0.5 * st.te_n, rel=0.01)
