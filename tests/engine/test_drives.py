"""Drive checks (beltstudy.engine.drives, SPEC 7.4): the motor power a drive needs against
its rating by hand, the steady warning of a drive short of power (engine and ``beltstudy
static``), and the transient load (time above the rated force, RMS force) of a drive held at a
known force."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from beltstudy.engine.conveyor import DRIVE_EFFICIENCY, load_mapping, parse_conveyor
from beltstudy.engine.drives import (
    OVERLOAD_S_MAX,
    power_required_kw,
    rated_power_kw,
    steady_checks,
    transient_checks,
)
from beltstudy.engine.dynamics.records import DRIVE_RESULT
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS, hand_conveyor_dict


def test_required_power_motoring_and_regenerating_by_hand():
    """DIN 22101 / CEMA (docs/drives.md): P_M = F v / eta driving, |F v| eta regenerating.
    Te = 240 kN, share 0.5, v = 4.5 m/s, eta = 0.95: 0.5 x 240 x 4.5 / 0.95 = 568.42 kW;
    a drive holding back 100 kN at 4 m/s passes 400 kW x 0.95 = 380 kW to its motor."""
    assert power_required_kw(0.5 * 240e3, 4.5, 0.95) == pytest.approx(568.421052631, rel=1e-9)
    assert power_required_kw(-100e3, 4.0, 0.95) == pytest.approx(380.0, rel=1e-12)
    assert power_required_kw(0.0, 4.0, 0.95) == 0.0


def test_steady_checks_utilisation_and_shortfall_by_hand():
    """Two head drives sharing Te = 240 kN at 4.5 m/s, efficiencies 0.95 and 0.9: need
    0.5 x 240 x 4.5 / 0.95 = 568.42 kW and 0.5 x 240 x 4.5 / 0.9 = 600 kW; rated 700 and
    500 kW: utilisation 0.8120 and 1.2, the second short by 100 kW (and only it warns)."""
    d = hand_conveyor_dict(drives=[
        {"position": "head", "share": 0.5, "rated_power_kw": 700},
        {"position": "head", "share": 0.5, "rated_power_kw": 500, "efficiency": 0.9}])
    conv = parse_conveyor(d)
    fields, warnings = steady_checks(conv, [120e3, 120e3], 4.5, 240e3, [700.0, 500.0])
    assert fields["drive1_power_required_kw"] == pytest.approx(568.421052631, rel=1e-9)
    assert fields["drive2_power_required_kw"] == pytest.approx(600.0, rel=1e-12)
    assert fields["drive1_utilisation"] == pytest.approx(568.421052631 / 700.0, rel=1e-9)
    assert fields["drive2_utilisation"] == pytest.approx(1.2, rel=1e-12)
    assert len(warnings) == 1
    assert warnings[0].startswith("drive 2 (head) needs 600 kW")
    assert "rated 500 kW: short by 100 kW" in warnings[0]


def test_the_motor_advised_for_a_drive_short_of_power_is_enough():
    """A drive pulling 189.677 kN at 5 m/s through 0.95 needs 189.677 x 5 / 0.95 = 998.3 kW.
    Rounded to the nearest the advice was "a motor of at least 998 kW", and a 998 kW motor
    is still short (utilisation 998.3 / 998 = 1.0003, warned again "short by 0 kW"): the
    advice is the next whole kilowatt, 999 kW, which passes. A shortfall under half a kilowatt
    is said in two figures (0.3 kW), not as 0."""
    conv = parse_conveyor(hand_conveyor_dict(drives=[{"position": "head",
                                                      "rated_power_kw": 900}]))
    force, v = 998.3 * 0.95 * 1e3 / 5.0, 5.0
    fields, (w,) = steady_checks(conv, [force], v, force, [900.0])
    assert fields["drive1_power_required_kw"] == pytest.approx(998.3, rel=1e-12)
    assert "a motor of at least 999 kW (drives.0.rated_power_kw)" in w
    _, again = steady_checks(conv, [force], v, force, [998.0])
    assert "short by 0.3 kW" in again[0] and "at least 999 kW" in again[0]
    assert steady_checks(conv, [force], v, force, [999.0])[1] == []
    # a need of a whole kilowatt is advised as that kilowatt
    whole = 1000.0 * 0.95 * 1e3 / 5.0
    (w,) = steady_checks(conv, [whole], v, whole, [900.0])[1]
    assert "a motor of at least 1000 kW" in w
    assert steady_checks(conv, [whole], v, whole, [1000.0])[1] == []


def test_a_regenerating_drive_short_of_power_holds_back():
    """A drive holding back 120 kN at 4.5 m/s passes 120 x 4.5 x 0.95 = 513 kW to its motor
    (the losses come off the belt's power); rated 400 kW it is short by 113 kW."""
    conv = parse_conveyor(hand_conveyor_dict(drives=[{"position": "head",
                                                      "rated_power_kw": 400}]))
    fields, (w,) = steady_checks(conv, [-120e3], 4.5, -120e3, [400.0])
    assert fields["drive1_power_required_kw"] == pytest.approx(513.0, rel=1e-12)
    assert w.startswith("drive 1 (head) holds back 513 kW at 4.5 m/s")
    assert "regenerating: x efficiency 0.95" in w and "short by 113 kW" in w


def test_default_efficiency_is_the_documented_one():
    conv = parse_conveyor(hand_conveyor_dict())
    assert conv.drives[0].efficiency == DRIVE_EFFICIENCY == 0.95


def test_solve_steady_warns_a_drive_short_of_power():
    """The hand conveyor (one head drive, share 1) rated at 100 kW: the steady solve reports
    P_M = Te v / eta (Te from the same solve) and warns with the shortfall in kW; an auto
    rated power (1.25 x the motor power, Te v / eta) leaves the drive at 1 / 1.25 = 0.8."""
    low = parse_conveyor(hand_conveyor_dict(drives=[{"position": "head",
                                                     "rated_power_kw": 100}]))
    st = solve_steady(low, model="din", n_elements=100)
    need = st.te_n * 4.0 / 0.95 / 1e3
    assert need > 100.0  # the case is short of power
    assert st.summary["drive1_power_required_kw"] == pytest.approx(need, rel=1e-9)
    assert st.summary["drive1_utilisation"] == pytest.approx(need / 100.0, rel=1e-9)
    assert st.status == "warning"
    assert f"drive 1 (head) needs {need:.0f} kW" in st.message
    assert f"rated 100 kW: short by {need - 100:.0f} kW" in st.message
    auto = solve_steady(parse_conveyor(hand_conveyor_dict()), model="din", n_elements=100)
    assert auto.summary["drive1_utilisation"] == pytest.approx(1.0 / 1.25, rel=1e-9)
    assert "short by" not in auto.message


@pytest.mark.parametrize("eta", [0.75, 0.5])
def test_an_auto_motor_behind_a_lossy_drive_train_passes_its_own_check(eta):
    """The auto size is 1.25 x the motor power the steady state needs, the power at the pulley
    through the drive train: Te v / eta. Sized on Te v alone, a train of efficiency 0.75 left
    the engine's own motor at 1 / (1.25 x 0.75) = 1.07 of its rating, warned short of power."""
    d = hand_conveyor_dict(drives=[{"position": "head", "wrap_deg": 200, "friction": 0.35,
                                    "share": 1.0, "pulley_diameter_m": 1.0,
                                    "efficiency": eta}])
    conv = parse_conveyor(d)
    st = solve_steady(conv, model="din", n_elements=100)
    by_hand_kw = 1.25 * st.te_n * 4.0 / eta / 1e3
    rated, why = rated_power_kw(conv, st.te_n, float(np.sum(st.resistance_n)))
    assert rated[0] == pytest.approx(by_hand_kw, rel=1e-9) and why == ["peripheral_force"]
    assert st.summary["drive1_power_required_kw"] == pytest.approx(by_hand_kw / 1.25, rel=1e-9)
    assert st.summary["drive1_utilisation"] == pytest.approx(0.8, rel=1e-9)
    assert "short by" not in st.message


def test_an_auto_motor_of_a_regenerating_belt_takes_in_its_power_times_eta():
    """A loaded decline (1 km falling 80 m): Te < 0, the motor takes in |Te v| eta; the empty
    belt's running resistance R v / eta is the other duty. The auto size is 1.25 x the larger,
    and names it."""
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": -80}])
    conv = parse_conveyor(d)
    st = solve_steady(conv, model="din", n_elements=100)
    assert st.te_n < 0.0
    regen = abs(st.te_n) * 4.0 * 0.95 / 1e3
    drive = float(np.sum(st.resistance_n)) * 4.0 / 0.95 / 1e3
    rated, why = rated_power_kw(conv, st.te_n, float(np.sum(st.resistance_n)))
    assert rated[0] == pytest.approx(1.25 * max(regen, drive), rel=1e-9)
    assert why == ["peripheral_force" if regen >= drive else "running_resistance"]


def test_a_vfd_force_limit_below_the_running_force_is_a_steady_warning():
    """The hand conveyor with an auto rating, 1.25 Te v / eta (eta 0.95): its rated force
    P_N / v is 1.25 Te / 0.95, so a torque_limit of 0.5 caps the drive at 0.658 Te, short of
    the running force Te (the belt never reaches design speed), and 0.95 / 1.25 = 0.76 is the
    least limit that holds it, which is named and then warns no more."""
    d = hand_conveyor_dict()
    d["drives"][0]["torque_limit"] = 0.5
    st = solve_steady(parse_conveyor(d), model="din", n_elements=100)
    cap_kn = 0.5 * 1.25 * st.te_n / 0.95 / 1e3
    assert st.status == "warning"
    assert (f"drive 1 (head) force limit {cap_kn:.1f} kN (torque_limit 0.5 x rated"
            in st.message)
    assert f"below its running force {st.te_n / 1e3:.1f} kN" in st.message
    assert "a torque_limit of at least 0.76 (drives.0.torque_limit)" in st.message
    d["drives"][0]["torque_limit"] = 0.76
    ok = solve_steady(parse_conveyor(d), model="din", n_elements=100)
    assert "force limit" not in ok.message


def test_static_cli_warns_the_drive_and_the_shortfall(tmp_path):
    """``beltstudy static`` of slope-5pct with its drive rated at 500 kW (the din model needs
    about 1 000 kW): status warning, the message names drive 1 (head) and the shortfall in
    kW, which is the JSON's required power less the rating."""
    data = load_mapping(CONVEYORS / "slope-5pct.yaml")
    data["drives"] = [{**data["drives"][0], "rated_power_kw": 500}]
    path = tmp_path / "short.json"
    path.write_text(json.dumps(data))
    p = subprocess.run([sys.executable, "-m", "beltstudy.service.cli", "static", str(path),
                        "--model", "din", "--json"], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    need = out["drive1_power_required_kw"]
    assert need == pytest.approx(out["power_kw"] / 0.95, rel=1e-9)  # share 1: Te v / eta
    assert out["drive1_utilisation"] == pytest.approx(need / 500.0, rel=1e-9)
    assert out["status"] == "warning"
    assert f"drive 1 (head) needs {need:.0f} kW" in out["message"]
    assert f"short by {need - 500.0:.0f} kW" in out["message"]


def _drive_result(**values) -> np.ndarray:
    drv = np.zeros(1, dtype=DRIVE_RESULT)
    for k, v in values.items():
        drv[0][k] = v
    return drv


def test_transient_checks_rms_of_a_constant_force_and_the_overload_warning():
    """A drive held at 30 kN for 20 s (f2_int = 30e3^2 x 20): RMS = 30 kN; rated 24 kN, at
    its limit (1.25 x rated = 30 kN) for 20 s: 25 % over its rating, and a start time that
    keeps the force within the rating from the rigid-body estimate t (F_max - F_run) /
    (F_rated - F_run) = 10 x (30 - 12) / (24 - 12) = 15 s."""
    drv = _drive_result(fmax=30e3, over_s=20.0, lim_s=20.0, f2_int=30e3**2 * 20.0, rms_s=20.0)
    fields, warnings = transient_checks(["drive 1 (head)"], drv, [24e3], [30e3], [True], 4.0,
                                        10.0, running_n=[12e3])
    assert fields["drive1_force_rms_kn"] == pytest.approx(30.0, rel=1e-12)
    assert fields["drive1_overload_s"] == 20.0
    (w,) = warnings
    assert w.startswith("drive 1 (head) was above its rated force (24 kN) for 20.0 s")
    assert "at most 25 % over its rating" in w and "at its torque limit (30 kN) for 20.0 s" in w
    assert "about 15 s keeps the force within the rating" in w
    # 30 kN x 4 m/s, a lower bound only: the force was held at the torque limit
    assert "a larger motor (more than 120 kW: its force was held at its torque limit" in w
    assert "at least 120 kW keeps it within" not in w
    assert "RMS force over the cycle, 30 kN, is above the rating" in w


def test_a_few_steps_at_the_limit_are_said_in_their_own_figures():
    """A drive at its torque limit for 0.042 s of a 20 s overload was said to be there 'for
    0.0 s'; below 0.1 s the time is given to two figures."""
    drv = _drive_result(fmax=30e3, over_s=20.0, lim_s=0.042, f2_int=30e3**2 * 20.0,
                        rms_s=20.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [30e3], [True], 4.0, 10.0,
                               running_n=[12e3])
    assert "at its torque limit (30 kN) for 0.042 s" in w
    assert "for 0.0 s" not in w
    drv = _drive_result(fmax=30e3, over_s=0.5, lim_s=0.5, f2_int=1.0, rms_s=20.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [30e3], [True], 4.0, 10.0,
                               running_n=[12e3])
    assert "for 0.5 s of the cycle" in w and "at its torque limit (30 kN) for 0.5 s" in w


@pytest.mark.parametrize("running_kn", [121.0, -121.0])
def test_a_drive_held_at_its_limit_below_its_running_force_is_not_offered_that_limit(
        running_kn):
    """A drive rated 300 kW at 4 m/s (75 kN) with a torque limit of 1.5 x 75 = 112.5 kN, held
    at that limit for 64 s, on a belt whose running force is 121 kN (motoring, or holding a
    decline back): the motor it needs is more than 121 x 4 = 484 kW, not the 112.5 x 4 = 450
    kW of the capped force, and the run cannot say that any size keeps the force within."""
    drv = _drive_result(fmax=112.5e3, fmax_t=6.1, over_s=71.5, lim_s=64.3,
                        f2_int=111.4e3**2 * 70.0, rms_s=70.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [75e3], [112.5e3], [True], 4.0, 30.0,
                               running_n=[running_kn * 1e3])
    assert "more than 484 kW" in w, w
    assert "450 kW" not in w and "keeps it within" not in w


def test_the_start_estimate_reads_the_rigid_body_acceleration_force():
    """With the drive's share of the rigid-body force at the start's peak acceleration given
    (18 kN at a 10 s start; running 12 kN, rated 24 kN): the start that keeps the force
    within the rating is 10 x 18 / (24 - 12) = 15 s whatever force the run reached (here a
    40 kN peak at the hand-over from rest, which the old estimate would have read as 23 s).
    An acceleration force within what the rating leaves (9 kN against 12 kN): the force above
    the rating is the belt's swing about the rigid body, and the start time offered scales the
    run's own peak above its running force as 1 / t: 10 x (40 - 12) / (24 - 12) = 23.3 s, so
    24 s, with the hand-over from rest named as the case it does not cover."""
    drv = _drive_result(fmax=40e3, fmax_t=2.1, over_s=20.0, f2_int=20e3**2 * 60.0,
                        rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], start_accel_n=[18e3])
    assert "a longer start (start.time_s, now 10 s; about 15 s keeps the force within" in w
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], start_accel_n=[9e3])
    assert ("a longer start (start.time_s, now 10 s; about 24 s with the run's own peak above "
            "its running force (28 kN) scaled as 1 / t" in w), w
    assert "the start's rigid-body acceleration (9 kN on this drive) keeps within" in w
    assert "unless the peak is the hand-over from rest" in w


