"""Pieces shared by the friction models: pulley allowances, accessories, feed."""

from __future__ import annotations

import numpy as np

from beltstudy.engine.conveyor import Conveyor
from beltstudy.engine.law import LawBuilder
from beltstudy.engine.loop import CARRY, Loop

#: CEMA pulley allowances T_p [N]: 200 lbf tight side (drive) pulleys, 150 lbf slack-side
#: pulleys (the take-up pulley), 100 lbf other pulleys (CEMA 6th ed., Table 6-5 allowances as
#: quoted in PHYSICS section 2; unverified).
LBF = 4.4482216
TP_TIGHT_N = 200 * LBF
TP_SLACK_N = 150 * LBF
TP_OTHER_N = 100 * LBF


def lumped_index(loop: Loop, conv: Conveyor, position: str) -> int:
    """Element that carries the lumped resistances of the head or tail pulleys.

    At a driven end they act on the belt just after its last drive pulley (the head scraper
    works on the return belt; the drive pulleys' own bearing losses are the drives'), so that
    the drive pulleys' T_in - T_out add up to their shares of Te exactly (Harrison 2008:
    Pe = v (T1 - T2)); at an end without a drive, on its plain pulley.
    """
    own = [p for p in loop.pulleys if p.position == position and not p.takeup]
    driven = [p for p in own if p.drive >= 0]
    if driven:
        return (driven[-1].element + 1) % loop.n
    if own:
        return own[0].element
    # a tail take-up pulley is the tail pulley of an undriven tail
    return next(p.element for p in loop.pulleys if p.position == position)


def lumped_indices(loop: Loop, conv: Conveyor) -> list[int]:
    """Elements carrying the pulley resistances: head, tail and a separate take-up pulley."""
    idx = {lumped_index(loop, conv, "head"), lumped_index(loop, conv, "tail")}
    if loop.i_takeup not in idx:
        idx.add(loop.i_takeup)
    return sorted(idx)


def pulley_allowances(loop: Loop, conv: Conveyor) -> np.ndarray:
    """Per-element pulley resistance allowances [N] (CEMA T_p): 200 lbf per drive pulley and
    150 lbf for the take-up pulley (slack side), 100 lbf for other pulleys, each drive's at its
    end's lumped element."""
    out = np.zeros(loop.n)
    for p in loop.pulleys:
        if p.drive >= 0:
            out[lumped_index(loop, conv, p.position)] += TP_TIGHT_N
        elif p.takeup:
            out[p.element] += TP_SLACK_N
        else:
            out[p.element] += TP_OTHER_N
    return out


def add_accessories(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """Lumped accessory resistances (scrapers, skirts, ploughs) at the head and tail [N]."""
    acc = np.zeros(loop.n)
    acc[lumped_index(loop, conv, "head")] += conv.accessories.head_kn * 1e3
    acc[lumped_index(loop, conv, "tail")] += conv.accessories.tail_kn * 1e3
    b.add("accessories", acc)


def add_feed(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """Force to accelerate the material at the feed, I_m (v - v0) [N] (DIN 22101, CEMA T_am).

    I_m = m'_L v_design is the mass flow [kg/s], with m'_L the material on the feed element
    (the first carry section's share of a load pattern); as a law term: I_m |v| - I_m v0 on
    the feed element, so in transients it scales with the belt speed.
    """
    j = 0  # the feed point: the first carry element (tail end)
    im = float(loop.mL_kg_m[j]) * loop.speed_m_s  # [kg/s]
    if im <= 0.0:
        return
    coef1 = np.zeros(loop.n)
    coef0 = np.zeros(loop.n)
    assert loop.strand[j] == CARRY
    coef1[j] = im
    coef0[j] = -im * conv.material.loading_speed_m_s
    b.add("feed", coef1, pv=1.0)
    b.add("feed", coef0)
