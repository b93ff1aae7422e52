"""Sampled studies (SPEC 7.2 ``sample:``): uncertain inputs drawn from distributions.

A study may hold ``sample:`` beside ``grid:``: ``n`` points, a ``method`` and a ``seed``, and per
axis (any numeric grid axis path: ``temperature_c``, ``takeup.mass_kg``,
``models.nonlin.mu_b``) a distribution. The points are drawn on the unit hypercube and mapped
through each distribution's inverse CDF (scipy.stats); together they are one more zip group of
the study (the sample axes vary together), crossed with the grid, so each point is a run like
any other (ids, Parquet rows, restart, merging of identical runs).

Methods:

* ``lhs``: a Latin hypercube of ``n`` points (``scipy.stats.qmc.LatinHypercube``, seeded).
  Its sensitivity measure is a rank correlation (:mod:`beltstudy.service.uncertainty`).
* ``sobol``: Saltelli's design for Sobol' indices as SALib draws it
  (``SALib.sample.sobol.sample`` with ``calc_second_order=False``, scrambled Sobol' sequence
  of dimension 2 D from ``scipy.stats.qmc.Sobol``, seeded): base samples A and B of N points
  and the D matrices AB_i (A with column i from B), N (D + 2) points in all, in SALib's order.
  ``n`` is that total when N = n / (D + 2) is a power of two (the Sobol' sequence's balance);
  another ``n`` of at least the smallest design, 2 (D + 2) (N = 2), draws the nearest such
  size (SPEC 7.2's ``n: 512`` over 3 axes draws 640, N = 128), which the study's uncertainty
  summary states (``points``); an ``n`` below 2 (D + 2) is refused, not rounded up (over 4
  axes ``n: 10`` is refused, though 12 is the nearest size: :func:`sobol_base`). First-order
  and total indices then come from ``SALib.analyze.sobol`` on the runs' results.

Distributions (parameters as scipy.stats names them in brackets):

* ``uniform: {low, high}``, low < high;
* ``normal: {mean, sd}``, sd > 0;
* ``lognormal: {median, sigma}``: ln X normal with mean ln(median) and sd sigma > 0
  (``scipy.stats.lognorm(s=sigma, scale=median)``), median > 0;
* ``triangular: {low, mode, high}``: low <= mode <= high, low < high
  (``scipy.stats.triang(c=(mode-low)/(high-low), loc=low, scale=high-low)``).
"""

from __future__ import annotations

import typing
from typing import Annotated, Any, Literal, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

__all__ = ["SampleIn", "Distribution", "draw", "unit_points", "sobol_base", "sobol_n_within",
           "DISTRIBUTIONS", "MAX_SAMPLE", "value_bounds", "bounds_problem"]

#: Largest sample (runs before crossing with the grid; BELTSTUDY_MAX_RUNS bounds the study).
MAX_SAMPLE = 1 << 16
#: The unit-cube values are kept this far inside (0, 1), where the normal's inverse is finite.
_EDGE = 1e-12