def test_the_start_estimate_is_rounded_up_past_the_start_already_run():
    """A 10 s start whose rigid-body acceleration force is 12.03 kN on a drive rated 24 kN and
    running at 12 kN: the start that keeps the force within the rating is 10 x 12.03 / (24 -
    12) = 10.025 s. Rounded to the nearest it was advised as 'about 10 s', the start already
    run (a 5 km flat belt at start.time_s 177 s was told 'now 177 s; about 177 s keeps the
    force within the rating'): the advice is the whole second above, 11 s, and 11 s leaves
    the rigid-body force within what the rating leaves (10 x 12.03 / 11 = 10.94 kN <= 12 kN).
    The same for a controlled stop: 20 s at 36.09 kN deceleration force, rated 24 kN,
    running 12 kN: 20 x 36.09 / 36 = 20.05 s, advised as 21 s, not 20 s."""
    drv = _drive_result(fmax=26e3, fmax_t=5.0, over_s=20.0, f2_int=13e3**2 * 60.0,
                        rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], start_accel_n=[12.03e3])
    assert "a longer start (start.time_s, now 10 s; about 11 s keeps the force within" in w, w
    assert 10.0 * 12.03e3 / 11.0 <= 24e3 - 12e3
    drv = _drive_result(fmax=26e3, fmax_t=50.0, over_s=20.0, over_stop_s=20.0,
                        f2_int=13e3**2 * 60.0, rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], stop_s=20.0, stop_accel_n=[36.09e3])
    assert "a longer stop (stop.time_s, now 20 s; about 21 s keeps the force within" in w, w


