"""A fixed (screw or winch) take-up holds its place, so the loop's length, not a tension: at
start-up the carry stretches under the drives' extra force and the rest of the loop gives
the length back. The start-up check (``slip_margin_start``, the auto pretension) must level
its walk that way (PHYSICS 1, DIN 22101's start-up force; ``statics.start_level``).

Before: the walk was levelled as a counterweight's, the take-up holding its running tension.
On a 2 km, 40 m incline (ST1600, 1 m, 1 440 t/h at 4 m/s) with a fixed take-up just behind
its head drive the auto pretension was 90.3 kN (``slip_start``, margin 1.000), and a 60 s
s-curve start, asking 1.26 x Te of a rigid belt, slid 10.9 m of belt over the head pulley;
the transient run's own search found 112 kN. Levelled by length, 109.0 kN."""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.loop import pulley_reduced_mass_kg
from beltstudy.engine.statics import solve_steady, startup_tensions
from tests.conftest import hand_conveyor_dict

G = 9.81


def _hand_te() -> float:
    """The hand conveyor's Te under DIN 22101, term by term [N]: 1 000 m at 5 % (50 m lift),
    f = 0.020, C(1000) = 1.09, accessories 1.0 + 0.5 kN."""
    cos = math.sqrt(1.0 - 0.05 ** 2)
    carry = 0.020 * G * 1000.0 * (10.0 + (20.0 + 50.0) * cos)
    ret = 0.020 * G * 1000.0 * (3.0 + 20.0 * cos)
    lift = 50.0 * G * 50.0
    secondary = 0.09 * (carry + ret)
    return carry + ret + lift + secondary + 1500.0


def _fixed_head():
    return hand_conveyor_dict(takeup={"type": "fixed", "position": "head",
                                      "pretension_kn": "auto"})


def test_start_up_of_a_fixed_take_up_keeps_the_loop_length():
    """The start-up tensions of a fixed take-up have the running state's length-weighted
    mean tension (the belt's elastic length, EB uniform), element by element."""
    res = solve_steady(parse_conveyor(_fixed_head()), model="din")
    dx = res.loop.dx_m
    run, start = res.tension_n, startup_tensions(res)
    length = lambda T: float(np.sum(dx * 0.5 * (np.roll(T, 1) + T)))  # noqa: E731
    assert length(start) == pytest.approx(length(run), rel=1e-12)


def test_auto_pretension_of_a_fixed_take_up_behind_the_head_drive_by_hand():
    """The slack side at start-up and the running slack side of the auto pretension, by hand.

    Start-up force 1.5 Te; the extra E = 0.5 Te accelerates everything at a = E / M,
    M = carry (20 + 50 + 10) x 1000 + return (20 + 3) x 1000 + the drive shaft (its shell,
    D 1 m) + the head take-up and tail pulleys' shells (0.8 m). Walking the extra tension
    from the tail pulley's out side (C): the carry end is C + M_c a, the drive takes
    E - m_d a, the take-up pulley and the return add m_h a and M_r a, the tail pulley m_t a.
    The same loop length (pulley arcs neglected, 3 m of 2 000) asks the carry mean C + M_c a
    / 2 and the return mean C - m_t a - M_r a / 2 to sum to nought:
    C = (m_t a + (M_r - M_c) a / 2) / 2, and the slack side falls by
    dT = C - (M_r + m_t + m_h) a (a counterweight there would drop it by m_h a / 2 only).
    The auto pretension sets the start-up slack side to (1.5 Te - m_d a) / (e^(mu theta) - 1),
    so running it is that less dT."""
    te = _hand_te()
    m_c, m_r = 80_000.0, 23_000.0
    m_d = pulley_reduced_mass_kg(1.0, 1.0)
    m_h = m_t = pulley_reduced_mass_kg(0.8, 1.0)
    a = 0.5 * te / (m_c + m_r + m_d + m_h + m_t)
    c = (m_t * a + 0.5 * (m_r - m_c) * a) / 2.0
    drop = c - (m_r + m_t + m_h) * a
    e = math.exp(0.35 * math.radians(200.0))
    slack_start = (1.5 * te - m_d * a) / (e - 1.0)

    res = solve_steady(parse_conveyor(_fixed_head()), model="din")
    assert res.te_n == pytest.approx(te, rel=1e-9)
    assert res.takeup_governed_by == "slip_start"
    assert res.summary["slip_margin_start"] == pytest.approx(1.0, abs=1e-9)
    i = res.loop.drive_elements[0]
    start = startup_tensions(res)
    # pulley arcs neglected by hand: 1.6 m of the 2 000 m weigh in the length
    assert start[i] - res.tension_n[i] == pytest.approx(drop, rel=3e-3)
    # the belt on the drive pulley's arc (about 35 kg) neglected by hand: a few newtons
    assert start[i] == pytest.approx(slack_start, rel=2e-4)
    assert res.summary["t2_kn"] * 1e3 == pytest.approx(slack_start - drop, rel=1e-3)


def test_a_gravity_take_up_there_still_holds_its_mean_tension():
    """The counterweight's level is unchanged: the start-up walk keeps the take-up pulley's
    mean tension (its two strands) at the running one."""
    d = hand_conveyor_dict(takeup={"type": "gravity", "position": "head", "mass_kg": "auto"})
    res = solve_steady(parse_conveyor(d), model="din")
    k = res.loop.i_takeup
    run, start = res.tension_n, startup_tensions(res)
    assert 0.5 * (start[k - 1] + start[k]) == pytest.approx(0.5 * (run[k - 1] + run[k]),
                                                            rel=1e-12)


def test_breakaway_of_a_regenerating_belt_on_a_fixed_take_up_by_hand():
    """The hand conveyor down 100 m (10 %) on a fixed take-up at the tail, held back by its
    head drive (Te < 0), is sized for breakaway as a counterweight's is: at standstill the
    drive holds the whole pull sum G = -50 x 9.81 x 100 = -49.05 kN with no resistance yet.
    Walking from the tail pulley's out side (C): the carry falls by 70 x 9.81 x 100 =
    68.67 kN to the head, the drive gives back 49.05 kN, the return climbs 19.62 kN to the
    tail. Tight C - 19.62, slack C - 68.67: C >= (68.67 e - 19.62) / (e - 1), e =
    e^(0.35 x 200 deg). Held by length, the loop's mean tension at rest is C less the walk's
    mean (carry C - 34.335, return C - 9.81 kN, pulley arcs neglected), and the running state
    keeps that mean. Before, a fixed take-up had no breakaway check (slip running set it)."""
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": -100}],
                           takeup={"type": "fixed", "position": "tail",
                                   "pretension_kn": "auto"})
    res = solve_steady(parse_conveyor(d), model="din")
    assert res.te_n < 0.0
    assert res.takeup_governed_by == "slip_breakaway"
    assert res.summary["slip_margin_start"] == pytest.approx(1.0, abs=1e-9)
    e = math.exp(0.35 * math.radians(200.0))
    c = (68.67e3 * e - 19.62e3) / (e - 1.0)
    mean_rest = c - 0.5 * (34.335e3 + 9.81e3)
    dx = res.loop.dx_m
    T = res.tension_n
    mean_run = float(np.sum(dx * 0.5 * (np.roll(T, 1) + T)) / np.sum(dx))
    assert mean_run == pytest.approx(mean_rest, rel=2e-3)
