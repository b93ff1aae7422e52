"""What the samples of a sampled study say (SPEC 7.4, ``GET /studies/{id}/uncertainty``).

For each grid cell (each combination of the study's grid and zip axis values; the sample is
crossed with them) and each deciding figure of the runs table: its distribution (mean,
standard deviation, quantiles), the probability that a run is past each design limit with a
confidence interval, and a ranking of the sampled inputs by their share of the figure's
variance. Everything is a pure function of the stored study document and its runs table.

Notes
-----
*Exceedance.* A run is past a limit when the design report says so
(:data:`beltstudy.service.web.verdicts.CAUSES`: belt safety factor below its minimum, slip
margin below 1 or slipping, sag past its limit, slack, a drive over its rating). Of n finished
runs k are past it (a run that stands for several sample points, merged because they differ
only in an axis it does not read, counts once for each): p = k / n with the Wilson score
interval (Wilson 1927; recommended over the normal approximation by Agresti & Coull 1998, also
for k = 0 or k = n):

    (p + z^2 / 2n +- z sqrt(p (1 - p) / n + z^2 / 4n^2)) / (1 + z^2 / n),   z = 1.96 (95 %).

It is the interval of the probability over the sampled distributions, given that the runs are
an independent random sample of them; a Sobol' or Latin hypercube sample is more even than
that, so the interval is conservative.

*Runs without a value.* A figure's mean, sd and quantiles are those of the sample points
whose run has it; the points whose run has none are counted beside them (``points``,
``without_value``) with the reason (``why``). Where a missing value is beyond every bound --
the sag of a strand that went slack (unbounded sag; the design report's rule,
:func:`beltstudy.service.web.verdicts._slack_no_sag`), the stop time of a transient that did
not stop (the report's ``null_worst``) -- it is counted in ``unbounded``, and
``unbounded_quantiles`` names the quantiles that, with those points counted past every value,
are unbounded (2 slack of 32: p95, whose position 0.95 x 31 = 29.45 lies past the 30
values).

*Sensitivity.* A ``method: sobol`` sample is Saltelli's design
(:mod:`beltstudy.service.door.sample`): the first-order index S_i = V[E(Y | X_i)] / V(Y) and
the total index S_Ti = E[V(Y | X_~i)] / V(Y) come from ``SALib.analyze.sobol`` (Saltelli et al.
2010 estimator for S_i, Jansen 1999 for S_Ti, 95 % bootstrap confidence), when every point of
the cell has the figure. Otherwise (``method: lhs``, or failed runs in the design) the ranking
is Spearman's rank correlation rho_i of input and figure (scipy.stats.spearmanr): its sign
says the direction, rho_i^2 roughly the share of a monotone effect; it is not a variance share
and interactions do not show in it.

References
----------
Saltelli, A. et al.: Variance based sensitivity analysis of model output. Computer Physics
Communications 181 (2010) 259-270.
Herman, J., Usher, W.: SALib: An open-source Python library for sensitivity analysis. JOSS 2
(2017) 97.
Agresti, A., Coull, B.A.: Approximate is better than "exact" for interval estimation of
binomial proportions. The American Statistician 52 (1998) 119-126.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd

from beltstudy.engine import results as result_fields
from beltstudy.engine.wording import gnum
from beltstudy.service.door.sample import sobol_base
from beltstudy.service.web.verdicts import (
    CAUSES,
    VERDICTS,
    _slack_no_sag,  # the report's rule: a sag missing because the strand went slack
    expand,
    never_going,
    transient_ran,
)

__all__ = ["FIGURES", "LIMITS", "QUANTILES", "summarise", "wilson", "distribution",
           "sensitivity", "small_sample_note", "index_text", "sd_text", "no_value",
           "without_text", "runs_text", "CONFIDENCE", "SOBOL_N_MIN"]

#: The deciding figures (SPEC issue 30: peak tension per phase, power, stop time, lowest
#: tension, slip margin, safety factor; with sag and slack, the limits' own figures). A figure
#: is shown when the runs carry it; ``{i}`` stands for each drive.
FIGURES = (
    "t_max_start_kn", "t_max_stop_kn", "t_min_start_kn", "t_min_stop_kn",
    "t_max_kn", "t_min_kn", "power_kw", "drive{i}_power_required_kw", "drive_power_max_kw",
    "stop_time_s", "slip_margin", "slip_margin_start", "slip_margin_min_dyn",
    "safety_factor", "safety_factor_dyn", "sag_max_pct", "sag_max_dyn_pct", "slack_max_m",
    "takeup_travel_m",
)
#: The design limits (keys of :data:`~beltstudy.service.web.verdicts.CAUSES`).
LIMITS = ("safety", "slip", "sag", "slack", "overload")
QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
CONFIDENCE = 0.95
#: Smallest base sample N of a Sobol' design whose indices are read as shares without a note.
#: Their sampling error falls as 1 / sqrt(N) (a Monte Carlo estimate; Saltelli et al. 2010):
#: on this project's slope study (docs/uncertainty.md, section 4) N = 64 left 95 % bootstrap
#: half-widths of 0.3-0.45 on the dominant input, so N = 512 brings them to about 0.1-0.15,
#: the first size at which a share of 0.3 is told from one of 0.6.
SOBOL_N_MIN = 512
#: Slack on [0, 1] before an index is noted as outside it: a share of 1e-4 of the variance,
#: below what any ranking reads. An index of an input the figure does not read is 0 up to
#: the estimator's round-off (S1 -4.2e-8 with S1_conf 1e-7), which was noted on nearly every
#: figure as outside [0, 1] and buried the notes of indices that are (S1 1.48).
_INDEX_SLACK = 1e-4


def wilson(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion k / n (module notes)."""
    if n <= 0:
        return (0.0, 1.0)
    from scipy.stats import norm

    z = float(norm.ppf(0.5 + confidence / 2))
    p = k / n
    centre = p + z * z / (2 * n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    den = 1 + z * z / n
    # at k = 0 (k = n) the bound is 0 (1) exactly; the subtraction leaves a rounding residue
    lo = 0.0 if k <= 0 else max(0.0, (centre - half) / den)
    hi = 1.0 if k >= n else min(1.0, (centre + half) / den)
    return (lo, hi)


def distribution(values: pd.Series) -> dict[str, Any] | None:
    """n, mean, sd (n - 1), min, max and :data:`QUANTILES` of the finite values."""
    v = pd.to_numeric(values, errors="coerce").astype(float)
    v = v[np.isfinite(v)]
    if not len(v):
        return None
    q = np.quantile(v.to_numpy(), QUANTILES)
    return {"n": int(len(v)), "mean": float(v.mean()),
            "sd": float(v.std(ddof=1)) if len(v) > 1 else 0.0,
            "min": float(v.min()), "max": float(v.max()),
            "quantiles": {f"p{round(100 * p):02d}": float(x) for p, x in zip(
                QUANTILES, q, strict=True)}}


#: The design report's verdict row of each figure (its limit, what a missing value means).
_VERDICT_OF = {v.column: v for v in VERDICTS}


def no_value(column: str, rows: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    """Why each run of ``rows`` has no finite ``column`` ("" where it has one) and whether the
    missing value lies beyond every bound, as the design report judges the run: a sag row's
    run that went slack (the report's
    :func:`~beltstudy.service.web.verdicts._slack_no_sag`: a slack span's sag has no bound),
    a ``null_worst`` row's transient that did not stop (its stop time has none); a transient
    whose belt never got going made no stop (no value, not beyond a bound); a failed run has
    no value at all."""
    values = pd.to_numeric(rows[column], errors="coerce").astype(float)
    missing = ~np.isfinite(values)
    why = pd.Series(np.where(missing, "no value", ""), index=rows.index, dtype=object)
    beyond = pd.Series(False, index=rows.index)
    v = _VERDICT_OF.get(column)
    if v is not None and v.limit == "sag":
        beyond = _slack_no_sag(v, rows, values.where(~missing)) & missing
        why[beyond] = "slack, sag unbounded"
    elif v is not None and v.null_worst:
        going = never_going(rows) & missing
        beyond = transient_ran(rows) & missing & ~going
        why[beyond] = f"{v.null_worst}, {column} unbounded"
        why[going] = "never got going, no stop"
    if "status" in rows:
        failed = (rows["status"].astype(str) == "failed") & missing
        why[failed] = "the run failed"
        beyond = beyond & ~failed
    return why.to_numpy(dtype=object), beyond.to_numpy(dtype=bool)


def _without(at: list[int | None], why: np.ndarray, beyond: np.ndarray, n: int
             ) -> dict[str, Any]:
    """The sample points with a run (``points``), of them those whose run has no value of the
    figure (``without_value``, ``why``: the reasons, counted where they differ) and those
    beyond every bound (``unbounded``); ``unbounded_quantiles``: the :data:`QUANTILES` that
    are unbounded over the ``n`` values and the unbounded points counted past them (linear
    quantile at position q (m - 1) of m sorted values: unbounded where it reaches past the
    n-th)."""
    ran = [i for i in at if i is not None]
    reasons = [str(why[i]) for i in ran if why[i]]
    unbounded = int(sum(bool(beyond[i]) for i in ran))
    counts: dict[str, int] = {}
    for r in reasons:
        counts[r] = counts.get(r, 0) + 1
    text = (next(iter(counts)) if len(counts) == 1
            else "; ".join(f"{k} {r}" for r, k in counts.items()))
    m = n + unbounded
    past = [f"p{round(100 * q):02d}" for q in QUANTILES
            if unbounded and math.ceil(round(q * (m - 1), 9)) > n - 1]
    return {"points": len(ran), "without_value": len(reasons), "why": text,
            "unbounded": unbounded, "unbounded_quantiles": past}


def _varies(y: np.ndarray) -> bool:
    """Whether a figure varies beyond round-off: its spread above :data:`ROUND_OFF` x its
    largest size, the rule the printed sd follows (a lowest tension of 129.22343938 and
    129.22343938000003 kN, one unit in the last place apart, printed sd 0 and was ranked
    with a total Sobol' index of 1.07 on the seal drag)."""
    if y.size == 0:
        return False
    return float(np.ptp(y)) > ROUND_OFF * max(float(np.max(np.abs(y))), 1e-300)


def _spearman(x: np.ndarray, y: np.ndarray) -> dict[str, float | None]:
    from scipy.stats import spearmanr

    ok = np.isfinite(y)
    if ok.sum() < 3 or np.ptp(y[ok]) == 0 or np.ptp(x[ok]) == 0:
        return {"rho": None, "rho2": None}
    rho = float(spearmanr(x[ok], y[ok]).statistic)
    return {"rho": rho, "rho2": rho * rho}


def sensitivity(sample: dict, points: np.ndarray, y: np.ndarray) -> dict[str, Any]:
    """The ranking of the sampled inputs for one figure.

    Parameters
    ----------
    sample : dict
        The study's ``sample`` (n, method, seed, axes).
    points : ndarray (n, D)
        The sampled input values, in the design's order.
    y : ndarray (n,)
        The figure at each point (NaN where the run has none).

    Returns
    -------
    dict
        ``method`` and per axis ``{S1, S1_conf, ST, ST_conf}`` (Sobol') or ``{rho, rho2}``
        (Spearman), ranked by ST or |rho| (largest first), and ``note``.
    """
    names = list(sample["axes"])
    d = len(names)
    finite = np.isfinite(y)
    note = ""
    varies = _varies(y[finite])
    if sample["method"] == "sobol" and finite.all() and varies:
        from SALib.analyze import sobol

        problem = {"num_vars": d, "names": names, "bounds": [[0.0, 1.0]] * d}
        sobol_base(len(y), d)  # the design's size, as drawn
        si = sobol.analyze(problem, y, calc_second_order=False, conf_level=CONFIDENCE,
                           seed=int(sample.get("seed", 0)))
        axes = {n: {"S1": float(si["S1"][k]), "S1_conf": float(si["S1_conf"][k]),
                    "ST": float(si["ST"][k]), "ST_conf": float(si["ST_conf"][k])}
                for k, n in enumerate(names)}
        ranked = sorted(names, key=lambda n: -axes[n]["ST"])
        note = _outside_unit(axes)
        return {"method": "sobol (SALib: Saltelli 2010 first-order, Jansen total, "
                          f"{round(100 * CONFIDENCE)} % bootstrap confidence)",
                "axes": axes, "ranking": ranked, "note": note}
    if sample["method"] == "sobol" and not finite.all():
        note = (f"{int((~finite).sum())} of {len(y)} design points have no value: Sobol' "
                "indices need every point; ranked by rank correlation instead")
    elif finite.sum() < 3:  # a rank correlation of fewer points says nothing
        k = int(finite.sum())
        note = f"{k} point{'s' if k != 1 else ''} with a value: a rank correlation needs 3"
    elif not varies:
        note = "the figure does not vary"
    axes = {n: (_spearman(points[:, k], y) if varies else {"rho": None, "rho2": None})
            for k, n in enumerate(names)}
    ranked = sorted(names, key=lambda n: -(abs(axes[n]["rho"]) if axes[n]["rho"] is not None
                                           else -1.0))
    return {"method": "spearman rank correlation (rho; rho^2 a rough share of a monotone "
                      "effect, not a variance share)", "axes": axes, "ranking": ranked,
            "note": note}


def _beyond_unit(value: float) -> str:
    """An index outside [0, 1] shown with the digits that show it outside (1.0005 as 1.0005,
    not as the 1 that three digits give, beside the words "outside [0, 1]")."""
    for digits in (3, 6, 12):
        text = f"{value:.{digits}g}"
        if not 0.0 <= float(text) <= 1.0:
            return text
    return repr(value)


def _outside_unit(axes: dict[str, dict[str, float]]) -> str:
    """A note naming the indices outside [0, 1] (a share of the variance cannot be: sampling
    error); "" when none is."""
    out = [f"{key} of {name} {_beyond_unit(v[key])}" for name, v in axes.items()
           for key in ("S1", "ST") if not -_INDEX_SLACK <= v[key] <= 1 + _INDEX_SLACK]
    if not out:
        return ""
    return (f"{', '.join(out)}: outside [0, 1], which a share of the variance cannot be; "
            "sampling error of the estimate (see S1_conf, ST_conf): a larger sample narrows it")


#: Two-sided 95 % point of the standard normal: Spearman's rho between independent samples
#: of n points is about normal with variance 1 / (n - 1) (Kendall & Stuart, The Advanced
#: Theory of Statistics, vol. 2, 31.19), so |rho| <= 1.96 / sqrt(n - 1) in 95 % of samples.
Z95 = 1.959964


def chance_rho(points: int) -> float:
    """The |rho| an input a figure does not depend on reaches by chance in 5 % of samples of
    ``points`` points: ``Z95 / sqrt(points - 1)`` (``inf`` below 3 points)."""
    return Z95 / math.sqrt(points - 1) if points > 2 else math.inf


def small_sample_note(sample: dict, points: int, with_run: int | None = None) -> str:
    """A note on a Sobol' design whose base sample N is below :data:`SOBOL_N_MIN` (its
    indices are rough); for a Latin hypercube, the |rho| reached by chance
    (:func:`chance_rho`) over the ``with_run`` points whose run has finished (``points``, the
    design's size, when not given): at 24 points a figure that does not read the temperature
    ranked it second with rho 0.31, within the 0.41 of chance; while the study runs, 15 of
    its 24 points give 1.96 / sqrt(14) = 0.52. "" otherwise."""
    if sample.get("method") == "lhs":
        count = points if with_run is None else min(with_run, points)
        of = f" with a run (of the {points} drawn)" if count < points else ""
        lim = chance_rho(count)
        if not math.isfinite(lim):
            return (f"{count} points{of} give no rank correlation to read: "
                    + ("give sample.n >= 3" if count >= points else "wait for more runs"))
        return (f"rank correlations from {count} points{of}: an input a figure does not "
                f"depend on shows |rho| up to about {lim:.2f} by chance (95 %: 1.96 / "
                "sqrt(n - 1), the spread of Spearman's rho between independent samples), so "
                "read a smaller |rho| as no dependence; a larger sample.n narrows it")
    if sample.get("method") != "sobol":
        return ""
    d = len(sample["axes"])
    n_base = points // (d + 2)
    if n_base >= SOBOL_N_MIN:
        return ""
    return (f"base sample N = {n_base} ({points} runs = N (D + 2), D = {d} axes): Sobol' "
            f"indices from fewer than N = {SOBOL_N_MIN} carry a sampling error of the order "
            "of the indices themselves (it falls as 1 / sqrt(N); docs/uncertainty.md), so "
            "read the ranking of clearly separated inputs only, not the shares; for shares "
            f"give sample.n >= {SOBOL_N_MIN * (d + 2)} (N = {SOBOL_N_MIN})")


def _figures(runs: pd.DataFrame, figures: Sequence[str]) -> list[str]:
    """The figures with a value in some run, or none in any because every run lies beyond
    every bound (a transient sag where every run went slack: it was left out, so the reader
    never saw that the sag was unbounded everywhere)."""
    out = []
    for pattern in figures:
        for col, _ in expand(pattern, runs.columns):
            v = pd.to_numeric(runs[col], errors="coerce")
            if v.notna().any() or (len(runs) and no_value(col, runs)[1].any()):
                out.append(col)
    return out


def _exceedance(rows: pd.DataFrame, weights: np.ndarray | None = None
                ) -> list[dict[str, Any]]:
    """Each limit's runs past it of the finished ``rows``, a row counted ``weights`` times
    (the sample points it stands for; once each by default)."""
    w = np.ones(len(rows), dtype=int) if weights is None else np.asarray(weights, dtype=int)
    keep = (rows["status"].astype(str) != "failed").to_numpy() if "status" in rows else (
        np.ones(len(rows), dtype=bool))
    done, w = rows[keep], w[keep]
    out = []
    for cause in CAUSES:
        if cause.key not in LIMITS:
            continue
        mask = (cause.detect(done).fillna(False).astype(bool).to_numpy() if len(done)
                else np.zeros(0, dtype=bool))
        k, n = int(w[mask].sum()), int(w.sum())
        lo, hi = wilson(k, n)
        out.append({"limit": cause.key, "title": cause.title, "runs_past": k, "runs": n,
                    "p": (k / n) if n else None, "ci_low": lo, "ci_high": hi,
                    "interval": f"Wilson score, {round(100 * CONFIDENCE)} %"})
    return out


def _unit(column: str) -> str:
    try:
        return result_fields.field(column).unit
    except KeyError:  # a figure the caller named (not a result field)
        return "-"


def _key(values) -> tuple:
    return tuple(None if v is None or (isinstance(v, float) and math.isnan(v)) else float(v)
                 for v in values)


def _runs_at(rows: pd.DataFrame, s_cols: list[str], points: np.ndarray) -> list[int | None]:
    """The position in ``rows`` of the run at each sample point (None: no run yet).

    A run that stands for several points (grid points whose runs are identical are one run,
    its axis column null where they differ: a ``models.nonlin.*`` axis under ``cema``) is the
    run of every point whose values match its non-null ones."""
    by_known: dict[tuple[bool, ...], dict[tuple, int]] = {}
    for i, r in enumerate(rows[s_cols].itertuples(index=False)):
        key = _key(r)
        known = tuple(v is not None for v in key)
        by_known.setdefault(known, {}).setdefault(
            tuple(v for v in key if v is not None), i)
    # the runs of one point first, then those standing for more points
    order = sorted(by_known, key=lambda known: -sum(known))
    at: list[int | None] = []
    for p in points:
        key = _key(p)
        found = None
        for known in order:
            found = by_known[known].get(tuple(v for v, k in zip(key, known, strict=True) if k))
            if found is not None:
                break
        at.append(found)
    return at


def summarise(study: dict, runs: pd.DataFrame, figures: Sequence[str] = FIGURES
              ) -> dict[str, Any]:
    """The uncertainty answer of a sampled study (module notes) from its stored study
    (``study.json``'s ``study``) and runs table. ``figures``: the figure columns (patterns
    with ``{i}``) to summarise."""
    sample = study.get("sample")
    if not sample:
        return {"sampled": False, "message": "the study has no sample (a sample: block, "
                "SPEC 7.2): its spread is that of its grid, in its runs and compare"}
    axes = study["axes"]
    s_axes = [a for a in axes if a.get("sample")]
    g_axes = [a for a in axes if not a.get("sample")]
    s_cols = [a["column"] for a in s_axes]
    g_cols = [a["column"] for a in g_axes]
    points = np.array([a["values"] for a in s_axes], dtype=float).T  # (n, D), design order
    cols = _figures(runs, figures) if len(runs) else []
    units = {c: _unit(c) for c in cols}
    cells = []
    groups = runs.groupby(g_cols, dropna=False, sort=False) if g_cols and len(runs) else (
        [((), runs)])
    for gkey, rows in groups:
        gkey = gkey if isinstance(gkey, tuple) else (gkey,)
        cells.append(_cell(sample, dict(zip(g_cols, gkey, strict=False)), rows, s_cols,
                           points, {c: units[c] for c in cols}))
    # the points whose run finished (the exceedance's count), fewest over the cells
    finished = [c["exceedance"][0]["runs"] for c in cells if c["exceedance"]]
    return {"sampled": True, "method": sample["method"], "n": sample["n"],
            "points": len(points),
            "note": small_sample_note(sample, len(points), min(finished, default=0)),
            "seed": sample.get("seed", 0), "axes": sample["axes"],
            "confidence": CONFIDENCE, "limits": [c.key for c in CAUSES if c.key in LIMITS],
            "cells": cells}


def _cell(sample: dict, grid: dict, rows: pd.DataFrame, s_cols: list[str],
          points: np.ndarray, units: dict[str, str]) -> dict[str, Any]:
    """One grid cell's answer (:func:`summarise`): its runs ``rows`` matched to the sample
    ``points``, each figure of ``units`` summarised."""
    at = _runs_at(rows, s_cols, points)
    # the sample points each run stands for (1 for a run no point has, as before)
    weights = np.bincount([i for i in at if i is not None], minlength=len(rows))
    weights[weights == 0] = 1
    cell = {"grid": grid, "runs": int(len(rows)),
            "points": int(sum(i is not None for i in at)),
            "points_missing": int(sum(i is None for i in at)),
            "figures": {}, "exceedance": _exceedance(rows, weights), "sensitivity": {}}
    for col, unit in units.items():
        vals = pd.to_numeric(rows[col], errors="coerce").to_numpy(dtype=float)
        y = np.array([vals[i] if i is not None else np.nan for i in at])
        dist = distribution(pd.Series(y))
        without = _without(at, *no_value(col, rows), 0 if dist is None else dist["n"])
        if dist is None:
            if not without["unbounded"]:
                continue
            # no point has a value and some lie beyond every bound: said, every quantile
            # unbounded (or of none)
            dist = {"n": 0, "mean": None, "sd": None, "min": None, "max": None,
                    "quantiles": {f"p{round(100 * q):02d}": None for q in QUANTILES}}
            cell["figures"][col] = {"unit": unit, **dist, **without}
            cell["sensitivity"][col] = {"method": "none", "axes": {}, "ranking": [],
                                        "note": "no sample point has a value to rank"}
            continue
        cell["figures"][col] = {"unit": unit, **dist, **without}
        cell["sensitivity"][col] = sensitivity(sample, points, y)
    return cell


def _g(value: Any) -> str:
    return "-" if value is None else f"{gnum(value)}"


#: An index or rank correlation smaller than this in magnitude is round-off of zero (SALib's
#: total index of an input a figure does not read came out 2.031e-30, or -1e-31).
ROUND_OFF = 1e-12


def index_text(value: Any, digits: int = 4) -> str:
    """A sensitivity index (S1, ST) or rho as text: ``digits`` significant figures, ``0`` for
    round-off of zero (``|value| < ROUND_OFF``, either sign), ``-`` for none. The JSON keeps
    the float."""
    if value is None or not math.isfinite(value):
        return "-"
    return "0" if abs(value) < ROUND_OFF else f"{value:.{digits}g}"


def sd_text(sd: float, mean: float) -> str:
    """A standard deviation as text: 3 significant figures, ``0`` for the round-off of a
    figure that does not vary (below :data:`ROUND_OFF` times |mean|: a lowest tension of
    39.97 kN equal in every run gave sd 7.29e-15). The JSON keeps the float."""
    return "0" if abs(sd) < ROUND_OFF * abs(mean) else f"{gnum(sd, 3)}"


def runs_text(cell: dict) -> str:
    """``20 runs``; where runs stand for several sample points each (a run merged over
    points that differ only in an axis it does not read), ``1 run standing for 20 sample
    points``."""
    runs = cell["runs"]
    text = f"{runs} run{'s' if runs != 1 else ''}"
    points = cell.get("points", runs)
    return text if points == runs else f"{text} standing for {points} sample points"


def without_text(d: dict) -> str:
    """The points of a figure without a value, said beside its quantiles: ``n 30 of 32; 2
    without a value: slack, sag unbounded (past every bound: p95 of all 32 is unbounded);
    mean, sd and quantiles are of the 30 with a value`` ("" when every point has one)."""
    if not d.get("without_value"):
        return ""
    text = f"n {d['n']} of {d['points']}; {d['without_value']} without a value: {d['why']}"
    if not d["n"]:
        return text + " (past every bound: every quantile of all of them is unbounded)"
    if d.get("unbounded"):
        m = d["n"] + d["unbounded"]
        qs = d["unbounded_quantiles"]
        text += (f" (past every bound: {' and '.join(qs)} of all {m} "
                 f"{'is' if len(qs) == 1 else 'are'} unbounded)" if qs else
                 f" (past every bound: above every quantile shown of all {m})")
    return f"{text}; mean, sd and quantiles are of the {d['n']} with a value"


def format_text(result: dict) -> str:
    """The answer as text: per grid cell, each figure's distribution and top-ranked inputs,
    then the exceedance probabilities."""
    if not result.get("sampled"):
        return result.get("message", "not a sampled study")
    drawn = result.get("points", result["n"])
    asked = "" if drawn == result["n"] else (
        f" (n = {result['n']}: the nearest Saltelli design, N (D + 2) with N a power of two)")
    lines = [f"sample: {drawn} points{asked}, method {result['method']}, seed {result['seed']}; "
             f"axes {', '.join(result['axes'])}"]
    if result.get("note"):
        lines.append(f"note: {result['note']}")
    for cell in result["cells"]:
        where = ", ".join(f"{k}={v}" for k, v in cell["grid"].items()) or "all runs"
        lines += ["", f"{where}: {runs_text(cell)}"
                  + (f" ({cell['points_missing']} sample points without a run yet)"
                     if cell["points_missing"] else "")]
        lines.append("  figure                         unit     mean       sd      p05      "
                     "p50      p95  ranking")
        for col, d in cell["figures"].items():
            q = d["quantiles"]
            sens = cell["sensitivity"][col]
            if not d["n"]:  # no value at any point: beyond every bound
                lines.append(f"  {col:<30} {d['unit']:<5} {'-':>8} {'-':>8} {'-':>8} "
                             f"{'-':>8} {'-':>8}")
                lines.append(f"    {without_text(d)}")
                continue
            key = "ST" if sens["method"].startswith("sobol") else "rho"
            rank = ", ".join(f"{n} {index_text(sens['axes'][n][key])}"
                             for n in sens["ranking"][:3])
            lines.append(f"  {col:<30} {d['unit']:<5} {d['mean']:>8.4g} "
                         f"{sd_text(d['sd'], d['mean']):>8} "
                         f"{q['p05']:>8.4g} {q['p50']:>8.4g} {q['p95']:>8.4g}  {key}: {rank}")
            if d.get("without_value"):
                lines.append(f"    {without_text(d)}")
            if sens.get("note"):
                lines.append(f"    note: {sens['note']}")
        # the exceedance counts sample points (a run standing for several counts for each)
        lines.append("  limit                                  past / points      p   "
                     f"{round(100 * result['confidence'])} % interval")
        for e in cell["exceedance"]:
            lines.append(f"  {e['title']:<38} {e['runs_past']:>5} / {e['runs']:<5} "
                         f"{_g(e['p']):>8}   [{e['ci_low']:.3f}, {e['ci_high']:.3f}]")
    return "\n".join(lines)