def test_an_overload_from_the_swing_offers_a_longer_start_and_the_larger_motor():
    """With the start's rigid-body acceleration force within what the rating leaves (9 kN
    against 24 - 12 kN), the force above the rating is the belt's swing about the rigid body,
    which the start excites: a 6 km overland over its rating at a 156 s start was within it
    at 250 s, though its words said a longer start would not remove it. The longer start is
    offered from the run's own peak, 10 x (26 - 12) / (24 - 12) = 11.7 s, so 12 s, beside the
    larger motor, each in its own brackets."""
    drv = _drive_result(fmax=26e3, fmax_t=5.0, over_s=20.0, f2_int=13e3**2 * 60.0,
                        rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], start_accel_n=[9e3])
    assert "a longer start (start.time_s, now 10 s; about 12 s with the run's own peak" in w, w
    assert w.endswith("rerun to check) or a larger motor (at least 104 kW keeps it within) "
                      "would avoid it"), w
    assert "would not remove" not in w


@pytest.mark.parametrize("vfd", [True, False])
def test_an_overload_while_running_offers_no_start_as_its_cure(vfd):
    """A drive whose running force (28 kN) is itself above its rating (24 kN) is overloaded
    whatever the start: the warning names the running force and offers the larger motor or
    more drives, neither a longer start nor a softer one."""
    drv = _drive_result(fmax=30e3, over_s=80.0, f2_int=28e3**2 * 80.0, rms_s=80.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [vfd], 4.0, 10.0,
                               running_n=[28e3])
    assert "its running force, 28 kN, is itself above the rating: no start avoids it" in w
    assert "at least 120 kW" in w
    assert "longer start" not in w and "softer start" not in w


