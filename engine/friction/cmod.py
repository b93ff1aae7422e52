"""Modified CEMA: Ky evaluated per element from the local sag (model ``cmod``).

Notes
-----
CEMA's classic method (``cema``) takes one carry factor Ky for the whole conveyor. For long
belts CEMA advises evaluating Ky section by section from the local belt tension and idler
pitch: a tight span sags little and flexes the belt and the load less. Here Ky_j at element j
follows the local sag ratio h/S = g (m'_G + m'_L) cos(a) S / (8 T):

    Ky_j = Ky [(1 - w) + w ((h/S)_j / h_c)^k]

with Ky the classic value (the documented fit of ``cema``, or ``ky``), h_c the sag the
classic Ky stands for (``ky_sag_ref_pct``), w the share of Ky that is sag-driven flexure
(``ky_sag_share``; the rest, indentation and other losses, does not depend on the sag) and k
the sag exponent. The carry resistance per element is CEMA's, with Ky_j:

    carry:   g [Kt (kx + Ky_j m'_G) + Ky_j m'_L] dx                            [N]
    return:  g Kt 0.015 m'_G dx                                                [N]

w, h_c and k are estimates (CEMA's tension-dependent Ky table is not available here): half of
Ky sag-driven, at 2 % sag (the sag usually allowed when idler spacing is chosen by CEMA's
table), linear in the sag. Because Ky_j depends on the local tension the steady solution is a
fixed point, iterated like ``nonlin``.

References
----------
CEMA, Belt Conveyors for Bulk Materials, 6th ed., 2005, chapter 6.
Harrison, A.: A hybrid model for numerical belt conveyor simulation. bulk solids handling 28
(2008) No. 4 (CMod in the Fig. 2 comparison).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from beltstudy.engine.conveyor import Conveyor, InputError
from beltstudy.engine.friction.base import FrictionModel, param
from beltstudy.engine.friction.cema import kt_as_read, kt_factor, kt_note, ky_fit
from beltstudy.engine.friction.common import add_accessories, add_feed, pulley_allowances
from beltstudy.engine.law import HS_REF, LawBuilder, ResistanceLaw
from beltstudy.engine.loop import CARRY, RETURN, G, Loop

__all__ = ["CmodParams", "build", "MODEL"]


@dataclass(frozen=True)
class CmodParams:
    """Parameters of the modified CEMA model."""

    ky: float | None = param(None, "classic carry factor Ky override [-] (default: the "
                                   "documented fit of the cema model)", hi=1.0)
    kt: float | None = param(None, "ambient temperature factor Kt override [-] (default: "
                                   "CEMA curve at the run temperature)", hi=10.0)
    ai_n: float | None = param(None, "idler drag A_i per carry set [N] (default: the "
                                     "conveyor's seal_drag_n / idler catalogue)", hi=500.0)
    ky_sag_share: float = param(
        0.5, "share w of Ky that is sag-driven belt and material flexure [-] (estimate: "
             "flexure and indentation about equal in CEMA's Ky)")
    ky_sag_ref_pct: float = param(
        2.0, "sag h_c the classic Ky stands for [%] (estimate: the sag usually allowed with "
             "CEMA's idler spacing table)", hi=50.0)
    ky_sag_exp: float = param(1.0, "sag exponent k of the sag-driven part [-] (estimate)", hi=10.0)

    def check(self) -> None:
        for name in ("ky", "kt", "ai_n"):
            val = getattr(self, name)
            if val is not None and val < 0:
                raise InputError(f"models.cmod.{name}: must be >= 0 (got {val})")
        if not 0.0 <= self.ky_sag_share <= 1.0:
            raise InputError(f"models.cmod.ky_sag_share: must be in 0..1 "
                             f"(got {self.ky_sag_share})")
        if self.ky_sag_ref_pct <= 0:
            raise InputError("models.cmod.ky_sag_ref_pct: must be > 0")
        if self.ky_sag_exp < 0:
            raise InputError("models.cmod.ky_sag_exp: must be >= 0")


def build(loop: Loop, conv: Conveyor, temperature_c: float, params: CmodParams) -> ResistanceLaw:
    """Per-element modified CEMA resistance law [N] (module notes).

    Parameters
    ----------
    loop : Loop
    conv : Conveyor
    temperature_c : float
        Ambient temperature [C] (CEMA Kt).
    params : CmodParams

    Returns
    -------
    ResistanceLaw
        Terms ``main_carry`` (a constant and a sag-dependent part), ``main_return``,
        ``feed``, ``secondary``, ``accessories``.
    """
    p = params
    b = LawBuilder(loop.n, loop.sag_w_n, hs_max=loop.sag_limit)
    kt = p.kt if p.kt is not None else kt_factor(temperature_c)
    carry = loop.strand == CARRY
    ret = loop.strand == RETURN
    spacing = np.where(carry, loop.spacing_m, 1.0)
    ai = np.where(carry, loop.seal_drag_n if p.ai_n is None else p.ai_n, 0.0)
    mG, mL = loop.mG_kg_m, loop.mL_kg_m
    ky = np.full(loop.n, p.ky) if p.ky is not None else ky_fit(loop.length_m, mG + mL, spacing)
    kx = 0.00068 * (mG + mL) + ai / (G * spacing)
    w = p.ky_sag_share
    ky_mass = G * (kt * mG + mL) * loop.dx_m  # multiplies Ky_j
    fixed = G * kt * kx * loop.dx_m + (1.0 - w) * ky * ky_mass
    # the sag part at the law's reference sag h_ref: w Ky (h_ref / h_c)^k, times phi^k
    sag_coef = w * ky * (HS_REF / (p.ky_sag_ref_pct / 100.0)) ** p.ky_sag_exp * ky_mass
    b.add("main_carry", np.where(carry, fixed, 0.0))
    b.add("main_carry", np.where(carry, sag_coef, 0.0), ps=p.ky_sag_exp)
    b.add("main_return", np.where(ret, G * kt * 0.015 * mG * loop.dx_m, 0.0))
    add_feed(b, loop, conv)
    b.add("secondary", pulley_allowances(loop, conv))
    add_accessories(b, loop, conv)
    return b.build(info={"kt": kt, "ky_mean": float(ky[carry].mean()) if carry.any() else None,
                         "ai_n": float(ai[carry].mean()) if carry.any() else None})


MODEL = FrictionModel(
    name="cmod",
    description="Modified CEMA: Ky per element from the local sag (tension), iterated",
    params_class=CmodParams,
    build=build,
    temperature_read=kt_as_read,
    range_note=lambda p, t: kt_note("cmod", p.kt, t),
)
