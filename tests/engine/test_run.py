"""One run (engine/run.py): the SPEC fields, the time series, a run with each load pattern, bad
input rejected before any transient computing. The ``beltstudy simulate`` command is
tests/service/test_cli_simulate.py."""

from __future__ import annotations

import importlib
import re

import pytest

from beltstudy.engine.conveyor import (
    InputError,
    Scenario,
    load_conveyor,
    load_mapping,
    parse_conveyor,
    parse_scenario,
)
from beltstudy.engine.dynamics.simulate import TIMESERIES_COLUMNS
from beltstudy.engine.results import FIELDS
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS, TRANSIENT_FIELDS, hand_conveyor_dict
from tests.engine.conftest import DIN, hand_conv, hand_drive, two_sections

SLOPE = CONVEYORS / "slope-5pct.yaml"
sim_mod = importlib.import_module("beltstudy.engine.dynamics.simulate")


@pytest.fixture
def no_kernel(monkeypatch):
    """Fail the test if the transient kernel is reached."""
    def boom(*a, **k):
        raise AssertionError("the kernel ran before the input was rejected")

    monkeypatch.setattr(sim_mod, "run_kernel", boom)


def test_run_one_returns_every_spec_field():
    conv = load_conveyor(SLOPE)
    scn = Scenario(elements=60, start={"time_s": 20}, run_s=5,
                   stop={"mode": "controlled", "time_s": 15})
    r = run_one(conv, scn, model="din")
    s = r.summary
    for key in TRANSIENT_FIELDS + ("te_kn", "t1_kn", "t_max_kn", "status", "message",
                                   "elapsed_s", "te_components_kn"):
        assert key in s, key
    assert s["status"] in ("ok", "warning")
    assert tuple(r.timeseries.columns[: len(TIMESERIES_COLUMNS)]) == TIMESERIES_COLUMNS
    assert list(r.surface.columns) == ["t_s", "s_m", "tension_kn", "velocity_m_s"]
    assert {"s_m", "strand", "elevation_m", "tension_kn", "sag_pct", "t_max_dyn_kn",
            "t_min_dyn_kn"} <= set(r.profile.columns)
    assert (r.profile["t_max_dyn_kn"] >= r.profile["t_min_dyn_kn"]).all()
    assert s["wave_loop_time_s"] > 0 and s["stop_wave_ratio"] == pytest.approx(
        s["stop_time_s"] / s["wave_loop_time_s"])
    steady = run_one(conv, scn, model="din", dynamics=False)
    assert steady.timeseries is None and steady.surface is None
    assert "t_max_dyn_kn" not in steady.summary
    assert steady.summary["te_kn"] == pytest.approx(s["te_kn"])


def test_warnings_name_the_limit():
    """A 6 s controlled stop of a belt whose wave loop takes 5 s is faster than 5 wave loops;
    the run says so and is a warning, not a failure."""
    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml")
    scn = Scenario(elements=60, start={"time_s": 20}, run_s=5,
                   stop={"mode": "controlled", "time_s": 6})
    r = run_one(conv, scn, model="din")
    assert r.summary["status"] == "warning"
    assert "faster than 5 wave loop times" in r.summary["message"]


def test_a_belt_that_never_reached_speed_is_not_told_its_stop_was_fast():
    """The hand conveyor's drive capped at 0.7 x its rated force (0.7 x 1.25 Te = 0.875 Te)
    cannot move the belt against its running resistance Te: the run says it never reached
    design speed, and does not judge a stop against the 5-wave-loop rule, which is about
    stopping a belt from design speed. Its mean speed at the stop command is below 1 % of
    design speed, so no stop *fell* below it (SPEC 4): stop time, distance and wave ratio are
    null, not the first step after the command."""
    d = hand_conveyor_dict()
    d["drives"][0]["torque_limit"] = 0.7
    r = run_one(parse_conveyor(d), Scenario(elements=40, start={"time_s": 10}, run_s=5,
                                            stop={"mode": "coast"}), model="din")
    s, ts = r.summary, r.timeseries
    v_cmd = float(ts.loc[ts["t_s"] <= 15.0 + 1e-9, "v_mean_m_s"].iloc[-1])
    assert abs(v_cmd) < 0.01 * 4.0  # 0.875 Te cannot move it
    assert s["start_time_s"] is None
    assert s["stop_time_s"] is None and s["stop_distance_m"] is None
    assert s["stop_wave_ratio"] is None
    assert "the belt never reached 99 % of design speed" in s["message"]
    assert "faster than 5 wave loop times" not in s["message"]