@pytest.mark.parametrize("coupling, softer", [
    (None, "a fluid coupling, a vfd"), ("none", "a fluid coupling, a vfd"),
    ("fluid", "a fill-controlled coupling (coupling: fluid_fill_controlled), a vfd"),
    ("fluid_fill_controlled", "a slower coupling fill (a longer coupling_fill_s), a vfd")])
def test_a_dol_overload_offers_the_coupling_it_does_not_have(coupling, softer):
    """A dol drive over its rating in the start (running 20 kN within its 24 kN): the softer
    start offered is the next step from the coupling it has, never the one already fitted."""
    drv = _drive_result(fmax=30e3, over_s=80.0, f2_int=20e3**2 * 80.0, rms_s=80.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [False], 4.0, 10.0,
                               running_n=[20e3],
                               coupling=None if coupling is None else [coupling])
    assert f"; a softer start ({softer}) or a larger motor" in w, w
    assert w.endswith("would avoid it") and "start.time_s" not in w


def test_a_dol_overload_is_not_told_a_larger_motor_keeps_it_within():
    """A dol drive rated 24 kN (96 kW at 4 m/s) peaking at 30 kN in the start, 25 % over for
    20 s. It was told 'a larger motor (at least 120 kW keeps it within)'; a dol motor's start
    force is its torque curve times its rating (an EP1000/5 belt at 200 kW peaked at 89.9 kN,
    57 % over 57.1 kN; at the 315 kW offered, 141.6 kN, 57 % over 90 kN, and it slipped and
    ran 117 % of design speed). The larger motor now only shortens the time over its rating,
    not the 25 % over it; the softer start comes first."""
    drv = _drive_result(fmax=30e3, over_s=20.0, f2_int=20e3**2 * 80.0, rms_s=80.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [False], 4.0, 10.0,
                               running_n=[20e3], coupling=["fluid"])
    assert "at most 25 % over its rating" in w
    assert "keeps it within" not in w and "120 kW" not in w, w
    assert ("a softer start (a fill-controlled coupling (coupling: fluid_fill_controlled), a "
            "vfd) or a larger motor, which shortens the time over its rating but not the 25 % "
            "over it") in w, w


