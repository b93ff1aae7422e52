"""Holding brakes whose given forces cannot hold the loaded belt at rest are a warning
(``beltstudy.engine.checks.holding_warning``).

Hand numbers: the hand conveyor of tests/conftest.py, 1 km, m'_L = 50 kg/m. Made a decline
of 50 m its load pulls 50 x 9.81 x 50 = 24.525 kN downhill; CEMA's backstop rule credits half
the running resistance without the feed (the DIN components main carry, main return,
secondary and accessories of the run)."""

from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

WORDS = (r"the holding brakes cannot hold the loaded belt at rest: brakes.0 ([\d.]+) kN give "
         r"[\d.]+ kN in all against its net gravity pull ([\d.]+) kN less ([\d.]+) kN .*?, "
         r"([\d.]+) kN, so it would creep (forward \(downhill\)|back) once stopped; holding "
         r"brakes of at least ([\d.]+) kN in all")


def _run(lift_m, brakes, **over):
    d = hand_conveyor_dict(profile=[{"length_m": 1000, "lift_m": lift_m}], brakes=brakes,
                           **over)
    return solve_steady(parse_conveyor(d), model="din")


def _need_kn(st, pull_kn):
    parts = st.summary["te_components_kn"]
    friction = sum(v for k, v in parts.items() if k not in ("lift", "feed"))
    return pull_kn - 0.5 * friction


def test_a_given_holding_brake_below_the_pull_of_a_decline_is_a_warning():
    """5 kN against 24.525 kN less half the resistance (12.77 kN): warned, with the pull, the
    credit, the force needed and the forward creep; the force advised (rounded up to 0.1 kN)
    holds when given; an auto brake (1.2 x the pull) and a brake without hold (released once
    stopped) are not warned."""
    st = _run(-50, [{"position": "head", "force_kn": 5}])
    said = re.search(WORDS, st.message)
    assert said, st.message
    need = _need_kn(st, 24.525)
    assert float(said.group(2)) == pytest.approx(24.525, abs=0.01)
    assert float(said.group(4)) == pytest.approx(need, abs=0.01)
    assert said.group(5) == "forward (downhill)"
    advised = float(said.group(6))
    assert need <= advised < need + 0.1
    assert st.status == "warning"
    assert "holding brakes cannot" not in _run(-50, [{"position": "head",
                                                      "force_kn": advised}]).message
    assert "holding brakes cannot" not in _run(-50, [{"position": "head",
                                                      "force_kn": "auto"}]).message
    assert "holding brakes cannot" not in _run(-50, [{"position": "head", "force_kn": 5,
                                                      "hold": False}]).message


def test_an_incline_is_held_by_its_holdback_or_warned_back():
    """On a 50 m incline the load pulls back: with a holdback nothing is said; without one a
    weak holding brake is warned of the run back, with the holdback as a remedy."""
    assert "holding brakes cannot" not in _run(50, [{"position": "head", "force_kn": 5}],
                                                holdback=True).message
    st = _run(50, [{"position": "head", "force_kn": 5}], holdback=False)
    said = re.search(WORDS, st.message)
    assert said and said.group(5) == "back", st.message
    assert "or a holdback (holdback: true) would avoid it" in st.message
