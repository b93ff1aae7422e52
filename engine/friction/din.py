"""DIN 22101 / ISO 5048 main and secondary resistances (model ``din``, alias ``iso5048``).

Notes
-----
Main resistance per idler element j (DIN 22101:2002 eq. for F_H, written per element):

    F_H,j = f g dx_j [m'_R + (m'_G + m'_L) cos(a_j)]                      [N]

with f = ``f_carry`` on the carry strand and ``f_return`` on the return strand. Secondary
resistances F_N follow from the coefficient C(L) with F_H + F_N = C F_H, so
F_N = (C - 1) sum F_H; they are placed at the pulleys (split evenly between the head and
tail pulley elements, and the take-up pulley when it is separate), where they act. For
L < 80 m DIN asks for explicit secondary resistances: the feed acceleration I_m (v - v0) on
the feed element, the friction F_f between the material and the skirt plates while it is
accelerated (:func:`acceleration_skirt_forces`, where a feed point has skirts) and pulley
allowances (CEMA T_p values, see ``common``). With the C factor the feed and F_f are part of
``secondary`` and the ``feed`` part is 0. Speed independent; ignores temperature.

References
----------
DIN 22101:2002-08 Continuous conveyors - Belt conveyors for loose bulk materials.
ISO 5048:1989 Continuous mechanical handling equipment - Belt conveyors with carrying idlers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from beltstudy.engine.conveyor import (
    SKIRT_WIDTH_SHARE,
    Conveyor,
    InputError,
)
from beltstudy.engine.friction.base import FrictionModel, param
from beltstudy.engine.friction.common import (
    add_accessories,
    add_feed,
    carry_element_at,
    lumped_indices,
    pulley_allowances,
)
from beltstudy.engine.law import LawBuilder, ResistanceLaw
from beltstudy.engine.loop import CARRY, RETURN, G, Loop

#: Coefficient C against conveyor length L [m] (DIN 22101 table as quoted in PHYSICS
#: section 2; *unverified*). Interpolated linearly; 1.03 from 5000 m on.
C_TABLE_L_M = np.array([80, 100, 150, 200, 300, 400, 500, 600, 800, 1000, 1500, 2000, 2500,
                        5000], dtype=float)
C_TABLE_C = np.array([1.92, 1.78, 1.58, 1.45, 1.31, 1.25, 1.20, 1.17, 1.12, 1.09, 1.06, 1.05,
                      1.04, 1.03])


def c_factor(length_m: float) -> float:
    """DIN 22101 coefficient C for a conveyor of length L [m] (L >= 80 m)."""
    return float(np.interp(length_m, C_TABLE_L_M, C_TABLE_C))



def acceleration_skirt_forces(loop: Loop, conv: Conveyor,
                              mu1: float | None = None) -> np.ndarray:
    """Friction between the material and the skirt plates in the acceleration zone, per
    element [N] (ISO 5048:1989 / DIN 22101 secondary resistance F_f).

    F_f = mu_2 I_V^2 rho g l_b / (((v + v_0) / 2)^2 b_1^2), with the acceleration length
    l_b = (v^2 - v_0^2) / (2 g mu_1), at most the skirts' length (no skirt plates, no F_f),
    on the element each feed point with skirts starts. I_V = m'_L v / rho is the volume flow
    on the belt there (the load case's; every feed upstream included), mu_2 the feed point's
    ``skirt_friction``, b_1 its ``skirt_width_m`` (default ``SKIRT_WIDTH_SHARE`` of the belt
    width), v_0 its along-belt loading speed (0 for one against the travel) and mu_1 its
    ``belt_friction`` unless ``mu1`` is given. ``I_V / ((v + v_0) / 2)`` is the material's
    cross-section in the zone, which sets its pressure on the skirts; at a feed point with
    feeds upstream only the flow fed there speeds up, the rest already runs at v, so the
    cross-section is ``I_V,up / v + I_V,here / ((v + v_0) / 2)`` (the feed's ``share`` of the
    shares fed up to it): a second feed of 0.3 on 0.7 already on the belt had its whole flow
    taken at the mean speed, 72.3 N of skirt friction where its material gives 30.6 N. The friction beyond l_b is the skirts' F_gL (:func:`beltstudy.engine.friction.common.skirt_forces`,
    an accessory).
    """
    out = np.zeros(loop.n)
    v = loop.speed_m_s
    rho = conv.material.density_t_m3 * 1e3
    for f in conv.material.feed or []:
        v0 = f.loading_speed_m_s
        if v0 is None:
            v0 = conv.material.loading_speed_m_s
        if f.skirt_length_m <= 0.0 or v0 >= v:
            continue
        # fed against the travel (v0 < 0) the belt first stops the material and then
        # accelerates it from rest: the formula (for 0 <= v0 < v; at v0 = -v its mean speed
        # (v + v0) / 2 is 0, a division by zero) is taken from rest, a lower bound (a note
        # says so: beltstudy.engine.checks.input_notes)
        v0 = max(v0, 0.0)
        j = carry_element_at(loop, f.at_m)
        iv = float(loop.mL_kg_m[j]) * v / rho  # [m3/s]
        b1 = f.skirt_width_m if f.skirt_width_m is not None \
            else SKIRT_WIDTH_SHARE * loop.belt.width_m
        m1 = f.belt_friction if mu1 is None else mu1
        lb = min((v * v - v0 * v0) / (2.0 * G * m1), f.skirt_length_m)
        # the share of the flow there that is fed there (the rest came from upstream at v)
        fed = sum(g.share for g in conv.material.feed if g.at_m <= f.at_m)
        here = f.share / fed if fed > 0.0 else 1.0
        area = iv * ((1.0 - here) / v + here / (0.5 * (v + v0)))  # [m2]
        out[j] += f.skirt_friction * rho * G * lb * area * area / (b1 * b1)
    return out


@dataclass(frozen=True)
class DinParams:
    """Parameters of the DIN 22101 model."""

    f_carry: float = param(0.020, "fictitious friction factor f, carry strand [-] (DIN 22101 "
                                  "default 0.020; Harrison's comparison uses 0.010)", hi=1.0)
    f_return: float = param(0.020, "fictitious friction factor f, return strand [-] (0.020; "
                                   "Harrison's comparison uses 0.008)", hi=1.0)
    c: float | None = param(None, "secondary resistance coefficient C override [-] (default "
                                  "from the DIN table by length; needs C >= 1)", hi=20.0)

    def check(self) -> None:
        for name in ("f_carry", "f_return"):
            f = getattr(self, name)
            # f = 1 is a resistance equal to the moving weight: far beyond the 0.010 to about
            # 0.04 of DIN 22101's table
            if not 0.0 <= f <= 1.0:
                raise InputError(f"models.din.{name}: a friction factor between 0 and 1 "
                                 f"(DIN 22101: 0.010 to about 0.04; got {f:g})")
        if self.c is not None and self.c < 1.0:
            raise InputError(f"models.din.c: C must be >= 1 (got {self.c})")


def build(loop: Loop, conv: Conveyor, temperature_c: float, params: DinParams) -> ResistanceLaw:
    """Per-element DIN 22101 resistance law [N] (temperature is ignored)."""
    b = LawBuilder(loop.n, loop.sag_w_n, hs_max=loop.sag_limit)
    mass = loop.mR_kg_m + (loop.mG_kg_m + loop.mL_kg_m) * loop.cos_a
    fh = G * loop.dx_m * mass
    carry = np.where(loop.strand == CARRY, params.f_carry * fh, 0.0)
    ret = np.where(loop.strand == RETURN, params.f_return * fh, 0.0)
    b.add("main_carry", carry)
    b.add("main_return", ret)
    fh_total = float(carry.sum() + ret.sum())
    c = params.c
    if c is None and loop.length_m < 80.0:
        add_feed(b, loop, conv)
        b.add("secondary", pulley_allowances(loop, conv) + acceleration_skirt_forces(loop, conv))
        c_used = None
    else:
        c_used = c if c is not None else c_factor(loop.length_m)
        idx = lumped_indices(loop, conv)
        sec = np.zeros(loop.n)
        sec[idx] = (c_used - 1.0) * fh_total / len(idx)
        b.add("secondary", sec)
    add_accessories(b, loop, conv)
    return b.build(info={"c_factor": c_used, "f_carry": params.f_carry,
                         "f_return": params.f_return})


MODEL = FrictionModel(
    name="din",
    description="DIN 22101 / ISO 5048: fictitious friction factor f per strand and the "
                "secondary-resistance coefficient C(L)",
    params_class=DinParams,
    build=build,
    temperature_term=False,
)
