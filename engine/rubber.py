"""Cover rubber: loss factor tan(delta) and storage modulus E' against temperature and frequency.

Time-temperature superposition (PHYSICS section 3): a loading at frequency f and temperature T
acts like a loading at the reduced frequency f_r = f a_T(T) at the reference temperature, with
the WLF shift referred to the glass transition,

    log10 a_T = -C1 (T - T_g) / (C2 + T - T_g).

In reduced frequency the compound has one loss peak (the glass transition) on top of a
frequency-independent loss of the filler network,

    tan(delta) = tan_delta_floor + loss_peak sech(x / w),    x = log10(f_r / f_peak),

a Fuoss-Kirkwood peak of width w decades centred on f_peak (the peak's reduced frequency at
T = T_g). The storage modulus rises through the same transition. It follows from the loss peak
by the approximate Kramers-Kronig relation d ln E' / d ln f = (2 / pi) tan(delta) (Booij and
Thoone 1982), applied to the relaxation part of the loss (the filler floor belongs to a
network that does not shift with the WLF law):

    E' = E_r exp[(2 / pi) ln(10) loss_peak w (gd(x / w) + pi / 2)],

with gd the Gudermannian function, gd(u) = 2 atan(tanh(u / 2)), and E_r the modulus of the
rubbery plateau. Far below the peak E' -> E_r; far above it E' -> E_r exp(2 ln(10) loss_peak w),
the glassy modulus (a few hundred times E_r for the catalogue compounds).

The parameters of each compound (standard, lrr, cold, fire-resistant) are catalogue data in
``engine/data/compounds.csv`` with their sources; every one of them is documented in the file
header.

References
----------
Williams, M.L., Landel, R.F., Ferry, J.D.: The temperature dependence of relaxation
mechanisms in amorphous polymers and other glass-forming liquids. J. Am. Chem. Soc. 77 (1955).
Fuoss, R.M., Kirkwood, J.G.: Electrical properties of solids VIII. J. Am. Chem. Soc. 63 (1941).
Booij, H.C., Thoone, G.P.J.M.: Generalization of Kramers-Kronig transforms and some
approximations of relations between viscoelastic quantities. Rheol. Acta 21 (1982).
Harrison, A.: A hybrid model for numerical belt conveyor simulation. bulk solids handling 28
(2008) No. 4 (tan(delta) as a function of frequency and temperature in the Non-Lin model).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from beltstudy.engine import catalog

__all__ = [
    "Compound",
    "compound",
    "shift_log10",
    "reduced_frequency_log10",
    "tan_delta",
    "storage_modulus",
    "loss_and_modulus",
    "contact_frequency",
]

#: The WLF law diverges at T = T_g - C2; below T_g - C2 / 2 the shift is held (glassy state).
_DT_MIN_FRACTION = 0.5
_LN10 = math.log(10.0)


@dataclass(frozen=True)
class Compound:
    """Viscoelastic parameters of one cover compound (units in the names).

    Attributes
    ----------
    id : str
    tg_c : float
        Glass transition temperature T_g [C], the WLF reference temperature.
    wlf_c1, wlf_c2 : float
        WLF constants [-] and [K] for T_ref = T_g.
    log10_fpeak_hz : float
        log10 of the reduced frequency of the loss peak at T = T_g [Hz].
    loss_peak : float
        Height of the relaxation loss peak above the floor [-].
    loss_width_dec : float
        Width w of the sech loss peak [decades of reduced frequency].
    tan_delta_floor : float
        Frequency-independent loss of the filler network [-].
    e_rubbery_mpa : float
        Storage modulus of the rubbery plateau [MPa].
    """

    id: str
    tg_c: float
    wlf_c1: float
    wlf_c2: float
    log10_fpeak_hz: float
    loss_peak: float
    loss_width_dec: float
    tan_delta_floor: float
    e_rubbery_mpa: float

    @property
    def glassy_ratio(self) -> float:
        """E'(glassy) / E'(rubbery) implied by the loss peak [-]."""
        return math.exp(2.0 * _LN10 * self.loss_peak * self.loss_width_dec)


def glass_note(compound_id: str, temperature_c: float, model: str) -> str:
    """The note of a run of a model that reads the cover rubber (``model``: nonlin, visco)
    colder than the cover compound's glass transition T_g (engine/data/compounds.csv, PHYSICS
    section 3): the cover is glassy there, its loss peak at the idler contact's frequency lies
    a few kelvin above T_g, so the indentation loss falls the colder it gets (a glassy cover
    barely indents) while the cover itself is brittle, out of the range a rubber cover serves
    in. "" at or above T_g. Names the catalogue compounds whose T_g lies
    below ``temperature_c`` (``belt.compound``)."""
    comp = compound(compound_id)
    if float(temperature_c) >= comp.tg_c:
        return ""
    colder = [f"{cid} (T_g {float(r['tg_c']):g} C)" for cid, r in catalog.compounds().items()
              if float(r["tg_c"]) < float(temperature_c)]
    way = (f"a compound rubbery there, belt.compound: {' or '.join(colder)}" if colder
           else "no catalogue compound is rubbery there; a compound of the maker's, with its "
                "measured master curve")
    return (f"note: at {float(temperature_c):g} C the {comp.id} cover is below its glass "
            f"transition (T_g {comp.tg_c:g} C, engine/data/compounds.csv): it is glassy, so "
            f"{model}'s indentation loss has passed its peak and falls the colder it gets, "
            f"and a glassy cover is brittle: {way}")


@cache
def compound(compound_id: str) -> Compound:
    """The catalogue compound ``compound_id`` (InputError listing the valid ids if unknown)."""
    rows = catalog.compounds()
    if compound_id not in rows:
        from beltstudy.engine.conveyor import InputError

        raise InputError(catalog._unknown("compound", compound_id, list(rows), "belt.compound"))
    r = rows[compound_id]
    return Compound(
        id=compound_id,
        tg_c=float(r["tg_c"]),
        wlf_c1=float(r["wlf_c1"]),
        wlf_c2=float(r["wlf_c2"]),
        log10_fpeak_hz=float(r["log10_fpeak_hz"]),
        loss_peak=float(r["loss_peak"]),
        loss_width_dec=float(r["loss_width_dec"]),
        tan_delta_floor=float(r["tan_delta_floor"]),
        e_rubbery_mpa=float(r["e_rubbery_mpa"]),
    )


def _as_compound(c: Compound | str) -> Compound:
    return compound(c) if isinstance(c, str) else c


def shift_log10(temperature_c, comp: Compound | str) -> np.ndarray:
    """WLF shift log10 a_T [-] referred to T_g.

    Parameters
    ----------
    temperature_c : float or array
        Temperature [C].
    comp : Compound or str
        Compound or its catalogue id.

    Notes
    -----
    log10 a_T = -C1 (T - T_g) / (C2 + T - T_g); T - T_g is held at -C2 / 2 or above, where
    the law would otherwise run to its pole at T_g - C2 (the compound is glassy there anyway).
    """
    c = _as_compound(comp)
    dt = np.maximum(np.asarray(temperature_c, dtype=float) - c.tg_c, -_DT_MIN_FRACTION * c.wlf_c2)
    return -c.wlf_c1 * dt / (c.wlf_c2 + dt)


def reduced_frequency_log10(temperature_c, frequency_hz, comp: Compound | str) -> np.ndarray:
    """x = log10(f a_T / f_peak): distance from the loss peak [decades]."""
    c = _as_compound(comp)
    f = np.maximum(np.asarray(frequency_hz, dtype=float), 1e-12)
    return np.log10(f) + shift_log10(temperature_c, c) - c.log10_fpeak_hz


def loss_and_modulus(temperature_c, frequency_hz, comp: Compound | str):
    """tan(delta) [-] and storage modulus E' [Pa] at temperature [C] and frequency [Hz].

    Returns
    -------
    tan_delta : ndarray
        Loss factor [-].
    e_storage_pa : ndarray
        Storage modulus E' [Pa].

    Notes
    -----
    tan(delta) = floor + A sech(x / w); E' = E_r exp[(2/pi) ln10 A w (gd(x / w) + pi/2)],
    x = log10(f a_T / f_peak) (module docstring).
    """
    c = _as_compound(comp)
    u = reduced_frequency_log10(temperature_c, frequency_hz, c) / c.loss_width_dec
    tan = c.tan_delta_floor + c.loss_peak / np.cosh(u)
    gd = 2.0 * np.arctan(np.tanh(0.5 * u))
    expo = (2.0 / math.pi) * _LN10 * c.loss_peak * c.loss_width_dec * (gd + 0.5 * math.pi)
    return tan, c.e_rubbery_mpa * 1e6 * np.exp(expo)


def tan_delta(temperature_c, frequency_hz, comp: Compound | str) -> np.ndarray:
    """Loss factor tan(delta) [-] at temperature [C] and frequency [Hz]."""
    return loss_and_modulus(temperature_c, frequency_hz, comp)[0]


def storage_modulus(temperature_c, frequency_hz, comp: Compound | str) -> np.ndarray:
    """Storage modulus E' [Pa] at temperature [C] and frequency [Hz]."""
    return loss_and_modulus(temperature_c, frequency_hz, comp)[1]


def contact_frequency(speed_m_s, contact_length_m) -> np.ndarray:
    """Loading frequency of the cover passing over a roll, f = v / contact length [Hz]."""
    return np.abs(np.asarray(speed_m_s, dtype=float)) / contact_length_m
