"""The design report's uncertainty section of a sampled study (SPEC 7.4; docs/uncertainty.md):
per grid cell the distribution of each deciding figure, the probability of passing each
design limit with its interval, the sensitivity ranking, and two figures (histograms of the
deciding figures, the ranking as bars). The numbers are
:func:`beltstudy.service.uncertainty.summarise`'s."""

from __future__ import annotations

import html
from typing import Any

import numpy as np
import pandas as pd

from beltstudy.service.uncertainty import index_text, runs_text, summarise, without_text
from beltstudy.service.web.numbers import eng

__all__ = ["uncertainty_section", "histograms_figure", "ranking_figure", "FIGURE_COLUMNS"]

#: The figures drawn as histograms (those the runs carry, up to six).
FIGURE_COLUMNS = ("t_max_start_kn", "t_max_stop_kn", "t_min_start_kn", "t_min_stop_kn",
                  "power_kw", "stop_time_s", "slip_margin_min_dyn", "safety_factor_dyn",
                  "t_max_kn", "t_min_kn", "slip_margin", "safety_factor")


def _e(value: Any) -> str:
    return html.escape(str(value), quote=True)


def _g(value: Any, digits: int = 4) -> str:
    """A number as the report writes numbers (:func:`~beltstudy.service.web.numbers.eng`:
    ``17 000``, ``6.3 × 10⁻⁵``, never ``1.7e+04``), ``-`` for none."""
    return eng(value, "", digits, empty="-")


def _index(value: Any, digits: int = 2) -> str:
    """A sensitivity index or rank correlation as the report writes numbers: ``0`` for
    round-off of zero (:func:`~beltstudy.service.uncertainty.index_text`), else :func:`_g`
    (a ranking read ``(6.3e-05)``)."""
    text = index_text(value, digits)
    return text if text in ("0", "-") else _g(value, digits)