def test_an_overload_in_the_stop_offers_a_longer_stop_not_a_longer_start():
    """A regenerating drive (running force -18 kN, rated 24 kN) braking the belt in a 20 s
    controlled stop, 16 of its 20 s above the rating after the stop command, its peak (30 kN,
    capped by its pulley's grip) at 95.5 s: the warning says when (the split and the peak's
    time) and offers a longer stop, by the rigid-body estimate F = F_run - m a with the peak
    deceleration as 1 / stop time: a deceleration force of 15 kN at 20 s needs 20 x 15 / (24 -
    18) = 50 s (not the 40 s the capped peak would give); never a longer start. In a coast
    or brake stop (no stop time: the drives are off) only the larger motor is offered."""
    drv = _drive_result(fmax=30e3, fmax_t=95.5, over_s=20.0, over_stop_s=16.0,
                        f2_int=20e3**2 * 60.0, rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[-18e3], stop_s=20.0, stop_accel_n=[15e3])
    assert "for 20.0 s of the cycle (4.0 s in the start and run, 16.0 s in the stop)" in w
    assert "(30 kN at t = 95.5 s)" in w
    assert "a longer stop (stop.time_s, now 20 s; about 50 s keeps the force within" in w
    assert "longer start" not in w and "at least 120 kW" in w
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[-18e3])
    assert "longer stop" not in w and "longer start" not in w
    assert w.endswith("a larger motor (at least 120 kW keeps it within) would avoid it"), w


