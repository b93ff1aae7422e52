"""The steady run's start-up checks take the drives at STARTUP_FACTOR x Te; a vfd start
faster than the one that accelerates the belt at that force asks more of the drives and the
take-up than the checks allow for, and the steady run says from what start time it does not
(``beltstudy.engine.statics.start_time_note``).

Hand numbers: the hand conveyor of tests/conftest.py made flat (1 km, 4 m/s, m'_G 20 kg/m on
both strands, m'_L 50 kg/m, idler rolls 10 + 3 kg/m): belt, load and rolls weigh
1000 x (2 x 20 + 50 + 10 + 3) = 103 000 kg; the pulley shells and drive shafts add a few
per cent."""

from __future__ import annotations

import re

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import STARTUP_FACTOR, solve_steady
from tests.conftest import hand_conveyor_dict

NOTE = (r"note: the start-up checks \(slip_margin_start, the auto take-up\) take the drives at "
        r"1.5 x Te, which accelerates this belt at ([\d.]+) m/s2 .*? from start.time_s (\d+) s")


def _flat(**takeup):
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 0}])
    d["takeup"] = {**d["takeup"], **takeup}
    return parse_conveyor(d)


def _start(conv, start_s):
    """The largest drive force in an s-curve start of ``start_s`` [N], and the run."""
    r = run_one(conv, Scenario(start={"time_s": start_s}, run_s=10, stop={"mode": "coast"}),
                model="din")
    ts = r.timeseries
    t = ts["t_s"].to_numpy()
    m = (t > 2.0) & (t < 2.0 + start_s)
    return float(ts["f_drive_kn"].to_numpy()[m].max()) * 1e3, r


def test_the_start_time_the_start_up_checks_allow_for_is_said_and_holds():
    """The note's acceleration is (1.5 - 1) Te / M with M at least the 103 000 kg of belt,
    load and rolls and at most 10 % more; its start time is 2 v / a rounded up (the
    cycloid's peak). With a take-up heavy enough that nothing slips, a transient s-curve start
    of that time asks the drive at most 1.5 x Te (2 % for the waves of a 1.2 s wave loop), one
    of 0.75 of it more than 1.6 x Te (rigid body: 1 + 0.5 / 0.75 = 1.67). With the auto
    take-up, sized by the checks (start-up slip margin 1), that faster start slips."""
    st = solve_steady(_flat(), model="din")
    te = st.te_n
    said = re.search(NOTE, st.message)
    assert said, st.message
    a, t_s = float(said.group(1)), float(said.group(2))
    m_hand = 103_000.0
    assert 0.5 * te / (1.10 * m_hand) <= a <= 0.5 * te / m_hand
    assert 2.0 * 4.0 / a <= t_s < 2.0 * 4.0 / a * 1.01 + 1.0
    assert t_s > 60.0
    heavy = _flat(mass_kg=3.0 * st.summary["takeup_mass_kg"])
    assert _start(heavy, t_s)[0] <= STARTUP_FACTOR * te * 1.02
    assert _start(heavy, 0.75 * t_s)[0] > 1.6 * te
    assert st.summary["slip_margin_start"] >= 1.0 - 1e-9
    _, r = _start(_flat(), 0.75 * t_s)
    assert r.summary["drive1_slip_s"] > 1.0
    # a transient run says it of its own start: the 54 s start asks 1 + 0.5 x 72 / 54 x Te
    # (a = 4 x 2 / 72), the note's start time itself nothing
    own = re.search(r"this run's 54 s s-curve asks ([\d.]+) x Te at its peak", r.summary["message"])
    assert own, r.summary["message"]
    assert float(own.group(1)) == round(1.0 + 0.5 * (2.0 * 4.0 / 54.0) / a, 2)
    assert "start-up checks" not in _start(_flat(), t_s)[1].summary["message"]


def test_no_note_where_the_default_start_is_within_the_checks():
    """A steep 1 km incline (lift 50 m): the lift makes Te large against the mass, so the
    checks' 0.5 Te accelerates it to 4 m/s within a 60 s s-curve; nothing is said. A dol
    drive's start is its motor's, not start.time_s: nothing is said either."""
    st = solve_steady(parse_conveyor(hand_conveyor_dict()), model="din")
    assert "start-up checks" not in st.message
    # a transient run whose own start is beyond the checks says so (a 10 s s-curve peaks at
    # 0.8 m/s2), one within them does not
    fast = run_one(parse_conveyor(hand_conveyor_dict()), Scenario(
        start={"time_s": 10}, run_s=5, stop={"mode": "coast"}), model="din")
    assert "this run's 10 s s-curve asks" in fast.summary["message"]
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": 0}])
    d["drives"] = [{**d["drives"][0], "control": "dol"}]
    assert "start-up checks" not in solve_steady(parse_conveyor(d), model="din").message


def test_a_steady_only_run_judges_the_scenarios_start_not_the_default():
    """A study without dynamics still gives its scenario's start: its rows were told of "the
    default 60 s s-curve" where the study's start was 45 s. The flat belt's default note
    (from start.time_s above 60 s) is said of the 54 s start asked, and a steep belt within
    the checks at 60 s is told of its own 10 s start."""
    flat = _flat()
    own = run_one(flat, Scenario(start={"time_s": 54}), model="din", dynamics=False)
    msg = own.summary["message"]
    assert "this run's 54 s s-curve asks" in msg and "the default" not in msg, msg
    plain = run_one(flat, Scenario(), model="din", dynamics=False).summary["message"]
    assert "the default 60 s s-curve asks" in plain
    steep = run_one(parse_conveyor(hand_conveyor_dict()), Scenario(start={"time_s": 10}),
                    model="din", dynamics=False)
    assert "this run's 10 s s-curve asks" in steep.summary["message"]
