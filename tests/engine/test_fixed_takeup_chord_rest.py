"""An auto fixed take-up sized to the sag limit held at rest meets it in the rest state the
transient model starts from, and a sag past its limit by less than the rounding is not printed
as the limit.

A fixed take-up holds the loop's length. The transient model's at-rest state keeps the
running state's chord length, the spans' sag in it (Ernst: ``eps = T / EB - (w S)^2 /
(24 T^2)``); the sizing took the elastic length alone (the length-weighted mean tension).
On a loaded 110 m decline with its drive and take-up at the tail the sag's part lowered the
rest level: the auto pretension 13.220 kN left the carry sagging 1.5005 % at rest against
1.5 %, and a transient sag warning beside it said 'the strand sags 1.5 % at rest too'.

The sag is checked by hand (PHYSICS section 1): h / a = g (m'_G + m'_L) a / (8 T) for an idler
span a at its lower tension T, with the weight's component across the belt, x cos(slope), on
the 18 m in 110 m slope (the sag of a span on a slope hangs across it: the engine's
``Loop.sag_w_n``; PHYSICS writes the level belt's form).
"""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system
from beltstudy.engine.dynamics.simulate import _sag_at_rest_too
from beltstudy.engine.loop import CARRY
from beltstudy.engine.statics import solve_steady
from tests.engine.test_fixed_takeup_sag_at_rest import DECLINE

G = 9.81
LIMIT = 0.015
#: the loaded 110 m decline of the head-drive test, driven at the tail
TAIL_DRIVE = dict(DECLINE, name="dec110-taildrive",
                  drives=[dict(DECLINE["drives"][0], position="tail")])
# by hand: EP800/4, 7.4 kg/m2 carcass and 6 + 2 mm covers x 1.15 kg/m2/mm, 1 m wide
# (engine/data/belts.csv); m'_L = Q / (3.6 v); the carry's idler span and slope
M_G = (7.4 + 8 * 1.15) * 1.0
M_L = 800.0 / (3.6 * 3.0)
SPAN_CARRY = 1.2
COS = math.sqrt(1.0 - (18.0 / 110.0) ** 2)  # length_m is along the belt (SPEC)


def _carry_rest_sag(conv, st) -> float:
    """The carry's largest sag ratio [-] in the transient model's rest state, by hand from
    each carry span's lower rest tension."""
    T = build_system(conv, Scenario(elements=st.loop.n), st, DynamicsOptions()).tension_rest_n
    loop = st.loop
    low = np.minimum(T, np.roll(T, 1))[loop.is_idler & (loop.strand == CARRY)]
    assert low.min() > 0.0
    return float(np.max(G * (M_G + M_L) * COS * SPAN_CARRY / (8.0 * low)))


@pytest.mark.parametrize("n", [110, None])
def test_an_auto_fixed_takeup_at_a_tail_drive_meets_the_sag_limit_at_rest(n):
    conv = parse_conveyor(TAIL_DRIVE)
    st = solve_steady(conv, model="din", n_elements=n)
    assert st.summary["takeup_governed_by"] == "sag_at_rest"
    sag = _carry_rest_sag(conv, st)
    # sized to it: at the limit to the solver's tolerance, not above it
    assert sag <= LIMIT * (1.0 + 1e-9), sag
    assert sag == pytest.approx(LIMIT, rel=1e-6)


def test_a_rest_sag_just_past_its_limit_is_printed_past_it():
    """1.5005 % against 1.5 % read 'sags 1.5 % at rest too': the figure now shows it past the
    limit. Four springs at 1 kN, the idler spans' g m' a cos / 8 = 15.005 N: 1.5005 %."""
    sys_ = SimpleNamespace(
        tension_rest_n=np.full(4, 1000.0), strand=np.zeros(4, dtype=int),
        model=SimpleNamespace(nodes=SimpleNamespace(sag_w=np.array([0.0, 15.005, 15.005,
                                                                     15.005]))))
    said = _sag_at_rest_too(sys_, 2, 1.5)
    shown = re.search(r"the strand sags ([\d.]+) % at rest too", said)
    assert shown, said
    assert float(shown.group(1)) > 1.5, said
    assert float(shown.group(1)) == pytest.approx(1.5005, abs=6e-4)
    # well past it, three figures as before; within it, nothing
    sys_.model.nodes.sag_w[1:] = 19.0
    assert "sags 1.9 % at rest too" in _sag_at_rest_too(sys_, 2, 1.5)
    sys_.model.nodes.sag_w[1:] = 15.0
    assert _sag_at_rest_too(sys_, 2, 1.5) == ""


def test_a_steady_sag_just_past_its_limit_is_printed_past_it():
    """A given pretension a little below the running sag need: the span's tension falls by
    0.002 %, so it sags 1.5 x 1.00002 = 1.50003 %, which '.2f' printed as 1.50 % against the
    limit 1.50 %."""
    off = {**TAIL_DRIVE, "takeup": {**TAIL_DRIVE["takeup"], "sag_at_rest": False}}
    st = solve_steady(parse_conveyor(off), model="din", n_elements=110)
    assert st.summary["takeup_governed_by"] == "sag_running"
    # the carry's governing span at the limit: its lower tension by hand
    t_need = G * (M_G + M_L) * COS * SPAN_CARRY / (8.0 * LIMIT)
    t_low = t_need * (1.0 - 2e-5)
    given = st.summary["takeup_pretension_kn"] - (t_need - t_low) / 1e3
    low = {**off, "takeup": {**off["takeup"], "pretension_kn": given}}
    msg = solve_steady(parse_conveyor(low), model="din", n_elements=110).message
    m = re.search(r"sag on the carry strand ([\d.]+) % exceeds sag_limit_pct.carry = ([\d.]+) %",
                  msg)
    assert m, msg
    assert float(m.group(1)) > float(m.group(2)) == pytest.approx(1.5), msg
    assert float(m.group(1)) == pytest.approx(1.5 * t_need / t_low, abs=1e-5)
