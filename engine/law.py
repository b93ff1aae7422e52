"""The per-element resistance law shared by statics and the transient kernel.

Every friction model returns a :class:`ResistanceLaw`: a sum of K named terms, per element j

    R_j(v, T) = reg(v) * sum_k coef[k, j] * |v|^pv[k] * phi_j(T)^ps[k]

with phi_j(T) = min(sag_w_n[j] / max(T, 1 N), hs_max_j) / hs_ref the local sag ratio h/S over a
reference sag (so a term equals ``coef`` at the reference sag) and T the element's mean
tension. The cap ``hs_max_j`` is the admissible sag of the element's strand (the conveyor's
``sag_limit_pct``, DIN 22101's running limits): the sag-dependent laws are calibrated on belts
running within those limits and are not extrapolated beyond them, so a slack or nearly slack
span keeps the resistance it has at its sag limit. Statics evaluates it at the design speed (reg = 1); the numba kernel evaluates the
same arrays every step.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["ResistanceLaw", "LawBuilder", "sag_phi"]

#: Default reference sag ratio h/S for tension-dependent terms (1 %).
HS_REF = 0.01
#: Cap on the sag ratio of a law built without per-element caps (friction models pass the
#: loop's ``sag_limit``, the admissible sag of each element's strand).
HS_MAX = 0.10


def sag_phi(sag_w_n: np.ndarray, tension_n: np.ndarray, hs_ref: float = HS_REF,
            hs_max=HS_MAX) -> np.ndarray:
    """Local sag ratio h/S relative to ``hs_ref`` (dimensionless), capped at ``hs_max`` (a
    number or one cap per element)."""
    hs = sag_w_n / np.maximum(tension_n, 1.0)
    return np.minimum(hs, hs_max) / hs_ref


@dataclass(frozen=True, eq=False)
class ResistanceLaw:
    """Per-element resistance as named terms (see module docstring). Forces in [N]."""

    names: tuple[str, ...]
    coef: np.ndarray  # (K, n) [N]
    pv: np.ndarray  # (K,) speed exponents
    ps: np.ndarray  # (K,) sag exponents
    sag_w_n: np.ndarray  # (n,) g (m'_G + m'_L) cos(a) S / 8 [N]
    hs_ref: float = HS_REF
    hs_max: float | np.ndarray = HS_MAX
    info: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return self.coef.shape[1]

    @property
    def tension_dependent(self) -> bool:
        return bool(np.any(self.ps != 0.0))

    def terms(self, v: float | np.ndarray, tension_mean_n: np.ndarray | None = None) -> np.ndarray:
        """Each term per element, shape (K, n) [N], for speed v [m/s] (reg(v) = sign)."""
        v = np.asarray(v, dtype=np.float64)
        av = np.abs(v)
        speed = np.where(self.pv[:, None] == 0.0, 1.0, av ** self.pv[:, None])
        if self.tension_dependent:
            if tension_mean_n is None:
                raise ValueError("this law depends on tension: pass tension_mean_n")
            phi = sag_phi(self.sag_w_n, tension_mean_n, self.hs_ref, self.hs_max)
            sag = np.where(self.ps[:, None] == 0.0, 1.0, phi[None, :] ** self.ps[:, None])
        else:
            sag = 1.0
        return np.sign(v) * self.coef * speed * sag

    def evaluate(self, v, tension_mean_n=None) -> np.ndarray:
        """Total resistance per element [N]."""
        return self.terms(v, tension_mean_n).sum(axis=0)

    def parts(self, v, tension_mean_n=None) -> dict[str, np.ndarray]:
        """Resistance per element grouped by component name [N]."""
        t = self.terms(v, tension_mean_n)
        out: dict[str, np.ndarray] = {}
        for k, name in enumerate(self.names):
            out[name] = out.get(name, 0.0) + t[k]
        return out


class LawBuilder:
    """Collect terms; terms with the same (name, pv, ps) are merged."""

    def __init__(self, n: int, sag_w_n: np.ndarray, hs_ref: float = HS_REF,
                 hs_max: float | np.ndarray = HS_MAX):
        self.n = n
        self.sag_w_n = np.asarray(sag_w_n, dtype=np.float64)
        self.hs_ref = hs_ref
        self.hs_max = hs_max
        self._terms: dict[tuple[str, float, float], np.ndarray] = {}

    def add(self, name: str, coef, pv: float = 0.0, ps: float = 0.0) -> LawBuilder:
        c = np.broadcast_to(np.asarray(coef, dtype=np.float64), (self.n,)).copy()
        key = (name, float(pv), float(ps))
        if key in self._terms:
            self._terms[key] = self._terms[key] + c
        else:
            self._terms[key] = c
        return self

    def build(self, info: dict | None = None) -> ResistanceLaw:
        keys = list(self._terms)
        if not keys:
            keys = [("secondary", 0.0, 0.0)]
            self._terms[keys[0]] = np.zeros(self.n)
        return ResistanceLaw(
            names=tuple(k[0] for k in keys),
            coef=np.vstack([self._terms[k] for k in keys]),
            pv=np.array([k[1] for k in keys], dtype=np.float64),
            ps=np.array([k[2] for k in keys], dtype=np.float64),
            sag_w_n=self.sag_w_n,
            hs_ref=self.hs_ref,
            hs_max=self.hs_max,
            info=dict(info or {}),
        )