def test_a_belt_held_below_speed_by_its_fluid_couplings_has_its_fast_stop_judged():
    """A dol drive behind a constant-fill fluid coupling rated at the running force runs the
    coupling at its rated slip, 3 % (engine/dynamics/laws.py): the belt settles near 97 % of
    design speed and never reaches 99 %. It stops from that running speed, so a stop faster than
    5 wave loop times is still a high-stress stop and is said; the short-of-speed words give the
    speed at the stop command (the time series' mean speed there, to the digits shown) and name
    the couplings' slip."""
    d = hand_conveyor_dict()
    te_kw = 48.03 * 4.0  # the hand conveyor's Te x v (DIN): the coupling at its rated torque
    d["drives"][0].update(control="dol", coupling="fluid", inertia_kg_m2=100,
                          rated_power_kw=te_kw)
    d["brakes"] = [{"position": "head", "force_kn": 30.0, "delay_s": 0.5}]
    r = run_one(parse_conveyor(d), Scenario(elements=40, start={"time_s": 20}, run_s=20,
                                            stop={"mode": "brake"}), model="din")
    s, ts = r.summary, r.timeseries
    m = re.search(r"at the stop command at t = ([0-9.]+) s", s["message"])
    assert m and float(m.group(1)) >= 40.0  # the start and the run before it
    v_cmd = float(ts.loc[ts["t_s"] <= float(m.group(1)) + 0.05, "v_mean_m_s"].iloc[-1])
    assert s["start_time_s"] is None
    assert 0.95 < v_cmd / 4.0 < 0.985  # 1.5-4 % coupling slip with the motor's own
    assert s["stop_wave_ratio"] < 5.0
    assert "faster than 5 wave loop times" in s["message"]
    assert "the belt never reached 99 % of design speed" in s["message"]
    assert f"{100.0 * v_cmd / 4.0:.1f} % of design speed" in s["message"]
    assert "fluid couplings run at their slip" in s["message"]


def test_a_brake_stop_of_a_belt_that_coasts_within_five_loops_is_not_told_to_brake_less():
    """The hand conveyor lifted 150 m coasts to rest with its brakes off in M v / Te, within 5
    wave loop times (the coast run itself shows it): no brake force or stop time makes its brake
    stop slower, so the fast-stop words say so, name that coast time (the hand M v / Te within
    5 %: M = 80 kg/m carry + 23 kg/m return over 1 km, the shaft reduced to the rim a few per
    cent more) and offer no stop.time_s for the brakes."""
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 150}])
    d["brakes"] = [{"position": "head", "force_kn": 20.0, "delay_s": 0.5}]
    conv = parse_conveyor(d)
    base = dict(elements=40, start={"time_s": 20}, run_s=10)
    coast = run_one(conv, Scenario(**base, stop={"mode": "coast"}), model="din").summary
    assert coast["stop_wave_ratio"] < 5.0
    s = run_one(conv, Scenario(**base, stop={"mode": "brake", "time_s": 30}),
                model="din").summary
    msg = s["message"]
    assert s["stop_wave_ratio"] < 5.0 and "faster than 5 wave loop times" in msg
    assert "no brake setting makes it slower" in msg
    assert "less brake force would be slower" not in msg
    m = re.search(r"coasts to rest in about ([0-9.]+) s", msg)
    hand_s = 103_000.0 * 4.0 / (s["te_kn"] * 1e3)
    assert m and abs(float(m.group(1)) - hand_s) <= 0.05 * hand_s + 0.05
    assert float(m.group(1)) < 5.0 * s["wave_loop_time_s"]


def test_negative_time_rejected_naming_the_field(no_kernel):
    with pytest.raises(InputError, match=r"scenario\.run_s"):
        parse_scenario({"run_s": -5}, prefix="scenario.")
    with pytest.raises(InputError, match=r"scenario\.start\.time_s"):
        parse_scenario({"start": {"time_s": -1}}, prefix="scenario.")
    # a scenario built without validation is still checked before any computing
    bad = Scenario.model_construct(**{**Scenario().__dict__, "run_s": -5.0})
    with pytest.raises(InputError, match=r"scenario\.run_s"):
        run_one(load_conveyor(SLOPE), bad, model="din")


