"""Pieces shared by the friction models: pulley allowances, accessories, feed."""

from __future__ import annotations

import numpy as np

from engine.conveyor import Conveyor
from engine.law import LawBuilder
from engine.loop import CARRY, Loop

#: CEMA pulley allowances T_p [N]: 200 lbf tight side (drive) pulleys, 150 lbf slack-side
#: pulleys (the take-up pulley), 100 lbf other pulleys (CEMA 6th ed., Table 6-5 allowances as
#: quoted in PHYSICS section 2; unverified).
LBF = 4.4482216
TP_TIGHT_N = 200 * LBF
TP_SLACK_N = 150 * LBF
TP_OTHER_N = 100 * LBF


def lumped_index(loop: Loop, conv: Conveyor, position: str) -> int:
    """Element that carries the lumped resistances of the head or tail pulley.

    On a drive pulley they act on the belt just after it (the head scraper works on the
    return belt; the drive pulley's own bearing losses are the drive's), so that
    T1 - T2 equals the drive's share of Te exactly (Harrison 2008: Pe = v (T1 - T2)).
    """
    idx = loop.i_head if position == "head" else loop.i_tail
    if any(d.position == position for d in conv.drives):
        idx = (idx + 1) % loop.n
    return idx


def lumped_indices(loop: Loop, conv: Conveyor) -> list[int]:
    """Elements carrying the pulley resistances: head, tail and a separate take-up pulley."""
    idx = {lumped_index(loop, conv, "head"), lumped_index(loop, conv, "tail")}
    if loop.i_takeup not in (loop.i_head, loop.i_tail):
        idx.add(loop.i_takeup)
    return sorted(idx)


def pulley_allowances(loop: Loop, conv: Conveyor) -> np.ndarray:
    """Per-element pulley resistance allowances [N] (CEMA T_p) at the pulleys."""
    out = np.zeros(loop.n)
    drive_pos = {d.position for d in conv.drives}
    for pos in ("head", "tail"):
        out[lumped_index(loop, conv, pos)] += TP_TIGHT_N if pos in drive_pos else TP_OTHER_N
    if loop.i_takeup not in (loop.i_head, loop.i_tail):
        out[loop.i_takeup] += TP_SLACK_N
    elif loop.i_takeup == loop.i_tail and "tail" not in drive_pos:
        out[loop.i_tail] += TP_SLACK_N - TP_OTHER_N
    return out


def add_accessories(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """Lumped accessory resistances (scrapers, skirts, ploughs) at the head and tail [N]."""
    acc = np.zeros(loop.n)
    acc[lumped_index(loop, conv, "head")] += conv.accessories.head_kn * 1e3
    acc[lumped_index(loop, conv, "tail")] += conv.accessories.tail_kn * 1e3
    b.add("accessories", acc)


def feed_index(loop: Loop) -> int:
    """The feed point: the first carry element (tail end)."""
    return 0


def add_feed(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """Force to accelerate the material at the feed, I_m (v - v0) [N] (DIN 22101, CEMA T_am).

    I_m = m'_L v_design is the mass flow [kg/s], with m'_L the material on the feed element
    (the first carry section's share of a load pattern); as a law term: I_m |v| - I_m v0 on
    the feed element, so in transients it scales with the belt speed.
    """
    im = float(loop.mL_kg_m[feed_index(loop)]) * loop.speed_m_s  # [kg/s]
    if im <= 0.0:
        return
    coef1 = np.zeros(loop.n)
    coef0 = np.zeros(loop.n)
    j = feed_index(loop)
    assert loop.strand[j] == CARRY
    coef1[j] = im
    coef0[j] = -im * conv.material.loading_speed_m_s
    b.add("feed", coef1, pv=1.0)
    b.add("feed", coef0)
