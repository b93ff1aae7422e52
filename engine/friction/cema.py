"""CEMA 6th edition, classic method (model ``cema``).

Notes
-----
CEMA's effective tension, imperial form,

    Te = L Kt (Kx + Ky Wb + 0.015 Wb) + Wm (L Ky +- H) + Tp + Tam + Tac,

is written here in SI per element j of length dx:

    carry:   g [Kt (kx + Ky m'_G) + Ky m'_L] dx                               [N]
    return:  g Kt 0.015 m'_G dx                                               [N]
    kx = 0.00068 (m'_G + m'_L) + A_i / (g S)                                  [kg/m]

with A_i the idler drag per carry set [N] (catalogue seal drag, or ``ai_n``), S the carry
idler spacing, Kt the ambient temperature correction (table below) and Ky the carry
resistance factor. The lift Wm H comes from gravity (statics), Tam = I_m (v - v0) is the
``feed`` part, Tp the pulley allowances (200/150/100 lbf) are ``secondary`` and Tac the
accessories.

Ky: CEMA Table 6-2 is not available here. This model uses a documented smooth fit that falls
with conveyor length L log-linearly from 0.035 at 250 ft (76.2 m) to a floor of 0.016 at
3000 ft (914.4 m) and longer, and rises with the carried mass (m'_G + m'_L) and with the
carry idler spacing S:

    Ky = max(0.016, Ky_L(L) (m_tot / 100 kg/m)^0.15 (S / 1.2 m)^0.3)

The mass and spacing exponents are estimates shaped like the table's trends (heavier belts and
wider spacing sag more and flex more). ``ky`` overrides the fit.

References
----------
CEMA, Belt Conveyors for Bulk Materials, 6th ed., 2005, chapter 6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from beltstudy.engine.conveyor import Conveyor, InputError
from beltstudy.engine.friction.base import FrictionModel, param
from beltstudy.engine.friction.common import add_accessories, add_feed, pulley_allowances
from beltstudy.engine.law import LawBuilder, ResistanceLaw
from beltstudy.engine.loop import CARRY, RETURN, G, Loop

#: Kt against ambient temperature [C]: an *unverified* digitisation of CEMA's curve (PHYSICS
#: section 2); 1.00 at and above 0 C (one reading of the curve puts Kt = 1.0 at and above
#: 32 F; an older digitisation has 1.05 at +4 C). Interpolated linearly, held at the ends.
KT_TABLE_C = np.array([-40.0, -34.0, -29.0, -23.0, -18.0, -12.0, -7.0, -1.0, 0.0])
KT_TABLE = np.array([1.65, 1.55, 1.45, 1.35, 1.27, 1.20, 1.14, 1.03, 1.00])

KY_LONG = 0.016  # floor for L >= 3000 ft
KY_SHORT = 0.035  # at L = 250 ft
L_SHORT_M = 76.2
L_LONG_M = 914.4


def kt_factor(temperature_c: float) -> float:
    """CEMA ambient temperature correction factor Kt [-]."""
    return float(np.interp(temperature_c, KT_TABLE_C, KT_TABLE))


def kt_as_read(params, temperature_c: float) -> float:
    """The Kt a run of ``params`` at ``temperature_c`` [C] uses: the override, else the curve
    (what the CEMA laws read of the temperature)."""
    return float(params.kt) if params.kt is not None else kt_factor(temperature_c)


def kt_note(model: str, override: float | None, temperature_c: float, name: str = "kt") -> str:
    """The note of a run colder than CEMA's Kt table (-40 C) whose Kt is read from it: the
    table's coldest value is used. "" otherwise (and with ``override``, the run's own Kt)."""
    if override is not None or temperature_c >= KT_TABLE_C[0]:
        return ""
    return (f"note: CEMA's ambient temperature factor Kt is tabulated down to "
            f"{KT_TABLE_C[0]:g} C; {temperature_c:g} C uses its value there, {KT_TABLE[0]:g} "
            f"(models.{model}.{name} sets Kt for a colder site)")


def ky_length(length_m: float) -> float:
    """Length part of the Ky fit: 0.035 at 76.2 m falling log-linearly to 0.016 at 914.4 m."""
    if length_m <= L_SHORT_M:
        return KY_SHORT
    if length_m >= L_LONG_M:
        return KY_LONG
    frac = math.log(length_m / L_SHORT_M) / math.log(L_LONG_M / L_SHORT_M)
    return KY_SHORT + (KY_LONG - KY_SHORT) * frac


def ky_fit(length_m: float, mass_kg_m, spacing_m) -> np.ndarray:
    """Ky [-] from the documented fit (see module notes)."""
    m = np.maximum(np.asarray(mass_kg_m, dtype=float), 1.0)
    s = np.asarray(spacing_m, dtype=float)
    return np.maximum(KY_LONG, ky_length(length_m) * (m / 100.0) ** 0.15 * (s / 1.2) ** 0.3)


@dataclass(frozen=True)
class CemaParams:
    """Parameters of the classic CEMA model."""

    ky: float | None = param(None, "carry resistance factor Ky override [-] (default: the "
                                   "documented length/mass/spacing fit)", hi=1.0)
    kt: float | None = param(None, "ambient temperature factor Kt override [-] (default: "
                                   "CEMA curve at the run temperature)", hi=10.0)
    ai_n: float | None = param(None, "idler drag A_i per carry set [N] (default: the idler "
                                     "catalogue seal drag, CEMA 6.7 N for 6 in C/D)", hi=500.0)

    def check(self) -> None:
        for name in ("ky", "kt", "ai_n"):
            val = getattr(self, name)
            if val is not None and val < 0:
                raise InputError(f"models.cema.{name}: must be >= 0 (got {val})")


def build(loop: Loop, conv: Conveyor, temperature_c: float, params: CemaParams) -> ResistanceLaw:
    """Per-element CEMA resistance law [N]."""
    b = LawBuilder(loop.n, loop.sag_w_n, hs_max=loop.sag_limit)
    kt = params.kt if params.kt is not None else kt_factor(temperature_c)
    carry = loop.strand == CARRY
    ret = loop.strand == RETURN
    spacing = np.where(carry, loop.spacing_m, 1.0)
    ai = np.where(carry, loop.seal_drag_n if params.ai_n is None else params.ai_n, 0.0)
    mG, mL = loop.mG_kg_m, loop.mL_kg_m
    if params.ky is not None:
        ky = np.full(loop.n, params.ky)
    else:
        ky = ky_fit(loop.length_m, mG + mL, spacing)
    kx = 0.00068 * (mG + mL) + ai / (G * spacing)
    main_carry = np.where(carry, G * (kt * (kx + ky * mG) + ky * mL) * loop.dx_m, 0.0)
    main_return = np.where(ret, G * kt * 0.015 * mG * loop.dx_m, 0.0)
    b.add("main_carry", main_carry)
    b.add("main_return", main_return)
    add_feed(b, loop, conv)
    b.add("secondary", pulley_allowances(loop, conv))
    add_accessories(b, loop, conv)
    return b.build(info={"kt": kt, "ky_mean": float(ky[carry].mean()) if carry.any() else None,
                         "ai_n": float(ai[carry].mean()) if carry.any() else None})


MODEL = FrictionModel(
    name="cema",
    description="CEMA 6th edition classic: Kt (Kx + Ky Wb + 0.015 Wb) + Wm Ky, Ky from a "
                "documented fit",
    params_class=CemaParams,
    build=build,
    temperature_read=kt_as_read,
    range_note=lambda p, t: kt_note("cema", p.kt, t),
)