def test_stop_mode_the_conveyor_cannot_do(no_kernel):
    conv = load_conveyor(SLOPE)  # no brakes
    with pytest.raises(InputError, match=r"scenario\.stop\.mode: 'brake' needs brakes"):
        run_one(conv, Scenario(stop={"mode": "brake", "time_s": 20}), model="din")
    with pytest.raises(InputError, match=r"scenario\.start\.control: 'torque'"):
        run_one(conv, Scenario(start={"control": "torque"}, formulation="support"),
                model="din")
    data = load_mapping(SLOPE)
    data["brakes"] = [{"position": "head", "force_kn": "auto", "delay_s": 3.0}]
    with pytest.raises(InputError, match=r"scenario\.stop\.time_s"):
        run_one(parse_conveyor(data), Scenario(stop={"mode": "brake", "time_s": 2}),
                model="din")


def test_cycles_and_samples_past_the_budget_are_refused_naming_the_field(no_kernel):
    """A cycle or a sample spacing asking for more than a million time-series samples is
    refused before any computing, naming the time that made it (not the mesh or the step)."""
    from beltstudy.engine.conveyor import parse_scenario

    conv = load_conveyor(SLOPE)
    # the times themselves are bounded at an hour (engine 0.6.26), before any cycle is built
    with pytest.raises(InputError, match=r"^scenario\.run_s: Input should be less than or "
                                         r"equal to 3600 \(got 1e\+308\)$"):
        parse_scenario({"run_s": 1e308}, prefix="scenario.")
    with pytest.raises(InputError, match=r"^scenario\.start\.time_s: Input should be less "
                                         r"than or equal to 3600 \(got 1000000000\)$"):
        parse_scenario({"start": {"time_s": 1e9}}, prefix="scenario.")
    with pytest.raises(InputError, match=r"^scenario\.record_dt_s: 1e-09 s over a cycle of "
                                         r"120 s .* at least 0\.00012 s"):
        run_one(conv, Scenario(record_dt_s=1e-9), model="din")


def test_samples_finer_than_the_step_are_one_per_step():
    """record_dt_s below the step: the kernel records once a step (the arrays are sized for
    that, not for the spacing asked), each sample at its own time."""
    conv = load_conveyor(SLOPE)
    r = run_one(conv, Scenario(elements=60, record_dt_s=1e-5, start={"time_s": 4}, run_s=0,
                               stop={"mode": "controlled", "time_s": 2}), model="din")
    assert r.summary["status"] != "failed"
    t = r.timeseries["t_s"].to_numpy()
    dt = r.summary["dt_used_s"]
    gaps = t[1:-1] - t[:-2]
    assert gaps.min() == pytest.approx(dt, rel=1e-9) and gaps.max() == pytest.approx(dt, rel=1e-9)


def test_fixed_step_above_the_limit(no_kernel):
    conv = load_conveyor(SLOPE)
    with pytest.raises(InputError, match=r"scenario\.dt_s: 0\.5 s is above the stability "
                                         r"limit [0-9.e-]+ s"):
        run_one(conv, Scenario(elements=60, dt_s=0.5), model="din")


def test_fixed_step_below_the_limit_runs():
    conv = load_conveyor(SLOPE)
    r = run_one(conv, Scenario(elements=60, dt_s=0.004, start={"time_s": 10}, run_s=2,
                               stop={"mode": "controlled", "time_s": 8}), model="din")
    assert r.summary["dt_used_s"] == 0.004
    assert r.summary["status"] != "failed"
    # elements_used counts the loop's elements as docs/results.md says: the scenario's 60
    # belt elements and one per pulley (head drive and tail here)
    from beltstudy.engine.loop import build_loop
    pulleys = len(build_loop(conv, n_elements=60).pulleys)
    assert pulleys == 2 and r.summary["elements_used"] == 60 + pulleys
    assert "and one per pulley" in FIELDS["elements_used"].meaning


@pytest.mark.parametrize("load", ["inclines", "declines", [0.5, 1.0], 1.2])
def test_a_transient_run_with_each_pattern(load):
    conv = two_sections()
    scn = Scenario(load=load, elements=40, start={"time_s": 15}, run_s=5,
                   stop={"mode": "coast"})
    r = run_one(conv, scn, model="din", params=DIN)
    assert r.summary["status"] in ("ok", "warning"), r.summary["message"]
    assert r.summary["t_max_dyn_kn"] >= r.summary["t_max_kn"] * 0.99
    assert ("surge" in r.summary["message"]) is (load == 1.2)


def test_controlled_stop_with_dol_drives_is_refused():
    conv = hand_conv(drives=[hand_drive(control="dol")])
    with pytest.raises(InputError, match="scenario.stop.mode"):
        run_one(conv, Scenario(stop={"mode": "controlled", "time_s": 20}), model="din")