class _Dist(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Uniform(_Dist):
    """Uniform on [low, high]."""

    dist: Literal["uniform"]
    low: float = Field(..., description="lower bound, in the axis's unit")
    high: float = Field(..., description="upper bound, in the axis's unit")

    @model_validator(mode="after")
    def _order(self):
        if not self.high > self.low:
            raise ValueError(f"high ({self.high:g}) must be above low ({self.low:g})")
        return self

    def ppf(self, u: np.ndarray) -> np.ndarray:
        return self.low + u * (self.high - self.low)


class Normal(_Dist):
    """Normal with mean and standard deviation sd > 0."""

    dist: Literal["normal"]
    mean: float = Field(..., description="mean, in the axis's unit")
    sd: float = Field(..., gt=0, description="standard deviation (> 0), in the axis's unit")

    def ppf(self, u: np.ndarray) -> np.ndarray:
        from scipy.stats import norm

        return norm.ppf(u, loc=self.mean, scale=self.sd)


class Lognormal(_Dist):
    """ln X normal: median exp(mu) > 0, sigma > 0 the sd of ln X."""

    dist: Literal["lognormal"]
    median: float = Field(..., gt=0, description="median (> 0)")
    sigma: float = Field(..., gt=0, description="standard deviation of ln X (> 0)")

    def ppf(self, u: np.ndarray) -> np.ndarray:
        from scipy.stats import norm

        return self.median * np.exp(self.sigma * norm.ppf(u))


class Triangular(_Dist):
    """Triangular on [low, high] with its mode between."""

    dist: Literal["triangular"]
    low: float = Field(..., description="lower bound, in the axis's unit")
    mode: float = Field(..., description="most likely value, in the axis's unit")
    high: float = Field(..., description="upper bound, in the axis's unit")

    @model_validator(mode="after")
    def _order(self):
        if not self.high > self.low:
            raise ValueError(f"high ({self.high:g}) must be above low ({self.low:g})")
        if not self.low <= self.mode <= self.high:
            raise ValueError(f"mode ({self.mode:g}) must lie between low ({self.low:g}) and "
                             f"high ({self.high:g})")
        return self

    def ppf(self, u: np.ndarray) -> np.ndarray:
        from scipy.stats import triang

        width = self.high - self.low
        return triang.ppf(u, (self.mode - self.low) / width, loc=self.low, scale=width)


DISTRIBUTIONS = {"uniform": Uniform, "normal": Normal, "lognormal": Lognormal,
                 "triangular": Triangular}
Distribution = Annotated[Union[Uniform, Normal, Lognormal, Triangular],  # noqa: UP007
                         Field(discriminator="dist")]


class SampleIn(BaseModel):
    """``sample:`` of a study (SPEC 7.2)."""

    model_config = ConfigDict(extra="forbid")

    n: int = Field(..., ge=2, le=MAX_SAMPLE, description="points drawn (runs before the grid "
                   "crosses them); method sobol draws the nearest N (D + 2) with N a power of "
                   "two, from 2 (D + 2) up: a smaller n is refused, not rounded up")
    method: Literal["sobol", "lhs"] = Field(
        "sobol", description="sobol: Saltelli's design on a scrambled Sobol' sequence "
        "(SALib; Sobol' indices) | lhs: Latin hypercube (rank correlations)")
    seed: int = Field(0, ge=0, description="seed: the same seed, the same points")
    axes: dict[str, Distribution] = Field(
        ..., description="axis path (as in grid) -> {dist: uniform|normal|"
        "lognormal|triangular, and its parameters}; at least one",
        json_schema_extra={"minProperties": 1})

    @field_validator("axes")
    @classmethod
    def _some_axis(cls, axes: dict) -> dict:
        # said here, not as pydantic's "Dictionary should have at least 1 item after
        # validation, not 0", which names neither what to give nor how
        if not axes:
            raise ValueError("give at least one axis with a dist (e.g. temperature_c: "
                             "{dist: uniform, low: -25, high: 35})")
        return axes

    @model_validator(mode="after")
    def _sobol_size(self):
        if self.method == "sobol":
            sobol_base(self.n, len(self.axes))
        return self


def sobol_base(n: int, d: int) -> int:
    """N of the Saltelli design drawn for ``n`` points over ``d`` inputs: N (d + 2) points with
    N a power of two (the Sobol' sequence's balance), the nearest to ``n`` (the smaller on a
    tie); ``n`` itself when it is such a size. ValueError below the smallest, 2 (d + 2)
    (N = 2), even where that is the nearest size (n = 10 over d = 4: not rounded up to 12;
    docs/uncertainty.md says so)."""
    per = d + 2
    if n < 2 * per:
        raise ValueError(f"n = {n}: method sobol draws N (D + 2) points for D = {d} axes with N "
                         f"a power of two from 2 (Saltelli's design for Sobol' indices); use n "
                         f">= {2 * per}, or method: lhs for any n")
    lo = 1 << ((n // per).bit_length() - 1)  # the largest N with N (d + 2) <= n
    hi = lo * 2
    return lo if n - lo * per <= hi * per - n else hi


def sobol_n_within(d: int, most: int) -> tuple[int, int] | None:
    """The largest ``n`` whose Saltelli design over ``d`` inputs (:func:`sobol_base`) has at
    most ``most`` points, and that design's size N (d + 2); None when even the smallest
    (N = 2) has more.

    With S = N (d + 2) the largest design within ``most``, every n up to 1.5 S draws S or
    less: the sizes around it are S and 2 S, and :func:`sobol_base` takes the nearer, the
    smaller on a tie (1.5 S itself); 1.5 S + 1 draws 2 S. Over one axis (d + 2 = 3) within
    5000 points: S = 3072 (N = 1024), n <= 4608; 4609 and the 5000 that the limit alone
    would suggest draw 6144. Capped at :data:`MAX_SAMPLE`, the largest ``n`` taken."""
    per = d + 2
    if most < 2 * per:
        return None
    size = (1 << ((most // per).bit_length() - 1)) * per
    n = min(size * 3 // 2, MAX_SAMPLE)
    return n, sobol_base(n, d) * per


def unit_points(sample: SampleIn) -> np.ndarray:
    """The sample's points on the unit hypercube, shape (n, D), axes in the order given."""
    d = len(sample.axes)
    if sample.method == "lhs":
        from scipy.stats import qmc

        u = qmc.LatinHypercube(d=d, rng=np.random.default_rng(sample.seed)).random(sample.n)
    else:
        from SALib.sample import sobol

        problem = {"num_vars": d, "names": list(sample.axes), "bounds": [[0.0, 1.0]] * d}
        u = sobol.sample(problem, sobol_base(sample.n, d), calc_second_order=False,
                         scramble=True, seed=sample.seed)
    return np.clip(u, _EDGE, 1.0 - _EDGE)


def draw(sample: SampleIn) -> dict[str, list[float]]:
    """Each axis's ``n`` values, in the order of the points."""
    u = unit_points(sample)
    out = {}
    for k, (name, dist) in enumerate(sample.axes.items()):
        values = dist.ppf(u[:, k])
        out[name] = [float(f"{v:.12g}") for v in values]
    return out


# ------------------------------------------------------------------ the field's own bounds
#: JSON Schema bound names (a model parameter's, :func:`param_bounds`) -> pydantic's.
_SCHEMA_BOUNDS = {"minimum": "ge", "exclusiveMinimum": "gt", "maximum": "le",
                  "exclusiveMaximum": "lt"}
_OPS = {"ge": ">=", "gt": ">", "le": "<=", "lt": "<"}


def value_bounds(item: Any, schema: dict | None = None) -> dict[str, float]:
    """The numeric bounds (``ge``, ``gt``, ``le``, ``lt``) of an axis's value type (its
    ``Annotated`` metadata, a union's numeric member) or of a model parameter's ``schema``
    bounds (``minimum``, ...)."""
    out: dict[str, float] = {}
    for key, value in (schema or {}).items():
        if key in _SCHEMA_BOUNDS:
            out[_SCHEMA_BOUNDS[key]] = float(value)

    def walk(t: Any) -> None:
        origin = typing.get_origin(t)
        if origin is Annotated:
            base, *meta = typing.get_args(t)
            walk(base)
            for m in meta:
                for inner in [m, *getattr(m, "metadata", [])]:
                    for op in _OPS:
                        v = getattr(inner, op, None)
                        if isinstance(v, int | float) and not isinstance(v, bool):
                            out.setdefault(op, float(v))
        elif origin is not None and origin is not Literal:
            for arg in typing.get_args(t):
                walk(arg)

    walk(item)
    return out


def _violated(values: np.ndarray, bounds: dict[str, float]) -> dict[str, np.ndarray]:
    """Bound name -> which values break it."""
    tests = {"ge": lambda v, b: v < b, "gt": lambda v, b: v <= b,
             "le": lambda v, b: v > b, "lt": lambda v, b: v >= b}
    return {op: tests[op](values, b) for op, b in bounds.items()
            if tests[op](values, b).any()}


def bounds_problem(name: str, dist: Any, values: list[float] | None,
                   bounds: dict[str, float]) -> str | None:
    """Why the axis ``name``'s distribution or drawn ``values`` leave the field's ``bounds``
    (``None`` when they do not), said with the bound and the fix. A bounded distribution
    (uniform, triangular) is checked by its ends before anything is drawn (``values`` None;
    the draws never reach the ends, so an open bound at an end is kept); the others by
    their draws."""
    if values is None:
        if not isinstance(dist, Uniform | Triangular):
            return None
        for end, op in (("low", "ge"), ("low", "gt"), ("high", "le"), ("high", "lt")):
            v, b = getattr(dist, end), bounds.get(op)
            if b is not None and (v < b if end == "low" else v > b):
                side = "below" if end == "low" else "above"
                fix = ">=" if end == "low" else "<="
                return (f"{end} ({v:g}) lies {side} the field's bound {name} {_OPS[op]} {b:g}: "
                        f"draws beyond it would be refused; give {end} {fix} {b:g}")
        return None
    arr = np.asarray(values, dtype=float)
    broken = _violated(arr, bounds)
    if not broken:
        return None
    bad = np.logical_or.reduce(list(broken.values()))
    said = " and ".join(f"{name} {_OPS[op]} {bounds[op]:g}" for op in broken)
    drawn = arr[bad]
    shown = ", ".join(f"{v:g}" for v in sorted({float(drawn.min()), float(drawn.max())}))
    return (f"{int(bad.sum())} of {len(arr)} drawn values break the field's bound {said} "
            f"(drawn {shown}): give a distribution within it, a narrower one or a bounded "
            "one (uniform or triangular with low and high within the bound)")


def spec_json(sample: SampleIn) -> dict[str, Any]:
    """The sample as stored in ``study.json`` (enough to know how it was drawn)."""
    return sample.model_dump(mode="json")