def test_an_overload_in_a_stop_whose_deceleration_fits_is_not_offered_a_longer_stop():
    """The same drive in a stop whose rigid-body deceleration force (4 kN) keeps within what
    the rating leaves (24 - 18 = 6 kN): its time above the rating follows the belt's waves and
    swing, so no stop time is offered, only the larger motor; one whose running hold-back
    (-26 kN) or running pull (26 kN) is itself beyond the rating is told that no stop avoids
    it."""
    drv = _drive_result(fmax=30e3, fmax_t=95.5, over_s=20.0, over_stop_s=16.0,
                        f2_int=20e3**2 * 60.0, rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[-18e3], stop_s=20.0, stop_accel_n=[4e3])
    assert "stop.time_s" not in w and "longer start" not in w
    assert "the stop's rigid-body deceleration (4 kN on this drive) keeps within" in w
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[-26e3], stop_s=20.0, stop_accel_n=[15e3])
    assert "its running force, -26 kN, is itself above the rating: no stop avoids it" in w
    assert "stop.time_s" not in w
    # a motoring drive whose running force (26 kN) is above the rating, overloaded mostly in
    # the stop: the running force, not waves, is what is above the rating
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[26e3], stop_s=20.0, stop_accel_n=[4e3])
    assert "its running force, 26 kN, is itself above the rating: no stop avoids it" in w
    assert "waves" not in w


def test_a_regenerating_drive_overloaded_in_its_start_is_not_offered_a_longer_start():
    """A regenerating drive (running force -18 kN, rated 24 kN) above its rating for 20 s in
    the start (holding the belt's downhill pull before the resistances build up; the
    acceleration eases it): a longer start keeps the belt slow for longer, so only the
    larger motor is offered; one whose running hold-back (-28 kN) is itself beyond the
    rating is told that no start avoids it."""
    drv = _drive_result(fmax=30e3, fmax_t=2.0, over_s=20.0, f2_int=20e3**2 * 60.0,
                        rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[-18e3])
    assert "start.time_s" not in w and "(30 kN at t = 2.0 s)" in w
    assert "a larger motor (at least 120 kW keeps it within; the drive holds back" in w
    assert w.endswith("which a longer start would not shorten) would avoid it"), w
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0, 60.0,
                               running_n=[-28e3])
    assert "its running force, -28 kN, is itself above the rating: no start avoids it" in w


def test_transient_checks_quiet_within_the_rating_and_a_short_overload():
    """Above the rating for less than OVERLOAD_S_MAX, never at the limit, RMS within: no
    warning; a cycle that never started has no RMS."""
    drv = _drive_result(fmax=26e3, over_s=OVERLOAD_S_MAX - 1.0, f2_int=20e3**2 * 60.0,
                        rms_s=60.0)
    fields, warnings = transient_checks(["drive 1 (head)"], drv, [24e3], [36e3], [True], 4.0,
                                        10.0)
    assert warnings == [] and fields["drive1_force_rms_kn"] == pytest.approx(20.0)
    fields, _ = transient_checks(["drive 1"], _drive_result(), [24e3], [36e3], [True], 4.0,
                                 10.0)
    assert fields["drive1_force_rms_kn"] is None and fields["drive1_overload_s"] == 0.0


@pytest.mark.parametrize("rated_kw, overloaded", [(30.0, True), (50.0, False)])
def test_kernel_rms_and_overload_of_a_held_force(rated_kw, overloaded):
    """A flat belt pulled by a constant open-loop force of 20 kN for 2 s after the start
    command (the run ends there, the belt below twice its design speed): the RMS force is
    20 kN (the RMS of a constant), the time above the rated force P_N / v is the whole 2 s
    when P_N / v = 30 kW / 2 m/s = 15 kN, none when it is 50 / 2 = 25 kN (to a step)."""
    from beltstudy.engine.conveyor import Scenario
    from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
    from tests.engine.integration.test_dynamics_physics import flat_conveyor

    conv = flat_conveyor(length_m=200.0, speed_m_s=2.0, takeup_kg=5000.0, drives=[
        {"position": "head", "wrap_deg": 200, "friction": 0.35, "pulley_diameter_m": 1.0,
         "rated_power_kw": rated_kw}])
    st = solve_steady(conv, model="din", n_elements=20)
    sys_ = build_system(conv, Scenario(run_s=100), st, DynamicsOptions(force_start_n=20e3))
    res = simulate(sys_, t_end_s=sys_.model.cycle.t_pre + 2.0)
    assert res.status != "failed" and float(res.raw["v_mean"]) < 2.0 * 2.0  # not run away
    dt = sys_.dt_s
    assert res.summary["drive1_force_rms_kn"] == pytest.approx(20.0, rel=1e-9)
    assert res.summary["drive1_overload_s"] == pytest.approx(2.0 if overloaded else 0.0,
                                                            abs=1.5 * dt)
    assert math.isclose(res.summary["drive1_force_max_kn"], 20.0, rel_tol=1e-9)


