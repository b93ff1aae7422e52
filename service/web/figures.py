"""Figures of a stored study or run: read the Parquet, pick the figure, render PNG or SVG.

The plot routes and notebooks share these. Every figure is drawn under one lock (pyplot
keeps global state) and closed after rendering.
"""

from __future__ import annotations

import difflib
import io
import threading

import pandas as pd

from beltstudy.engine import build_loop, parse_conveyor, parse_scenario
from beltstudy.service import charts
from beltstudy.service.charts import RUN_PLOTS, STUDY_PLOTS
from beltstudy.service.errors import Invalid, NotFound
from beltstudy.service.grid.expand import ResolvedStudy
from beltstudy.service.store import query
from beltstudy.service.studies import StudyService, study_models
from beltstudy.service.web.verdicts import never_going

__all__ = [
    "STUDY_PLOTS",
    "RUN_PLOTS",
    "FORMATS",
    "render",
    "study_figure",
    "figure_of",
    "run_figure",
    "check_name",
    "figure_columns",
    "FIGURE_COLUMNS",
]

#: Output formats and their media types.
FORMATS = {"png": "image/png", "svg": "image/svg+xml"}

_lock = threading.Lock()


def check_name(name: str, valid: dict) -> None:
    """:class:`Invalid` naming the valid plot names when ``name`` is not one of them."""
    if name not in valid:
        close = difflib.get_close_matches(name, list(valid), n=1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        if not close and valid is RUN_PLOTS and name in STUDY_PLOTS:
            hint = " (a plot of the whole study: /studies/{id}/plots/" + name + ")"
        elif not close and valid is STUDY_PLOTS and name in RUN_PLOTS:
            hint = " (a plot of one run: /studies/{id}/runs/{run_id}/plots/" + name + ")"
        raise Invalid(f"name: unknown plot '{name}'{hint}; valid: {', '.join(valid)}")


def render(make, fmt: str = "png") -> bytes:
    """Draw ``make()`` and return the figure as ``fmt`` bytes (the figure is closed)."""
    if fmt not in FORMATS:
        raise Invalid(f"format: unknown format '{fmt}'; valid: {', '.join(FORMATS)}")
    # deferred: matplotlib loads only when a figure is drawn
    import matplotlib
    import matplotlib.pyplot as plt

    # SVG keeps its text as text (smaller, searchable); matplotlib escapes it as XML.
    with _lock, matplotlib.rc_context({"svg.fonttype": "none"}):
        fig = make()
        try:
            buf = io.BytesIO()
            fig.savefig(buf, format=fmt, dpi=100)
        finally:
            plt.close(fig)
    return buf.getvalue()


def _text(value) -> str:
    """User text safe for matplotlib (no mathtext)."""
    return str(value).replace("$", r"\$")


def resolved_study(service: StudyService, study_id: str) -> ResolvedStudy:
    """The resolved study of ``study_id`` (a study id is a hash of its content: cached)."""
    return service.resolved(study_id)


def _pick_models(runs: pd.DataFrame, baseline: str | None, candidate: str | None):
    models = sorted(set(runs["friction_model"].dropna())) if "friction_model" in runs else []
    if baseline is None:  # not the candidate given: a ratio needs two models
        pool = [m for m in models if m != candidate] or models
        baseline = "cema" if "cema" in pool or not pool else pool[0]
    if candidate is None:
        others = [m for m in models if m != baseline]
        # no other model (a study of one model): the baseline itself, so that the figure
        # says a ratio needs two models (not a 422 for 'nonlin' the study never ran); no
        # models at all (no runs yet): the defaults
        candidate = ("nonlin" if "nonlin" in others or not models
                     else others[0] if others else baseline)
    return baseline, candidate


#: The result columns each figure of the study page reads besides the run id, the status,
#: the friction model, the temperature and the study's axes: the figure is drawn from those
#: columns only (a few of the 337 of a runs row), not from every column of every run.
FIGURE_COLUMNS: dict[str, tuple[str, ...]] = {
    "power-temperature": ("power_kw",),
    "peak-dynamic-tension": ("t_max_stop_kn", "t_min_stop_kn", "t_max_dyn_kn", "t_min_dyn_kn",
                             "stop_time_s", "stop_time_target_s", "stop_window_s"),
    "ratio": tuple(query.DEFAULT_METRICS),
}


def figure_columns(doc: dict, name: str, stored: list[str]) -> list[str] | None:
    """The columns of the runs table figure ``name`` of study ``doc`` needs, of those
    ``stored``; None: every column (a figure not in :data:`FIGURE_COLUMNS`)."""
    if name not in FIGURE_COLUMNS:
        return None
    axes = [a["column"] for a in (doc.get("study") or {}).get("axes", [])]
    wanted = ["run_id", "status", "friction_model", "temperature_c", *axes,
              *FIGURE_COLUMNS[name]]
    return [c for c in dict.fromkeys(wanted) if c in stored]


def study_figure(
    service: StudyService,
    study_id: str,
    name: str,
    baseline: str | None = None,
    candidate: str | None = None,
):
    """A callable drawing plot ``name`` of a study (checks the id, then the name) from the
    columns of the runs table it needs (:func:`figure_columns`)."""
    doc = service.store.read(study_id)
    check_name(name, STUDY_PLOTS)
    models = study_models(doc)
    for label, given in (("baseline", baseline), ("candidate", candidate)):
        # given: a model the study runs (an empty or unknown value is a 422 naming it)
        if given is not None and query.model_name(given, label) not in models:
            raise Invalid(f"{label}: model '{given}' is not in this study; it has: "
                          + ", ".join(models))
    if name == "ratio" and baseline is not None and candidate is not None:
        query.model_pair(baseline, candidate)  # the same model twice: a 422 as /compare's
    baseline = query.model_name(baseline, "baseline") if baseline is not None else None
    candidate = query.model_name(candidate, "candidate") if candidate is not None else None
    columns = figure_columns(doc, name, service.store.runs_columns(study_id))
    return figure_of(doc, service.store.read_runs(study_id, columns=columns), name, baseline,
                     candidate, study_id)


def figure_of(doc: dict, runs: pd.DataFrame, name: str, baseline: str | None = None,
              candidate: str | None = None, study_id: str = ""):
    """A callable drawing plot ``name`` of a stored study document ``doc`` and its runs
    table (the design report draws from these without asking the store again)."""
    check_name(name, STUDY_PLOTS)
    study_id = study_id or doc.get("id", "")
    title = _text(doc.get("name", study_id))
    axes = [a["column"] for a in doc.get("study", {}).get("axes", [])]
    zips: dict[int, list[str]] = {}
    for a in doc.get("study", {}).get("axes", []):
        if a.get("group") is not None:
            zips.setdefault(a["group"], []).append(a["column"])
    groups = list(zips.values())
    if name == "power-temperature":
        temperature = (doc.get("study", {}).get("scenario") or {}).get("temperature_c")
        return lambda: charts.power_temperature_figure(
            runs, f"{title}: power against temperature", temperature, axes=axes, groups=groups
        )
    if name in ("peak-dynamic-tension", "start-stop-peaks"):
        if not doc.get("study", {}).get("dynamics", True):
            return lambda: charts.message_figure(charts.NO_TRANSIENT, f"{title}: peak tension")
        if name == "start-stop-peaks":
            return lambda: charts.phase_peaks_figure(
                runs, f"{title}: peak and lowest tension of the start and the stop",
                axes=axes, groups=groups, never_going=never_going(runs))
        return lambda: charts.peak_dynamic_tension_figure(
            runs, f"{title}: peak and lowest tension against stop time", axes=axes,
            groups=groups)
    base, cand = _pick_models(runs, baseline, candidate)
    if not len(runs):
        return lambda: charts.message_figure("no finished runs yet", f"{title}: ratio")
    if base == cand:
        return lambda: charts.message_figure(
            f"a ratio needs two friction models in the grid; this study ran {_text(base)} "
            "only", f"{title}: ratio"
        )
    # those some run has a value of (compare refuses a metric named without any)
    metrics = [m for m in query.DEFAULT_METRICS
               if m in runs.columns and pd.api.types.is_float_dtype(runs[m])
               and runs[m].notna().any()]
    summary = query.compare(runs, axes, base, cand, metrics, study_id)["summary"]
    label = f"{title}: {_text(cand)} / {_text(base)} per axis value"
    return lambda: charts.ratio_figure(summary, _text(base), _text(cand), label)


def run_figure(service: StudyService, study_id: str, run_id: str, name: str):
    """A callable drawing plot ``name`` of one run (checks the study, the name, the run)."""
    doc = service.store.read(study_id)
    check_name(name, RUN_PLOTS)
    study = resolved_study(service, study_id)
    spec = next((r for r in study.runs if r.run_id == run_id), None)
    if spec is None:
        raise NotFound(f"run '{run_id}' of study '{study_id}' not found")
    axes = ", ".join(f"{k}={charts._text(v)}" for k, v in spec.axes.items()
                     if k != "friction_model")
    title = _text(f"{doc.get('name', study_id)} · {spec.model}" + (f" · {axes}" if axes else ""))
    if name == "steady-profile":
        # stored with the run; recomputed (steady solve only) for runs stored before
        profile, _source = service.run_profile(study_id, run_id)
        if not len(profile):
            runs = service.store.read_runs(study_id, columns=["run_id", "message"])
            row = runs[runs["run_id"] == run_id]
            message = row["message"].iloc[0] if len(row) else ""
            return lambda: charts.message_figure(
                _text(f"no steady solution: {message}" if message else "no steady profile"),
                title)
        return lambda: charts.steady_profile_figure(profile, title)
    if not study.dynamics:
        return lambda: charts.message_figure(charts.NO_TRANSIENT, title)
    service.require_row(study_id, run_id)  # 409 for a run not finished yet
    runs = service.store.read_runs(study_id)
    row = runs[runs["run_id"] == run_id]
    ts = service.store.read_timeseries(study_id, run_id)
    # the surface: stored, or recomputed from the run's inputs
    surface = service.run_surface(study_id, run_id)[0]
    if not len(ts) and not len(surface):
        return lambda: charts.message_figure("no transient data for this run", title)
    extremes = {}
    if len(row):
        for label, column, size, time in (
                ("highest tension", "t_max_dyn_at_m", "t_max_dyn_kn", "t_max_dyn_time_s"),
                ("lowest tension", "t_min_dyn_at_m", "t_min_dyn_kn", "t_min_dyn_time_s")):
            value = row[column].iloc[0] if column in row else None
            kn = row[size].iloc[0] if size in row else None
            when = row[time].iloc[0] if time in row else None
            extremes[label] = None if pd.isna(value) else (
                float(value), None if kn is None or pd.isna(kn) else float(kn),
                None if when is None or pd.isna(when) else float(when))
    locate = _locator(spec)
    return lambda: charts.transient_figure(ts, surface, title, extremes=extremes, locate=locate)


def _locator(spec):
    """``s_m -> (strand, distance from the tail)`` on the run's own loop (None if it cannot
    be cut: the figure then names loop positions)."""

    try:
        scenario = parse_scenario(spec.scenario)
        n = None if scenario.elements == "auto" else int(scenario.elements)
        return build_loop(parse_conveyor(spec.conveyor), scenario.load, n_elements=n).where
    except Exception:  # a run that cannot even be cut into elements
        return None
