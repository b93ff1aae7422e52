"""Viscoelastic model with constant flexure allowances (model ``visco``, the paper's ViscoAH).

Notes
-----
Per belt element j of length dx, in [N]:

    idler rotation  g Kta Ks dx + A_i e^{-c (T - T_r)} / S dx     (Kta: CEMA's Kt)
    indentation     (sum over the rolls of F_ir) / S dx,
                    F_ir = kappa tan(delta) F_v^{4/3} h^{1/3} / (b^{1/3} E'^{1/3} D^{2/3})
    belt flexure    g m* Kta (m'_G + m'_L) cos(a) (h_d / h_ref)^n dx
    material flex.  g (p + q v) (1.66 S_c / S_r)^s (m'_L / m_ref) (h_d / h_ref)^{n_m} dx   (carry)

The indentation is the same per-roll Winkler law as ``nonlin``, but tan(delta) and E' are taken
at a fixed reference frequency (``frequency_hz``, the frequency of a standard dynamic test)
at the ambient temperature, not at the running contact frequency. The idler drag is the
conveyor's seal drag A_i (the idler catalogue's CEMA value when the file gives none),
independent of speed, with the same temperature law as ``nonlin``: its own e^{-c (T - T_r)}
and not Kta as well (the cold counted once). Belt and material flexure
are constant allowances: the Non-Lin expressions evaluated at a fixed design sag h_d, by
default the conveyor's admissible sag of each strand (``sag_limit_pct``), which is the sag a
design without tension coupling has to assume. There is no sag coupling, so the law does not
depend on tension and the steady solve is a single pass.

References
----------
Harrison, A.: A hybrid model for numerical belt conveyor simulation. bulk solids handling 28
(2008) No. 4 (ViscoAH in the Fig. 2 comparison; CEMA and ViscoAH over-estimate the power).
Jonkers, C.O.: The indentation rolling resistance of belt conveyors. Fördern und Heben 30
(1980) No. 4.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from beltstudy.engine import rubber
from beltstudy.engine.conveyor import Conveyor, InputError
from beltstudy.engine.friction.base import FrictionModel, param
from beltstudy.engine.friction.cema import kt_factor
from beltstudy.engine.friction.common import add_accessories, add_feed, pulley_allowances
from beltstudy.engine.friction.nonlin import (
    NonlinParams,
    bearing_term_n,
    idler_drag_n,
    indentation_per_set,
    roll_loads,
    spacing_ratio,
)
from beltstudy.engine.law import HS_REF, LawBuilder, ResistanceLaw
from beltstudy.engine.loop import CARRY, RETURN, G, Loop

__all__ = ["ViscoParams", "build", "MODEL"]


_NONLIN_FIELDS = {f.name: f for f in dataclasses.fields(NonlinParams)}


def _as_nonlin(name: str):
    """The Non-Lin parameter ``name``: its default and meaning, defined once in
    :class:`~beltstudy.engine.friction.nonlin.NonlinParams`."""
    f = _NONLIN_FIELDS[name]
    return param(f.default, f"{f.metadata['doc']} (as nonlin)", hi=f.metadata.get("hi"))


@dataclass(frozen=True)
class ViscoParams:
    """Parameters of the viscoelastic model (units in brackets); the ones it shares with
    Non-Lin take their default and meaning from :class:`NonlinParams`."""

    frequency_hz: float = param(
        10.0, "reference frequency of tan(delta) and E' [Hz] (10 Hz, the usual frequency of "
              "dynamic mechanical tests of cover rubber)", hi=10000.0)
    kappa_ir: float = _as_nonlin("kappa_ir")
    centre_share: float = _as_nonlin("centre_share")
    kta: float | None = _as_nonlin("kta")
    mu_b: float = _as_nonlin("mu_b")
    bearing_diameter_m: float = _as_nonlin("bearing_diameter_m")
    drag_per_set_n: float | None = param(
        None, "idler drag A_i per set [N] (default: the conveyor's seal_drag_n, from the "
              "idler catalogue's CEMA A_i when the file gives none)", hi=500.0)
    drag_temp_coef: float = _as_nonlin("drag_temp_coef")
    drag_ref_temp_c: float = _as_nonlin("drag_ref_temp_c")
    m_star: float = _as_nonlin("m_star")
    bf_sag_exp: float = _as_nonlin("bf_sag_exp")
    p_mf: float = _as_nonlin("p_mf")
    q_mf: float = _as_nonlin("q_mf")
    s_mf: float = _as_nonlin("s_mf")
    mf_ref_load_kg_m: float = _as_nonlin("mf_ref_load_kg_m")
    mf_sag_exp: float = _as_nonlin("mf_sag_exp")
    sag_carry_pct: float | None = param(
        None, "design sag h_d of the carry strand for the flexure allowances [%] (default: "
              "the conveyor's sag_limit_pct.carry)", hi=50.0)
    sag_return_pct: float | None = param(
        None, "design sag h_d of the return strand [%] (default: sag_limit_pct.return)", hi=50.0)

    def check(self) -> None:
        for name in ("frequency_hz", "mf_ref_load_kg_m"):
            if getattr(self, name) <= 0:
                raise InputError(f"models.visco.{name}: must be > 0 (got {getattr(self, name)})")
        for name in ("kappa_ir", "mu_b", "bearing_diameter_m", "drag_temp_coef",
                     "m_star", "bf_sag_exp", "p_mf", "q_mf", "s_mf", "mf_sag_exp"):
            if getattr(self, name) < 0:
                raise InputError(f"models.visco.{name}: must be >= 0 (got {getattr(self, name)})")
        if not 0.0 <= self.centre_share <= 1.0:
            raise InputError("models.visco.centre_share: must be in 0..1")
        for name in ("kta", "drag_per_set_n"):
            val = getattr(self, name)
            if val is not None and val < 0:
                raise InputError(f"models.visco.{name}: must be >= 0 (got {val})")
        for name in ("sag_carry_pct", "sag_return_pct"):
            val = getattr(self, name)
            if val is not None and val <= 0:
                raise InputError(f"models.visco.{name}: must be > 0 (got {val})")


def build(loop: Loop, conv: Conveyor, temperature_c: float, params: ViscoParams) -> ResistanceLaw:
    """Per-element ViscoAH resistance law [N] (module notes); tension independent.

    Parameters
    ----------
    loop : Loop
    conv : Conveyor
    temperature_c : float
        Ambient temperature [C].
    params : ViscoParams

    Returns
    -------
    ResistanceLaw
        Terms ``idler_rotation``, ``indentation``, ``belt_flexure``, ``material_flexure``,
        ``feed``, ``secondary``, ``accessories``.
    """
    p = params
    b = LawBuilder(loop.n, loop.sag_w_n, hs_max=loop.sag_limit)
    idl = loop.is_idler
    carry = loop.strand == CARRY
    ret = loop.strand == RETURN
    spacing = np.where(idl, loop.spacing_m, 1.0)
    dx = loop.dx_m
    kta = p.kta if p.kta is not None else kt_factor(temperature_c)

    b.add("idler_rotation", bearing_term_n(loop, p.mu_b, p.bearing_diameter_m, kta))
    temp = math.exp(-p.drag_temp_coef * (temperature_c - p.drag_ref_temp_c))
    drag = idler_drag_n(loop, conv, p.drag_per_set_n, None)
    # the seal drag carries its own temperature law e^{-c (T - T_r)}, not Kta as well
    b.add("idler_rotation", drag * temp / spacing * dx)

    comp = rubber.compound(loop.belt.compound)
    tan, e_st = rubber.loss_and_modulus(temperature_c, p.frequency_hz, comp)
    tan, e_st = float(tan), float(e_st)
    loads, width = roll_loads(loop, p.centre_share)
    per_set = indentation_per_set(loads, width, loop.roll_diameter_m,
                                  loop.belt.bottom_cover_mm * 1e-3, tan, e_st, p.kappa_ir)
    b.add("indentation", np.where(idl, per_set / spacing * dx, 0.0))

    hc = (p.sag_carry_pct if p.sag_carry_pct is not None else conv.sag_limit_pct.carry) / 100
    hr = (p.sag_return_pct if p.sag_return_pct is not None else conv.sag_limit_pct.return_) / 100
    phi = np.where(carry, hc, np.where(ret, hr, 0.0)) / HS_REF
    bf = G * p.m_star * kta * (loop.mG_kg_m + loop.mL_kg_m) * loop.cos_a * dx
    b.add("belt_flexure", np.where(idl, bf * phi ** p.bf_sag_exp, 0.0))
    mf = np.where(carry, G * dx * spacing_ratio(conv) ** p.s_mf * loop.mL_kg_m
                  / p.mf_ref_load_kg_m * phi ** p.mf_sag_exp, 0.0)
    b.add("material_flexure", p.p_mf * mf)  # zero coefficients when empty: same parts
    b.add("material_flexure", p.q_mf * mf, pv=1.0)

    add_feed(b, loop, conv)
    b.add("secondary", pulley_allowances(loop, conv))
    add_accessories(b, loop, conv)
    return b.build(info={"tan_delta": tan, "e_storage_mpa": e_st / 1e6,
                         "frequency_hz": p.frequency_hz, "drag_temperature_factor": temp,
                         "design_sag_carry": hc, "design_sag_return": hr, "compound": comp.id,
                         "kta": kta})


MODEL = FrictionModel(
    name="visco",
    description="ViscoAH: rubber indentation at a fixed test frequency, idler drag and constant "
                "flexure allowances at the design sag (no sag coupling)",
    params_class=ViscoParams,
    build=build,
)
