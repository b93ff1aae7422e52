"""Harrison's hybrid Non-Lin model, the paper's Eq. (1) term by term (model ``nonlin``).

Notes
-----
Per belt element j of length dx (Harrison 2008, Eq. 1; PHYSICS section 2):

    dF_j = dx g [R + (BI + BF) + MF + V] + Q v (feed) + P + O

with every bracketed term in [kg/m]:

* Idler rotation, R = Kta Ks + A_z (v / v_r)^b e^{-c (T - T_r)} / S: Ks = mu_b (d_b / D)
  (m'_G + m'_L) cos(a) the load-dependent bearing part, A_z = A_i / g the seal drag of an idler
  set [kg] (the conveyor file's ``seal_drag_n`` when given, else ``drag_per_roll_n`` x rolls;
  the idler catalogue's CEMA A_i is a design allowance of CEMA's method and is not used), S the
  idler spacing. The paper writes (v / 2)^b e^{-c T}: the drag A_z is referred to v_r = 2 m/s
  and T_r = 0 C. Kta is read as CEMA's ambient temperature factor Kt (1 from 0 C up): in
  Eq. 1 it multiplies idler rotation and belt flexure, the terms CEMA's Kt multiplies
  (L Kt (Kx + Ky Wb + 0.015 Wb)); the material terms and the indentation (with its own
  tan(delta)(T)) carry no Kta. The seal drag has its own temperature law in Eq. 1,
  e^{-c T} (c ~ 0.017 /C: the drag doubles between +20 and -20 C), so Kta is not applied to
  it a second time: one temperature law per term (engine 0.3; before, the cold counted twice
  on the seal drag, 2.45 x at -30 C against 0 C instead of the paper's e^{0.017 x 30} = 1.66).
* Indentation, BI = (sum over the rolls of a set of F_ir) / (g S), per roll the Winkler-layer
  law of Jonkers, F_ir = kappa tan(delta) F_v^{4/3} h^{1/3} / (b^{1/3} E'^{1/3} D^{2/3}), with
  F_v the roll's share of the set load g (m'_G + m'_L) cos(a) S, h the bottom cover, b the
  belt width on the roll (width / rolls), D the roll diameter and tan(delta), E' of the
  compound at the contact frequency f = v / l_c and the ambient temperature
  (:mod:`beltstudy.engine.rubber`). Per metre of belt BI grows as S^{1/3}, not as the S^{4/3} that the
  paper's printed form suggests. Speed enters through tan(delta) and E' at f = v / l_c; in
  the law it is the local power v^e, e = d ln(tan(delta) E'^{-1/3}) / d ln f at the design
  speed (the paper's v^e).
  kappa: for a Winkler layer of modulus E' with a viscous loss, a roll of radius R = D / 2
  indents the cover over a contact 2a, a^3 = 3 R F_v h / (2 b E'), with a parabolic strain
  pulse; its dissipation per metre rolled, with the viscosity taken from tan(delta) at the
  pulse's frequency (the pulse read as half a sine period, f = v / (4a)), gives
  kappa = (4 / (3 pi)) (3/2)^{4/3} 2^{2/3} = 1.16 (reading it as a whole period gives half).
  The compound is read at PHYSICS's f = v / l_c; the factor 2 in frequency against v / (4a)
  changes tan(delta) E'^{-1/3} by about 3 % at 20 C. The paper's f(d) = k1 d + k2 is replaced
  by the law's D^{2/3}.
* Belt flexure, BF = m* Kta (m'_G + m'_L) cos(a) (h/S / h_ref)^n, h/S = g (m'_G + m'_L) cos(a)
  S / (8 T) the local sag ratio, h_ref = 1 %, n = 3/2.
* Material flexure (carry strand), MF = (p + q v) (1.66 S_c / S_r)^s (m'_L / m_ref)
  (h/S / h_ref)^{n_m}, scaled by the load (m_ref: the line load the paper's p + q v stands for).
* V = m' H / L, the lift: gravity, computed by statics; Q v the feed acceleration
  (``feed``), P the pulleys (CEMA T_p allowances, ``secondary``), O the accessories.

Design choice of this project: the paper prints BF and MF without tension. Here both grow
with the local sag, so with 1/T (a slack span flexes the belt and churns the load more), which
makes the steady solution a fixed point and gives the transient kernel the same tension
dependence. The paper leaves the constants proprietary; every one is a parameter below with a
default inside the paper's stated ranges (0.003 < m* < 0.008, n = 3/2, 0.2 < p < 3,
0.02 < q < 0.6, 1 < s < 3, b 0.3-0.5, c ~ 0.017 /C, mu_b ~ 0.0015).

Law terms (``beltstudy.engine.law``; coef [N] per element, speed exponent pv, sag exponent ps):
``idler_rotation`` (bearing: pv 0; drag: pv b), ``indentation`` (pv e), ``belt_flexure``
(ps n), ``material_flexure`` (p: pv 0, q: pv 1, both ps n_m), ``feed``, ``secondary``,
``accessories``.

References
----------
Harrison, A.: A hybrid model for numerical belt conveyor simulation. bulk solids handling 28
(2008) No. 4, pp. 240-245, Eq. (1).
Jonkers, C.O.: The indentation rolling resistance of belt conveyors. Fördern und Heben 30
(1980) No. 4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from beltstudy.engine import rubber
from beltstudy.engine.conveyor import Conveyor, InputError
from beltstudy.engine.friction.base import FrictionModel, param
from beltstudy.engine.friction.cema import kt_factor, kt_note
from beltstudy.engine.friction.common import add_accessories, add_feed, pulley_allowances
from beltstudy.engine.law import HS_REF, LawBuilder, ResistanceLaw
from beltstudy.engine.loop import CARRY, RETURN, G, Loop

__all__ = ["NonlinParams", "build", "roll_loads", "indentation_per_set", "MODEL"]


@dataclass(frozen=True)
class NonlinParams:
    """Parameters of the Non-Lin model (every constant of Eq. 1; units in brackets)."""

    kta: float | None = param(
        None, "Kta [-], the paper's factor on idler rotation R and belt flexure BF (default: "
              "CEMA's ambient temperature factor Kt at the run temperature, 1 at 0 C and "
              "above, 1.45 at -29 C; Kta multiplies the terms CEMA's Kt multiplies, the "
              "bearing part of idler friction and belt flexure; the seal drag has its own "
              "law e^(-c T))", hi=10.0)
    mu_b: float = param(
        0.0015, "bearing friction coefficient mu_b [-] (deep-groove ball bearings, about "
                "0.0015; PHYSICS section 2)", hi=0.1)
    bearing_diameter_m: float = param(
        0.045, "mean bearing diameter d_b [m] (6305/6306 bearings of 133-159 mm rolls, pitch "
               "about 45 mm; estimate); Ks = mu_b d_b / D (m'_G + m'_L)", hi=0.5)
    drag_per_roll_n: float | None = param(
        1.0, "seal drag of one roll at v_r and T_r [N], used where the conveyor file gives no "
             "seal_drag_n: A_z = rolls x this / g. 1.0 N is typical of the running drag of "
             "sealed 127-159 mm rolls (estimate); the catalogue's CEMA A_i (6.7 N a set) is a "
             "design allowance of CEMA's method, which the paper finds too high (None: use "
             "the catalogue value)", hi=500.0)
    drag_per_set_n: float | None = param(
        None, "seal drag A_i of one idler set at v_r and T_r [N], overriding both the file "
              "and drag_per_roll_n", hi=500.0)
    seal_drag_factor: float = param(
        1.0, "factor on the seal drag A_z of every idler set [-] (1: the drag as the file, "
             "drag_per_roll_n or drag_per_set_n gives it); a plant's seals differ from the "
             "catalogue's by tens of percent, which a sampled study (SPEC 7.2) draws", hi=100.0)
    drag_speed_exp: float = param(
        0.3, "seal drag speed exponent b [-] (paper range 0.3-0.5; 0.3, the lower end: grease "
             "seals whose drag grows weakly with speed)", hi=5.0)
    drag_ref_speed_m_s: float = param(
        2.0, "reference speed v_r of the seal drag [m/s] (the paper's (v / 2)^b)", hi=30.0)
    drag_temp_coef: float = param(
        0.017, "seal drag temperature coefficient c [1/C] (paper: c ~ 0.017, the drag doubles "
               "between +20 and -20 C)", hi=1.0)
    drag_ref_temp_c: float = param(
        0.0, "reference temperature T_r of the seal drag [C] (the paper's e^{-c T}: 0 C; the "
             "drag values of the file or drag_per_roll_n are read as the drag at 0 C)", hi=80.0)
    kappa_ir: float = param(
        1.16, "indentation constant kappa [-] of the per-roll Winkler law (the paper's d); "
              "1.16 = (4 / (3 pi)) (3/2)^(4/3) 2^(2/3): a Winkler layer of viscous loss "
              "tan(delta), the parabolic strain pulse over the contact 2a read as half a sine "
              "period (module notes; as a whole period: 0.58)", hi=100.0)
    contact_length_m: float = param(
        0.03, "contact length l_c of cover and roll [m] setting the loading frequency "
              "f = v / l_c (PHYSICS section 3: 20-40 mm)", hi=1.0)
    centre_share: float = param(
        0.65, "share of the material load on the centre roll of a three-roll set [-] (wings "
              "carry the rest equally; about 0.65 for 30-45 deg troughs; estimate)")
    indentation_speed_exp: float | None = param(
        None, "speed exponent e of BI [-] (default: derived from the rubber model, "
              "d ln(tan(delta) E'^(-1/3)) / d ln f at the design speed)", hi=5.0)
    m_star: float = param(
        0.0035, "belt flexure constant m* [-] (paper range 0.003-0.008): BF = m* Kta (m'_G + "
                "m'_L) at 1 % sag; 0.0035, low in the range, for steel-cord belts, which bend "
                "little between idlers", hi=1.0)
    bf_sag_exp: float = param(
        1.5, "belt flexure sag exponent n [-] (paper: n = 3/2)", hi=10.0)
    p_mf: float = param(
        0.4, "material flexure constant p [kg/m] (paper range 0.2-3), at the reference sag and "
             "line load m_ref", hi=100.0)
    q_mf: float = param(
        0.08, "material flexure speed constant q [kg s/m2] (paper range 0.02-0.6)", hi=100.0)
    s_mf: float = param(
        1.5, "material flexure spacing exponent s [-] (paper range 1-3) on 1.66 S_c / S_r", hi=10.0)
    mf_ref_load_kg_m: float = param(
        100.0, "line load m_ref [kg/m] that p + q v stands for (MF scales with m'_L / m_ref; "
               "estimate: the load of the paper's example belts)", hi=100000.0)
    mf_sag_exp: float = param(
        1.0, "material flexure sag exponent [-] (1: the bulk's flexing energy per span grows "
             "in proportion to the sag ratio; estimate)", hi=10.0)

    def check(self) -> None:
        for name in ("mu_b", "bearing_diameter_m", "seal_drag_factor", "drag_speed_exp",
                     "drag_temp_coef",
                     "kappa_ir", "m_star", "bf_sag_exp", "p_mf", "q_mf", "s_mf",
                     "mf_sag_exp"):
            if getattr(self, name) < 0:
                raise InputError(f"models.nonlin.{name}: must be >= 0 (got {getattr(self, name)})")
        for name in ("drag_ref_speed_m_s", "contact_length_m", "mf_ref_load_kg_m"):
            if getattr(self, name) <= 0:
                raise InputError(f"models.nonlin.{name}: must be > 0 (got {getattr(self, name)})")
        if not 0.0 <= self.centre_share <= 1.0:
            raise InputError(f"models.nonlin.centre_share: must be in 0..1 "
                             f"(got {self.centre_share})")
        for name in ("kta", "drag_per_set_n", "drag_per_roll_n"):
            val = getattr(self, name)
            if val is not None and val < 0:
                raise InputError(f"models.nonlin.{name}: must be >= 0 (got {val})")


# ---------------------------------------------------------------------------------------------
# Pieces shared with ``visco``


def roll_loads(loop: Loop, centre_share: float) -> tuple[np.ndarray, np.ndarray]:
    """Vertical load on each roll of the idler set of every element [N] and its contact width.

    Parameters
    ----------
    loop : Loop
    centre_share : float
        Share of the material load on the centre roll of a three-roll set [-].

    Returns
    -------
    loads : ndarray (n, 5)
        Roll loads F_v [N] (unused roll slots 0; pulley elements all 0).
    width : ndarray (n,)
        Belt width on one roll b = B / rolls [m] (inf on pulleys).

    Notes
    -----
    The set carries g (m'_G + m'_L) cos(a) S. The belt's own weight is shared equally by the
    rolls (each carries B / rolls of the width); the material load too, except on three-roll
    sets, where the centre roll takes ``centre_share`` and each wing half of the rest.
    """
    n = loop.n
    rolls = loop.rolls.astype(int)
    spacing = np.where(np.isfinite(loop.spacing_m), loop.spacing_m, 0.0)
    w_belt = G * loop.mG_kg_m * loop.cos_a * spacing
    w_mat = G * loop.mL_kg_m * loop.cos_a * spacing
    loads = np.zeros((n, 5))
    for k in range(1, 6):
        sel = rolls == k
        if not sel.any():
            continue
        if k == 3:
            loads[sel, 0] = w_belt[sel] / 3 + centre_share * w_mat[sel]
            loads[sel, 1] = w_belt[sel] / 3 + 0.5 * (1 - centre_share) * w_mat[sel]
            loads[sel, 2] = loads[sel, 1]
        else:
            loads[sel, :k] = ((w_belt[sel] + w_mat[sel]) / k)[:, None]
    width = np.where(rolls > 0, loop.belt.width_m / np.maximum(rolls, 1), np.inf)
    return loads, width


def indentation_per_set(loads: np.ndarray, width_m: np.ndarray, roll_diameter_m: np.ndarray,
                        cover_m: float, tan_delta: float, e_storage_pa: float,
                        kappa: float) -> np.ndarray:
    """Indentation rolling resistance of one idler set [N], summed over its rolls.

    Parameters
    ----------
    loads : ndarray (n, rolls)
        Vertical load on each roll F_v [N].
    width_m : ndarray (n,)
        Belt width on one roll b [m].
    roll_diameter_m : ndarray (n,)
        Roll diameter D [m] (0 on pulleys: no resistance).
    cover_m : float
        Bottom cover thickness h [m].
    tan_delta : float
        Loss factor of the cover [-].
    e_storage_pa : float
        Storage modulus E' of the cover [Pa].
    kappa : float
        Constant of the Winkler-layer law [-].

    Notes
    -----
    F_ir = kappa tan(delta) F_v^{4/3} h^{1/3} / (b^{1/3} E'^{1/3} D^{2/3}) per roll (Jonkers
    1980; PHYSICS section 2).
    """
    d = np.asarray(roll_diameter_m, dtype=float)
    ok = d > 0
    geo = np.zeros_like(d)
    geo[ok] = cover_m ** (1 / 3) / (width_m[ok] ** (1 / 3) * d[ok] ** (2 / 3))
    s43 = (np.maximum(loads, 0.0) ** (4.0 / 3.0)).sum(axis=1)
    return kappa * tan_delta * s43 * geo / e_storage_pa ** (1 / 3)


def indentation_factor(temperature_c: float, frequency_hz, compound) -> np.ndarray:
    """tan(delta) E'^(-1/3) [Pa^(-1/3)], the compound's part of the indentation law."""
    tan, e = rubber.loss_and_modulus(temperature_c, frequency_hz, compound)
    return tan / np.cbrt(e)


def speed_exponent(temperature_c: float, frequency_hz: float, compound) -> float:
    """Local exponent e = d ln(tan(delta) E'^(-1/3)) / d ln f [-], clipped to 0..1."""
    f1, f2 = frequency_hz / 1.1, frequency_hz * 1.1
    k1 = float(indentation_factor(temperature_c, f1, compound))
    k2 = float(indentation_factor(temperature_c, f2, compound))
    return float(np.clip(math.log(k2 / k1) / math.log(f2 / f1), 0.0, 1.0))


def idler_drag_n(loop: Loop, conv: Conveyor, drag_per_set_n: float | None,
                 drag_per_roll_n: float | None) -> np.ndarray:
    """Seal drag A_i per idler set of every element [N] (0 on pulleys).

    Precedence: ``drag_per_set_n`` when given; else the conveyor file's ``seal_drag_n`` of
    the strand when the file gives it; else ``drag_per_roll_n`` x rolls when given; else the
    loop's value (the idler catalogue).
    """
    idl = loop.is_idler
    if drag_per_set_n is not None:
        return np.where(idl, drag_per_set_n, 0.0)
    out = np.where(idl, loop.seal_drag_n, 0.0)
    if drag_per_roll_n is None:
        return out
    for strand, spec in ((CARRY, conv.idlers.carry), (RETURN, conv.idlers.return_)):
        if spec.seal_drag_n is None:
            sel = loop.strand == strand
            out[sel] = drag_per_roll_n * loop.rolls[sel]
    return out


def bearing_term_n(loop: Loop, mu_b: float, d_b: float, kta: float) -> np.ndarray:
    """Load-dependent bearing part g Kta Ks dx [N] per element."""
    idl = loop.is_idler
    d = np.where(idl & (loop.roll_diameter_m > 0), loop.roll_diameter_m, np.inf)
    ks = mu_b * d_b / d * (loop.mG_kg_m + loop.mL_kg_m) * loop.cos_a  # [kg/m]
    return np.where(idl, G * kta * ks * loop.dx_m, 0.0)


def spacing_ratio(conv: Conveyor) -> float:
    """1.66 S_c / S_r, the paper's spacing factor of material flexure [-]."""
    return 1.66 * conv.idler_spacing_m("carry") / conv.idler_spacing_m("return")


# ---------------------------------------------------------------------------------------------


def build(loop: Loop, conv: Conveyor, temperature_c: float, params: NonlinParams) -> ResistanceLaw:
    """Per-element Non-Lin resistance law [N] (see the module notes for the equations).

    Parameters
    ----------
    loop : Loop
    conv : Conveyor
    temperature_c : float
        Ambient temperature T [C] (cover rubber and seal drag).
    params : NonlinParams

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
    v = loop.speed_m_s
    kta = p.kta if p.kta is not None else kt_factor(temperature_c)
    spacing = np.where(idl, loop.spacing_m, 1.0)
    dx = loop.dx_m

    # R: idler rotation = Kta x bearing part + seal drag (v / v_r)^b e^{-c (T - T_r)} / S
    b.add("idler_rotation", bearing_term_n(loop, p.mu_b, p.bearing_diameter_m, kta))
    drag = idler_drag_n(loop, conv, p.drag_per_set_n, p.drag_per_roll_n) * p.seal_drag_factor
    temp = math.exp(-p.drag_temp_coef * (temperature_c - p.drag_ref_temp_c))
    # the seal drag carries its own temperature law e^{-c (T - T_r)}, not Kta as well
    drag_coef = drag * temp / spacing * dx / p.drag_ref_speed_m_s ** p.drag_speed_exp
    b.add("idler_rotation", drag_coef, pv=p.drag_speed_exp)

    # BI: indentation, per-roll 4/3 law summed over the set, per metre / S
    comp = rubber.compound(loop.belt.compound)
    freq = float(rubber.contact_frequency(v, p.contact_length_m))
    tan, e_st = rubber.loss_and_modulus(temperature_c, freq, comp)
    tan, e_st = float(tan), float(e_st)
    loads, width = roll_loads(loop, p.centre_share)
    per_set = indentation_per_set(loads, width, loop.roll_diameter_m,
                                  loop.belt.bottom_cover_mm * 1e-3, tan, e_st, p.kappa_ir)
    bi = np.where(idl, per_set / spacing * dx, 0.0)  # [N] at the design speed
    e_exp = (p.indentation_speed_exp if p.indentation_speed_exp is not None
             else speed_exponent(temperature_c, freq, comp))
    b.add("indentation", bi / v ** e_exp, pv=e_exp)

    # BF: belt flexure at the reference sag, times phi^n
    bf = np.where(idl, G * p.m_star * kta * (loop.mG_kg_m + loop.mL_kg_m) * loop.cos_a * dx,
                  0.0)
    b.add("belt_flexure", bf, ps=p.bf_sag_exp)

    # MF: material flexure (carry), (p + q v) (1.66 S_c / S_r)^s (m'_L / m_ref) phi^n_m
    # (added also when empty, with zero coefficients, so every run reports the same parts)
    mf_scale = np.where(carry, G * dx * spacing_ratio(conv) ** p.s_mf
                        * loop.mL_kg_m / p.mf_ref_load_kg_m, 0.0)
    b.add("material_flexure", p.p_mf * mf_scale, ps=p.mf_sag_exp)
    b.add("material_flexure", p.q_mf * mf_scale, pv=1.0, ps=p.mf_sag_exp)

    add_feed(b, loop, conv)
    b.add("secondary", pulley_allowances(loop, conv))
    add_accessories(b, loop, conv)
    ret = loop.strand == RETURN
    return b.build(info={
        "tan_delta": tan, "e_storage_mpa": e_st / 1e6, "frequency_hz": freq,
        "indentation_speed_exp": e_exp, "drag_temperature_factor": temp,
        "compound": comp.id, "hs_ref": HS_REF, "kta": kta,
        "indentation_carry_n_m": float(bi[carry].sum() / max(dx[carry].sum(), 1e-9)),
        "indentation_return_n_m": float(bi[ret].sum() / max(dx[ret].sum(), 1e-9)),
    })


MODEL = FrictionModel(
    name="nonlin",
    description="Harrison's hybrid Non-Lin (2008 Eq. 1): idler rotation, rubber indentation "
                "(4/3 law, WLF rubber), belt and material flexure growing with sag",
    params_class=NonlinParams,
    build=build,
    range_note=lambda p, t: kt_note("nonlin", p.kta, t, "kta"),
)