def histograms_figure(cell: dict, runs: pd.DataFrame, title: str):
    """Histograms of up to six deciding figures of one cell's runs, p05/p50/p95 marked."""
    import matplotlib.pyplot as plt

    # a figure no point has a value of (every run beyond every bound) has no histogram
    cols = [c for c in FIGURE_COLUMNS if c in cell["figures"] and cell["figures"][c]["n"]][:6]
    fig, axs = plt.subplots(2, 3, figsize=(11, 6), squeeze=False)
    for ax, col in zip(axs.flat, cols, strict=False):
        v = pd.to_numeric(runs[col], errors="coerce").dropna().to_numpy()
        d = cell["figures"][col]
        spread = np.ptp(v) > 1e-9 * max(abs(v).max(), 1.0)
        ax.hist(v, bins=min(30, max(5, len(v) // 8)) if spread else 1,
                range=None if spread else (v[0] - 0.5, v[0] + 0.5), color="#4a7ab5",
                alpha=0.85)
        for q, style in (("p05", ":"), ("p50", "-"), ("p95", ":")):
            ax.axvline(d["quantiles"][q], color="k", ls=style, lw=1)
        ax.set_title(f"{col} [{d['unit']}]", fontsize=9)
        ax.tick_params(labelsize=8)
    for ax in list(axs.flat)[len(cols):]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def ranking_figure(cell: dict, title: str):
    """The sensitivity of each drawn figure to each sampled input as grouped bars (S_T, or
    |rho| for a rank ranking)."""
    import matplotlib.pyplot as plt

    cols = [c for c in FIGURE_COLUMNS if c in cell["sensitivity"]
            and cell["sensitivity"][c]["axes"]][:6]
    names = list(cell["sensitivity"][cols[0]]["axes"]) if cols else []
    fig, ax = plt.subplots(figsize=(11, 4))
    width = 0.8 / max(len(names), 1)
    for k, name in enumerate(names):
        vals = []
        for col in cols:
            s = cell["sensitivity"][col]
            a = s["axes"][name]
            v = a.get("ST") if "ST" in a else (abs(a["rho"]) if a.get("rho") is not None
                                                  else 0.0)
            vals.append(v if v is not None else 0.0)
        ax.bar(np.arange(len(cols)) + k * width, vals, width, label=name)
    ax.set_xticks(np.arange(len(cols)) + width * (len(names) - 1) / 2)
    ax.set_xticklabels(cols, fontsize=8, rotation=15)
    method = cell["sensitivity"][cols[0]]["method"] if cols else ""
    ax.set_ylabel("total index S_T" if method.startswith("sobol") else "|Spearman rho|")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return fig


def _cell_tables(cell: dict, table, n_cell) -> str:
    rows = []
    for col, d in cell["figures"].items():
        q = d["quantiles"]
        sens = cell["sensitivity"][col]
        key = "ST" if sens["method"].startswith("sobol") else "rho"
        rank = ", ".join(f"{n} ({_index(sens['axes'][n][key])})"
                        for n in sens["ranking"][:3]) if d["n"] else without_text(d)
        rows.append([f"<code>{_e(col)}</code>", _e(d["unit"]), n_cell(d["mean"]),
                     n_cell(d["sd"]), n_cell(q["p05"]), n_cell(q["p50"]), n_cell(q["p95"]),
                     _e(rank)])
    dist = table(["figure", "unit", "mean", "sd", "p05", "p50", "p95",
                  "inputs that matter most"], rows, "runs")
    ex = [[_e(e["title"]), n_cell(e["runs_past"]), n_cell(e["runs"]), n_cell(e["p"]),
           _e(f"{e['ci_low']:.3f} to {e['ci_high']:.3f}")] for e in cell["exceedance"]]
    # the exceedance counts sample points (a run standing for several counts for each)
    return dist + table(["design limit", "points past it", "points", "probability",
                         "interval (Wilson, 95 %)"], ex, "runs")


def _ranking_notes(cell: dict) -> list[str]:
    """Each figure's ranking note once, with the figures it is about (a note is per figure:
    the first figure's alone hid a power index of 1.2 outside [0, 1] that ``beltstudy
    uncertainty`` names)."""
    by_note: dict[str, list[str]] = {}
    for col, sens in cell["sensitivity"].items():
        if sens.get("note"):
            by_note.setdefault(sens["note"], []).append(col)
    return [f"{', '.join(cols)}: {note}" for note, cols in by_note.items()]


def uncertainty_section(study: dict, runs: pd.DataFrame, table, n_cell, png, figure) -> str:
    """The section's markup; ``table``, ``n_cell``, ``png`` and ``figure`` are the report's
    own helpers (so its tables and figures look like the rest)."""
    result = summarise(study, runs)
    if not result.get("sampled"):
        return f"<p class=muted>{_e(result['message'])}</p>"
    axes = "; ".join(f"<code>{_e(k)}</code> {_e(v['dist'])}("
                     + ", ".join(f"{_e(p)} {_g(x)}" for p, x in v.items() if p != "dist") + ")"
                     for k, v in result["axes"].items())
    out = [f"<p>{result['n']} points drawn by {_e(result['method'])} (seed "
           f"{result['seed']}): {axes}. Distributions of the deciding figures, the probability "
           "that a run is past each design limit with its 95 % Wilson interval, and the "
           "sampled inputs ranked by their share of each figure's variance (method named "
           "per figure; docs/uncertainty.md).</p>"]
    if result.get("note"):
        out.append(f"<p class=muted>note: {_e(result['note'])}</p>")
    g_cols = [a["column"] for a in study["axes"] if not a.get("sample")]
    for cell in result["cells"]:
        where = ", ".join(f"{k} = {v}" for k, v in cell["grid"].items()) or "all runs"
        mask = pd.Series(True, index=runs.index)
        for c in g_cols:
            mask &= runs[c].astype(str) == str(cell["grid"].get(c))
        part = runs[mask]
        out.append(f"<h3>{_e(where)}: {_e(runs_text(cell))}</h3>")
        sens = next(iter(cell["sensitivity"].values()), None)
        if sens is not None:
            out.append(f"<p class=muted>ranking: {_e(sens['method'])}"
                       + "".join(f"; {_e(t)}" for t in _ranking_notes(cell)) + "</p>")
        out.append(_cell_tables(cell, table, n_cell))
        if cell["figures"] and len(part):
            out.append(figure(png(lambda c=cell, p=part, w=where: histograms_figure(
                c, p, f"{w}: distributions (lines: p05, p50, p95)")),
                "Histograms of the deciding figures over the sample; solid line the median, "
                "dotted the 5 % and 95 % quantiles.", "distributions"))
            out.append(figure(png(lambda c=cell, w=where: ranking_figure(
                c, f"{w}: sensitivity to the sampled inputs")),
                "Share of each figure's variance each sampled input accounts for (Sobol' "
                "total index), or the size of its rank correlation.", "ranking"))
    return "".join(out)
