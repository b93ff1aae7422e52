"""Pieces shared by the friction models: pulley allowances, accessories, feed."""

from __future__ import annotations

import numpy as np

from beltstudy.engine.conveyor import SKIRT_WIDTH_SHARE, Conveyor
from beltstudy.engine.law import LawBuilder
from beltstudy.engine.loop import CARRY, G, Loop

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
    end's lumped element (a booster's just after its own pulley)."""
    out = np.zeros(loop.n)
    for p in loop.pulleys:
        if p.drive >= 0 and p.at_m is not None:  # a booster: just after its own pulley
            out[(p.element + 1) % loop.n] += TP_TIGHT_N
        elif p.drive >= 0:
            out[lumped_index(loop, conv, p.position)] += TP_TIGHT_N
        elif p.takeup:
            out[p.element] += TP_SLACK_N
        else:
            out[p.element] += TP_OTHER_N
    return out


def add_accessories(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """Lumped accessory resistances (scrapers, skirts, ploughs) at the head and tail [N],
    and the skirts of the feed points, the belt cleaners and the ploughs where they sit
    (:func:`skirt_forces`, :func:`scraper_forces`, :func:`plough_forces`)."""
    acc = np.zeros(loop.n)
    acc[lumped_index(loop, conv, "head")] += conv.accessories.head_kn * 1e3
    acc[lumped_index(loop, conv, "tail")] += conv.accessories.tail_kn * 1e3
    if conv.material.feed is not None:
        acc += skirt_forces(loop, conv)
    if conv.accessories.scrapers or conv.accessories.ploughs:
        acc += scraper_forces(loop, conv) + plough_forces(loop, conv)
    b.add("accessories", acc)


def carry_element_at(loop: Loop, at_m: float) -> int:
    """The carry element that starts at or contains ``at_m`` along the carry [m] (a feed
    point starts an element: :func:`beltstudy.engine.loop.section_cuts`)."""
    carry = np.flatnonzero(loop.strand == CARRY)
    s = loop.x_m[carry]
    tol = 1e-6 * max(1.0, loop.length_m)
    return int(carry[max(int(np.searchsorted(s, at_m + tol, side="right")) - 1, 0)])


def _section_fraction(loop: Loop, conv: Conveyor, at_m: float) -> float:
    """The load case's fraction of the design load on the profile section holding ``at_m``."""
    ends = np.cumsum([p.length_m for p in conv.profile])
    i = min(int(np.searchsorted(ends, at_m, side="right")), len(ends) - 1)
    return float(loop.section_load[i]) if loop.section_load else loop.load_fraction


def _add_feed_points(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """The feed acceleration I_m,i (v - v0,i) of each feed point i on the element it starts
    (DIN 22101 / ISO 5048 F_bA = I_V rho (v - v0)), with I_m,i = share_i x (the load case's
    fraction on its section) x m'_L,design x v_design [kg/s]."""
    coef1 = np.zeros(loop.n)
    coef0 = np.zeros(loop.n)
    for f in conv.material.feed:
        im = f.share * _section_fraction(loop, conv, f.at_m) * loop.design_load_kg_m \
            * loop.speed_m_s  # [kg/s]
        v0 = f.loading_speed_m_s
        if v0 is None:
            v0 = conv.material.loading_speed_m_s
        j = carry_element_at(loop, f.at_m)
        coef1[j] += im
        coef0[j] -= im * v0
    if coef1.any():
        b.add("feed", coef1, pv=1.0)
        b.add("feed", coef0)


def skirt_forces(loop: Loop, conv: Conveyor) -> np.ndarray:
    """Skirt-board friction per element [N] (ISO 5048:1989 / DIN 22101 F_gL).

    F_gL = mu_2 I_V^2 rho g l_b / (v^2 b_1^2): with the volume flow I_V = m'_L v / rho on
    the belt under the skirt (all the material fed at or upstream of it), per element
    dF_j = mu_2 g l_j m'_L,j^2 / (rho b_1^2), l_j the length of element j under the skirts
    (from the feed point ``skirt_length_m`` downstream). b_1 is ``skirt_width_m``, default
    ``SKIRT_WIDTH_SHARE`` of the belt width; rho the bulk density [kg/m3]. Speed independent
    (the load on the belt is the case's; in transients it keeps the sign of the speed).
    """
    out = np.zeros(loop.n)
    carry = loop.strand == CARRY
    start = loop.x_m  # along the route (pulleys along the carry take no route length)
    end = loop.x_m + loop.dx_m
    rho = conv.material.density_t_m3 * 1e3
    for f in conv.material.feed or []:
        if f.skirt_length_m <= 0.0:
            continue
        b1 = f.skirt_width_m if f.skirt_width_m is not None \
            else SKIRT_WIDTH_SHARE * loop.belt.width_m
        over = np.clip(np.minimum(end, f.at_m + f.skirt_length_m)
                       - np.maximum(start, f.at_m), 0.0, None)
        out += np.where(carry, f.skirt_friction * G * over * loop.mL_kg_m ** 2
                        / (rho * b1 * b1), 0.0)
    return out


def scraper_forces(loop: Loop, conv: Conveyor) -> np.ndarray:
    """Belt cleaner resistance F_r = A p mu_3 (ISO 5048:1989) on the head or tail lumped
    element [N] (:func:`lumped_index`, where the lumped ``head_kn`` and ``tail_kn`` act)."""
    out = np.zeros(loop.n)
    for sc in conv.accessories.scrapers:
        out[lumped_index(loop, conv, sc.at)] += sc.contact_area_m2 * sc.pressure_n_m2 \
            * sc.friction
    return out


def plough_forces(loop: Loop, conv: Conveyor) -> np.ndarray:
    """Plough resistance F_a = B k_a (ISO 5048:1989) on the carry element at the plough [N]."""
    out = np.zeros(loop.n)
    for p in conv.accessories.ploughs:
        out[carry_element_at(loop, p.at_m)] += loop.belt.width_m * p.k_n_m
    return out


def add_feed(b: LawBuilder, loop: Loop, conv: Conveyor) -> None:
    """Force to accelerate the material at the feed, I_m (v - v0) [N] (DIN 22101, CEMA T_am).

    I_m = m'_L v_design is the mass flow [kg/s], with m'_L the material on the feed element
    (the first carry section's share of a load pattern); as a law term: I_m |v| - I_m v0 on
    the feed element, so in transients it scales with the belt speed.
    """
    if conv.material.feed is not None:
        _add_feed_points(b, loop, conv)
        return
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