def test_a_start_at_the_torque_limit_warns_and_agrees_with_the_time_series():
    """Two 650 kW head drives on slope-5pct started in 12 s (s-curve): the master sits at its
    torque limit in the start. The warning names the drive, the time above its rating and at
    its limit; drive1_overload_s and drive1_force_rms_kn agree with the recorded force
    (f_drive1_kn: the time above P_N / v = 650 / 4.5 = 144.4 kN, and the RMS from the start
    command to the belt at rest, summed over the records) to 0.1 s and 1 %."""
    from beltstudy.engine.conveyor import Scenario
    from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
    from tests.engine.dynamics.test_kernel import HEAD_PAIR, conveyor

    conv = conveyor("slope-5pct", drives=HEAD_PAIR)
    scn = Scenario(start={"control": "s-curve", "time_s": 12}, run_s=3,
                   stop={"mode": "controlled", "time_s": 10}, record_dt_s=0.01)
    st = solve_steady(conv, model="din", load=scn.load, n_elements=40)
    sys_ = build_system(conv, scn, st, DynamicsOptions())
    res = simulate(sys_, steady_summary=st.summary, conveyor=conv)
    s = res.summary
    rated = 650e3 / 4.5
    assert sys_.model.drives.rated[0] == pytest.approx(rated, rel=1e-12)
    assert (f"drive 1 (head) was above its rated force ({rated / 1e3:.4g} kN) for "
            f"{s['drive1_overload_s']:.1f} s") in res.message
    assert "at its torque limit" in res.message
    ts = res.timeseries  # recorded every step here (the step is above record_dt_s)
    t, f = ts["t_s"].to_numpy(), np.abs(ts["f_drive1_kn"].to_numpy()) * 1e3
    step = np.diff(t, prepend=t[0])  # each record stands for the step that ended at it
    after = t > sys_.model.cycle.t_pre
    assert s["drive1_overload_s"] == pytest.approx(float(step[after & (f > rated)].sum()),
                                                   abs=0.1)
    window = after & (t <= float(res.raw["t_stopped"]))
    assert s["drive1_force_rms_kn"] * 1e3 == pytest.approx(
        math.sqrt(float(np.sum(f[window] ** 2 * step[window]) / step[window].sum())),
        rel=0.01)


def _regen_stop(stop_s: float):
    """downhill-regen (DIN, full load, 60 elements) in a controlled stop of ``stop_s``: the
    run's summary, the largest |drive force| after the stop command and the drive's rated
    force P_N / v [kN]."""
    from beltstudy.engine.conveyor import Scenario
    from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
    from tests.engine.dynamics.test_kernel import conveyor

    conv = conveyor("downhill-regen")
    scn = Scenario(stop={"mode": "controlled", "time_s": stop_s}, elements=60)
    st = solve_steady(conv, model="din", load=scn.load, n_elements=60)
    sys_ = build_system(conv, scn, st, DynamicsOptions())
    res = simulate(sys_, steady_summary=st.summary, conveyor=conv)
    ts = res.timeseries
    t_cmd = sys_.model.cycle.t_pre + scn.start.time_s + scn.run_s
    return ({**res.summary, "message": res.message},
            float(ts.loc[ts.t_s > t_cmd, "f_drive1_kn"].abs().max()),
            float(sys_.model.drives.rated[0]) / 1e3)


def test_a_regenerating_belt_overloaded_in_its_stop_is_offered_the_stop_that_holds_it():
    """downhill-regen braked by its drive in a 20 s controlled stop: the drive holds back
    its running force and the belt's deceleration together, beyond its rating (P_N / v).
    The warning puts the overload in the stop and offers a longer stop by the rigid-body
    law F = F_run - m a, a_peak = 2 v / t_stop (the s-curve's); rerun at that stop time, the
    stop's largest force falls to the rating within the running swing the run also names
    (10 %), from more than 1.3 x it."""
    import re

    s, f_stop, rated = _regen_stop(20.0)
    assert f_stop > 1.3 * rated
    m = re.search(r"drive 1 \(head\) was above its rated force .*?\(([\d.]+) s in the start "
                  r"and run, ([\d.]+) s in the stop\).*?a longer stop \(stop.time_s, now 20 s; "
                  r"about (\d+) s keeps", s["message"])
    assert m, s["message"]
    assert float(m.group(2)) > float(m.group(1))
    # the overload is the stop's: its cure is not a longer start (the settling words of the
    # same run may name one for the running swing)
    over = re.search(r"drive 1 \(head\) was above its rated force.*?would avoid it", s["message"])
    assert over and "a longer start" not in over.group(0)
    _, f_stop2, _ = _regen_stop(float(m.group(3)))
    assert f_stop2 == pytest.approx(rated, rel=0.10)


def _small_conveyor(**over) -> dict:
    """A 20 m conveyor rising 1 m at 1 m/s, 20 t/h, no accessories: Te 1.85 kN (din), a
    drive of about 1.9 kW."""
    d = hand_conveyor_dict(speed_m_s=1.0, profile=[{"length_m": 20, "lift_m": 1}],
                           material={"capacity_t_h": 20, "density_t_m3": 1.0},
                           accessories={"head_kn": 0.0, "tail_kn": 0.0},
                           drives=[{"position": "head", "wrap_deg": 200, "friction": 0.35,
                                    "share": 1.0, "pulley_diameter_m": 0.5,
                                    "rated_power_kw": 0.2}])
    d.update(over)
    return d


def test_small_powers_and_masses_keep_their_figures_in_the_words():
    """A motor rated 0.2 kW was 'rated 0 kW' (twice: the shortfall and the force limit), the
    1.94 kW it needs '2 kW', and a 0.4 kg take-up '0 kg is below the 519 kg needed': a value
    below 10 now keeps two figures, one from 10 up stays whole."""
    st = solve_steady(parse_conveyor(_small_conveyor()), model="din", n_elements=40)
    assert st.summary["drive1_power_required_kw"] == pytest.approx(1.94, abs=0.005)
    assert "drive 1 (head) needs 1.9 kW at 1 m/s" in st.message
    assert "rated 0.2 kW: short by 1.7 kW (utilisation 9.72)" in st.message
    assert "(torque_limit 1.5 x rated 0.2 kW / 1 m/s)" in st.message
    light = _small_conveyor(takeup={"type": "gravity", "position": "tail", "mass_kg": 0.4})
    light["drives"][0]["rated_power_kw"] = 5
    st = solve_steady(parse_conveyor(light), model="din", n_elements=40)
    assert "take-up mass 0.4 kg is below the 519 kg needed" in st.message


def test_figures_in_words():
    from beltstudy.engine.drives import figures

    assert [figures(x) for x in (0.2, 0.04321, 1.94, 9.96, 12.6, 998.3, 17000.0, 0.0)] == [
        "0.2", "0.043", "1.9", "10", "13", "998", "17000", "0"]
    assert figures(17000.0, thousands=True) == "17,000"
    assert figures(0.35, thousands=True) == "0.35"
    assert figures(-0.2) == "-0.2" and figures(float("inf")) == "inf"


def test_a_drive_held_at_a_torque_limit_below_its_rating_is_not_said_to_be_over_it():
    """A regenerating drive on a decline with torque_limit 0.4: rated 8.334 kN (20.835 kW at
    2.5 m/s), its limit 0.4 x 8.334 = 3.334 kN, held there for 12.7 s from t = 2 s and never
    above the rating (over_s 0). The warning said 'was above its rated force (8.334 kN) for
    0.0 s of the cycle, at most -60 % over its rating'; it now says the drive was held at its
    torque limit, 3.334 / 8.334 = 40 % of its rated force, for 12.7 s."""
    drv = _drive_result(fmax=3.334e3, fmax_t=2.0, over_s=0.0, lim_s=12.7,
                        f2_int=3.334e3**2 * 12.7, rms_s=20.0)
    _fields, warnings = transient_checks(["drive 1 (head)"], drv, [8.334e3], [3.334e3], [True],
                                         2.5, 12.0, running_n=[-4.0e3])
    (w,) = warnings
    assert "over its rating" not in w and "above its rated force" not in w
    assert w.startswith("drive 1 (head) was held at its torque limit (3.334 kN, 40 % of its "
                        "rated force 8.334 kN) for 12.7 s of the cycle (first at t = 2.0 s)")
    assert "a larger motor (more than" in w


def test_a_start_overload_gives_the_swing_scaled_figure_beside_the_rigid_body_one():
    """A 10 s vfd start on a drive rated 24 kN, running at 12 kN, whose rigid-body share at
    the peak acceleration is 15 kN while the run's own peak reached 30 kN (18 kN above its
    running force): the rigid body says 10 x 15 / 12 = 12.5 s (13 s), which leaves the belt's
    swing out; the run's own peak scaled as 1 / t says 10 x 18 / 12 = 15 s, and both are
    given. A 5 km route's 60 s start was told 128 s by the rigid body and still overloaded
    there for 19.6 s; its swing-scaled 142 s kept it within. A run whose peak is within the
    rigid body's gets the one figure."""
    drv = _drive_result(fmax=30e3, fmax_t=5.0, over_s=20.0, f2_int=13e3**2 * 60.0,
                        rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], start_accel_n=[15e3])
    assert "about 13 s keeps the force within the rating, a rigid-body estimate" in w, w
    assert "about 15 s with the run's own peak above its running force (18 kN against the " \
           "rigid body's 15 kN) scaled as 1 / t" in w, w
    drv = _drive_result(fmax=26e3, fmax_t=5.0, over_s=20.0, f2_int=13e3**2 * 60.0,
                        rms_s=60.0)
    _, (w,) = transient_checks(["drive 1 (head)"], drv, [24e3], [60e3], [True], 4.0, 10.0,
                               running_n=[12e3], start_accel_n=[15e3])
    assert "about 13 s keeps the force within" in w and "run's own peak" not in w, w
