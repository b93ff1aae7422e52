"""Figures shared by the CLI, the REST routes and the pages (matplotlib, Agg backend).

Every function returns a matplotlib Figure; callers save it as PNG or SVG.
:data:`STUDY_PLOTS` and :data:`RUN_PLOTS` name the figures of a study and of a run (the names
the plot routes take).
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pandas as pd

from beltstudy.engine.wording import gnum

#: Plot names of a study, with what they show.
STUDY_PLOTS = {
    "power-temperature": "power against temperature, a line per combination of the other "
    "varying axes (Fig. 2)",
    "peak-dynamic-tension": "peak and lowest tension of the stop against the stop time, a line "
    "per combination of the other varying axes",
    "ratio": "candidate / baseline ratio per axis value (default nonlin over cema)",
    "start-stop-peaks": "peak and lowest tension of the start and of the stop against a study "
    "axis, a point per run (colour per friction model, marker per other axis values)",
}
#: Plot names of a run.
RUN_PLOTS = {
    "steady-profile": "steady tension along the loop with the elevation profile (Fig. 1)",
    "transient": "tension at eight points round the loop and at the highest and lowest tension, "
    "belt speed below (Fig. 4)",
}


def _plt():
    # deferred: matplotlib loads only when a figure is drawn
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def steady_profile_figure(profile, title: str = ""):
    """Elevation profile with the carry and return tensions along it (Harrison 2008, Fig. 1).

    ``profile`` is the steady profile table (``s_m``, ``strand``, ``elevation_m``,
    ``tension_kn``, ``sag_pct``). Distances are along the conveyor from the tail [m]: the
    return strand is drawn at the position it passes over.
    """
    plt = _plt()
    s = np.asarray(profile["s_m"], dtype=float)
    strand = np.asarray(profile["strand"])
    z = np.asarray(profile["elevation_m"], dtype=float)
    t = np.asarray(profile["tension_kn"], dtype=float)
    carry = strand == "carry"
    ret = strand == "return"
    length = float(s[carry].max()) if carry.any() else float(s.max())
    s_head_end = float(s[strand == "head"].max()) if (strand == "head").any() else length
    x_carry = s[carry]
    x_ret = length - (s[ret] - s_head_end)
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(9, 6),
                                   gridspec_kw={"height_ratios": [1, 2]})
    ax1.plot(np.concatenate(([0.0], x_carry)), np.concatenate(([0.0], z[carry])), color="0.3")
    ax1.fill_between(np.concatenate(([0.0], x_carry)), np.concatenate(([0.0], z[carry])),
                     min(0.0, float(z.min())), color="0.85")
    ax1.set_ylabel("elevation [m]")
    ax1.grid(alpha=0.3)
    if title:
        ax1.set_title(wrap_title(title))
    ax2.plot(x_carry, t[carry], label="carry", color="tab:red")
    ax2.plot(x_ret, t[ret], label="return", color="tab:blue")
    ax2.set_xlabel("distance from the tail along the conveyor [m]")
    ax2.set_ylabel("belt tension [kN]")
    ax2.set_ylim(bottom=0.0)
    ax2.grid(alpha=0.3)
    ax2.legend(loc="best")
    fig.tight_layout()
    return fig


# ---------------------------------------------------------------------------------------------
# Study and run figures for the pages and the plot routes (service/web).

#: Message of the figures drawn for a study or run without transient results.
NO_TRANSIENT = "no transient data (dynamics: false)"
#: Lines in one panel before a comparison figure is split into small multiples.
MAX_LINES = 8
#: Characters per line of a figure title (longer titles wrap instead of being cut off).
TITLE_WIDTH = 72


def wrap_title(text: str, width: int = TITLE_WIDTH) -> str:
    """A figure title wrapped onto several lines (no part of it is cut off)."""

    return "\n".join(textwrap.wrap(str(text), width=width, break_long_words=True)) or ""


def message_figure(message: str, title: str = "", figsize=(8, 4.5)):
    """A figure holding only ``message`` (no data to draw) and an optional title."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=figsize)
    ax.set_axis_off()
    ax.text(0.5, 0.5, message, ha="center", va="center", fontsize=13, color="0.3",
            wrap=True, transform=ax.transAxes)
    if title:
        ax.set_title(wrap_title(title))
    return fig


def _numeric(df, column: str):
    if column not in df.columns:
        return None
    values = pd.to_numeric(df[column], errors="coerce")
    return values if values.notna().any() else None


def no_rows_message(runs) -> str:
    """Why a study figure has no point: no run finished yet, or every finished run failed
    (a failed run has no results), never 'dynamics: false' for a dynamic study."""
    n = len(runs)
    if not n:
        return "no finished runs yet"
    return f"no results: all {n} finished run{'s' if n != 1 else ''} failed (see their messages)"


def _ok_rows(runs):
    if "status" in runs.columns:
        return runs[runs["status"] != "failed"]
    return runs


def _text(value) -> str:
    """An axis value in a legend: numbers short, a merged (null) value as 'any'."""

    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "any"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def default_axis_columns(runs) -> list[str]:
    """The input columns of a runs table when the study's axes are not given: the design
    card's named axes and every dotted axis column present."""
    named = ("friction_model", "temperature_c", "load", "belt_type", "stop_time_target_s")
    return [c for c in runs.columns if c in named or "." in c]


def varying(df, columns: list[str]) -> list[str]:
    """The columns of ``columns`` with more than one value in ``df`` (null counts as one)."""
    out = []
    for c in columns:
        if c in df.columns and df[c].astype(str).nunique(dropna=False) > 1:
            out.append(c)
    return out


def unchanging(df, inputs: list[str], y: str, others: list[str], rtol: float = 1e-9
               ) -> list[str]:
    """The columns of ``others`` that never change ``y``: runs that differ only in such a
    column (all ``inputs`` and the other columns equal) have the same ``y`` (a stop time in a
    steady result, say). Their lines would lie on top of each other, so they are drawn once;
    the figure says which axes those are. ``inputs`` are the input columns behind the x axis
    (not the x values themselves: an achieved stop time is a result)."""

    out: list[str] = []
    keep = list(others)
    data = df.dropna(subset=[y])
    if not len(data):
        return out
    text = {k: data[k].astype(str) for k in [*inputs, *others] if k in data.columns}
    changed = True
    while changed:  # dropping one axis can make another comparable (a merged null value)
        changed = False
        for c in list(keep):
            rest = [k for k in (*inputs, *keep) if k != c and k in text]
            # a group compares c only where it holds two or more values of c
            grouped = data.assign(__c=text[c], **{f"__{k}": text[k] for k in rest})
            if rest:
                g = grouped.groupby([f"__{k}" for k in rest], dropna=False)
                spread = g[y].agg(["min", "max"]).assign(values=g["__c"].nunique())
            else:
                spread = pd_frame(data[y]).assign(values=grouped["__c"].nunique())
            compared = spread["values"] >= 2
            scale = np.maximum(np.abs(spread["max"]), 1e-12)
            if compared.any() and ((spread["max"] - spread["min"]) <= rtol * scale).all():
                out.append(c)
                keep = [k for k in keep if k != c]
                changed = True
    return [c for c in others if c in out]


def pd_frame(values):
    """min and max of one series as a one-row frame."""

    return pd.DataFrame({"min": [values.min()], "max": [values.max()]})


def series(df, x: str, y: str, others: list[str]):
    """The points of ``df`` as lines: one per combination of the ``others`` columns, sorted
    by ``x``. Returns ``[(key dict, x array, y array)]``; points with another value of any
    of ``others`` are never on one line."""
    df = df.dropna(subset=[x, y])
    if not others:
        part = df.sort_values(x, kind="stable")
        return [({}, part[x].to_numpy(float), part[y].to_numpy(float))] if len(part) else []
    keyed = df.assign(**{f"__{c}": df[c].astype(str) for c in others})
    out = []
    for _, part in keyed.groupby([f"__{c}" for c in others], sort=True, dropna=False):
        part = part.sort_values(x, kind="stable")
        key = {c: part[c].iloc[0] for c in others}
        out.append((key, part[x].to_numpy(float), part[y].to_numpy(float)))
    return out


def _label(key: dict, skip: tuple[str, ...] = ()) -> str:
    parts = []
    for c, v in key.items():
        if c in skip:
            continue
        parts.append(_text(v) if c == "friction_model" else f"{c} {_text(v)}")
    return ", ".join(parts) or "all runs"


#: Most panels of one comparison figure.
MAX_PANELS = 12


def _panels(df, others: list[str]):
    """Small multiples: when one panel would hold more than :data:`MAX_LINES` lines, a panel
    per combination of the first of ``others`` (then the first two, ...) until each panel's
    lines fit or :data:`MAX_PANELS` would be passed. Returns ``[(title part, rows, the others
    drawn as lines in it)]``."""
    def combos(cols):
        return df[cols].astype(str).drop_duplicates().shape[0] if cols else 1

    k = 0
    while (k < len(others) - 1 and combos(others) > MAX_LINES * combos(others[:k])
           and combos(others[:k + 1]) <= MAX_PANELS):
        k += 1
    if k == 0:
        return [("", df, others)]
    split, rest = others[:k], others[k:]
    out = []
    keys = [df[c].astype(str) for c in split]
    for _value, part in df.groupby(keys, sort=True, dropna=False):
        first = part.iloc[0]
        label = ", ".join(_text(first[c]) if c == "friction_model" else f"{c} {_text(first[c])}"
                          for c in split)
        out.append((label, part, rest))
    return out


#: Room below zero of a figure drawn from zero (``ymin0``), as a share of its top: a point
#: at zero keeps its whole marker inside the frame.
ZERO_ROOM = 0.04


def comparison_figure(df, x: str, y: str, others: list[str], xlabel: str, ylabel: str,
                      title: str, y2: str | None = None, y2label: str = "", ymin0=False,
                      inputs: list[str] | None = None, notes: list[str] | None = None):
    """Lines of ``y`` (and ``y2`` below it) against ``x``, one per combination of
    ``others``, in small multiples when there are many (one colour per combination in every
    panel, one legend). Axes that change neither ``y`` nor ``y2`` (:func:`unchanging`, with
    ``inputs`` the input columns behind ``x``, default ``x`` itself) are drawn once and named
    under the figure with the ``notes``. A combination with more than one point at one ``x``
    (a sampled study's runs at one temperature) is drawn as points, not joined."""

    plt = _plt()
    inputs = [x] if inputs is None else [c for c in inputs if c in df.columns]
    same = [c for c in unchanging(df, inputs, y, others)
            if not y2 or c in unchanging(df, inputs, y2, others)]
    others = [c for c in others if c not in same]
    df = df.drop_duplicates(subset=[x, *others], keep="first") if same else df
    panels = _panels(df, others)
    lines = panels[0][2]
    keys = sorted({tuple(str(v) for v in row) for row in df[lines].itertuples(index=False)}
                  ) if lines else [()]
    ncols = min(len(panels), 3)
    nrows_p = math.ceil(len(panels) / ncols)
    rows = nrows_p * (2 if y2 else 1)
    longest = max((len(_label({c: v for c, v in zip(lines, k, strict=True)})) for k in keys),
                  default=10)
    legend_in = min(0.06 * longest + 0.9, 5.0)  # the legend's column beside the panels
    fig, grid = plt.subplots(rows, ncols, figsize=(5.4 * ncols + 1.0 + legend_in,
                                                   3.6 * rows + 0.9),
                             squeeze=False, sharex=True)
    # colour: one per value of the first line axis; marker and dash: one per combination of
    # the rest (each colour and each marker one legend entry, none repeated)
    ckeys = sorted({k[:1] for k in keys})
    mkeys = sorted({k[1:] for k in keys})
    colours = dict(zip(ckeys, _palette(len(ckeys)), strict=True))
    styles = ("-", "--", ":", "-.")
    look = {m: (MARKERS[i % len(MARKERS)], styles[(i // len(MARKERS)) % len(styles)])
            for i, m in enumerate(mkeys)}
    for k, (ptitle, part, cols) in enumerate(panels):
        r, c = divmod(k, ncols)
        targets = [(grid[r * (2 if y2 else 1)][c], y, ylabel)]
        if y2:
            targets.append((grid[r * 2 + 1][c], y2, y2label))
        for ax, col, lab in targets:
            for key, xs, ys in series(part, x, col, cols):
                kk = tuple(str(key[c]) for c in cols)
                marker, dash = look.get(kk[1:], ("o", "-"))
                if len(np.unique(xs)) < len(xs):
                    # several points at one x on one line (a sampled study's runs share
                    # their temperature): a line would zigzag up and down between them
                    dash = "none"
                (line,) = ax.plot(xs, ys, marker=marker, ms=4, color=colours.get(kk[:1], "0.3"),
                                  linestyle=dash, label=_label(key))
                line.set_gid(repr(sorted((kk_, _text(vv)) for kk_, vv in key.items())))
            ax.set_ylabel(lab)
            ax.grid(alpha=0.3)
            if ymin0:
                # from zero, with room below it: a point at zero (a stop whose belt went
                # slack, the worst run) is drawn whole, not half hidden by the frame
                top = ax.get_ylim()[1]
                ax.set_ylim(bottom=-ZERO_ROOM * top if top > 0 else 0.0)
            if ptitle and col == y:
                ax.set_title(wrap_title(ptitle, 40), fontsize=10)
        targets[-1][0].set_xlabel(xlabel)
        # sharex shows tick labels on the grid's last row only: a panel above an unused
        # one of an incomplete last row would have its axis named but not numbered
        targets[-1][0].tick_params(axis="x", labelbottom=True)
    for k in range(len(panels), nrows_p * ncols):  # unused panels of the last row
        r, c = divmod(k, ncols)
        for rr in range(r * (2 if y2 else 1), (r + 1) * (2 if y2 else 1)):
            grid[rr][c].set_axis_off()
    handles, labels = _legend_entries(lines, ckeys, mkeys, colours, look)
    if handles:
        fig.legend(handles, labels, loc="upper right", fontsize=8,
                   bbox_to_anchor=(0.995, 0.93), frameon=True)
    fig.suptitle(wrap_title(title, int(TITLE_WIDTH * max(ncols, 1) / 1.2)))
    note_lines = list(notes or [])
    if same:
        note_lines.append("the same for every value of " + ", ".join(same))
    if note_lines:
        fig.text(0.01, 0.005, wrap_title("; ".join(note_lines), 120), fontsize=8,
                 color="0.35", va="bottom")
    width, height = fig.get_size_inches()
    right = 1.0 - legend_in / width
    top = 1.0 - (0.25 + 0.22 * fig._suptitle.get_text().count("\n")) / height
    fig.tight_layout(rect=(0, 0.3 / height if note_lines else 0, right, top))
    return fig


def _shown(text: str):
    """An axis value kept as text (a legend key) back as a number where it is one."""
    try:
        value = float(text)
    except ValueError:
        return text
    return None if math.isnan(value) else value


def _legend_entries(lines: list[str], ckeys, mkeys, colours: dict, look: dict):
    """The legend of :func:`comparison_figure`: one entry per colour (the first line axis)
    and, under a heading, one per marker and dash (the others); one entry per line when
    there is a single line axis."""
    from matplotlib.lines import Line2D

    handles, labels = [], []
    if not lines:
        return handles, labels
    if len(lines) == 1:
        for c in ckeys:
            handles.append(Line2D([], [], color=colours[c], marker="o", ms=4))
            labels.append(_label({lines[0]: _shown(c[0])}))
        return handles, labels
    handles.append(Line2D([], [], linestyle="none"))
    labels.append(f"colour: {lines[0]}")
    for c in ckeys:
        handles.append(Line2D([], [], color=colours[c], linewidth=3))
        labels.append(_text(_shown(c[0])))
    handles.append(Line2D([], [], linestyle="none"))
    labels.append("marker: " + ", ".join(lines[1:]))
    for m in mkeys:
        marker, dash = look[m]
        handles.append(Line2D([], [], color="0.35", marker=marker, ms=5, linestyle=dash))
        labels.append(_label({k: _shown(v) for k, v in zip(lines[1:], m, strict=True)}))
    return handles, labels


def _one_per_zip_group(others: list[str], groups: list[list[str]] | None
                       ) -> tuple[list[str], list[str]]:
    """``others`` with only the first axis of each zip group (its partners vary with it, so
    they add no lines), and notes naming the partners."""
    out, notes = [], []
    for c in others:
        group = next((g for g in groups or [] if c in g), None)
        if group is not None:
            first = next(g for g in group if g in others)
            if first != c:
                continue
            partners = [g for g in group if g != c and g in others]
            if partners:
                notes.append(f"{c} with {', '.join(partners)} (zip)")
        out.append(c)
    return out, notes


#: Units of axis columns by their name's end (SPEC: every key that carries a unit ends in it).
_AXIS_UNITS = (("_rad_s", "rad/s"), ("_m_s", "m/s"), ("_kg_m2", "kg m²"), ("_kg_m", "kg/m"),
               ("_t_h", "t/h"), ("_t_m3", "t/m³"), ("_kn_m", "kN/m"), ("_kn", "kN"),
               ("_kw", "kW"), ("_kg", "kg"), ("_deg", "°"), ("_pct", "%"), ("_mm", "mm"),
               ("_s", "s"), ("_m", "m"), ("_n", "N"), ("_c", "°C"))


def axis_label(column: str) -> str:
    """An axis column as an axis label with its unit: ``temperature_c [°C]``,
    ``takeup.mass_kg [kg]``; a column without a unit as it is."""
    for end, unit in _AXIS_UNITS:
        if column.endswith(end):
            return f"{column} [{unit}]"
    return column


def _tied_label(label: str, tied: list[str]) -> str:
    return label + (f" (with {', '.join(tied)})" if tied else "")


def power_temperature_figure(runs, title: str = "", temperature_c: float | None = None,
                             axes: list[str] | None = None, groups: list[list[str]] | None = None):
    """Power at the drive pulleys against temperature (Harrison's Fig. 2).

    A line per combination of the other axes that vary in the study (friction model, load,
    belt type, ...), never joined across them and never averaged; small multiples (a panel per
    value of the first of them) when that would be more than :data:`MAX_LINES` lines. Without
    a ``temperature_c`` axis every run sits at ``temperature_c`` [deg C] (the scenario's).
    ``axes`` are the study's axis columns (default: every input column of ``runs``);
    ``groups`` its zip groups (columns): axes zipped with the temperature vary along the x axis
    with it and are named in its label.
    """

    title = title or "power against temperature"
    df = _ok_rows(runs).copy()
    power = _numeric(df, "power_kw")
    if not len(df):
        return message_figure(no_rows_message(runs), title)
    if power is None:
        return message_figure("no steady results yet", title)
    df["power_kw"] = power
    if "temperature_c" not in df.columns:
        df["temperature_c"] = float(temperature_c if temperature_c is not None else 20.0)
    df["temperature_c"] = pd.to_numeric(df["temperature_c"], errors="coerce")
    cols = _model_first_axes(df, axes)
    tied = _tied(groups, "temperature_c")
    others = varying(df, [c for c in cols if c != "temperature_c" and c not in tied])
    others, notes = _one_per_zip_group(others, groups)
    return comparison_figure(df, "temperature_c", "power_kw", others,
                             _tied_label("temperature [°C]", tied),
                             "power at the drive pulleys [kW]", title,
                             inputs=["temperature_c", *tied], notes=notes)


def _model_first_axes(df: pd.DataFrame, axes) -> list[str]:
    """The axis columns of a figure, the friction model first (``df`` gets a one-value
    ``friction_model`` column when it has none): the given ``axes`` or the varying ones."""
    if "friction_model" not in df.columns:
        df["friction_model"] = "model"
    cols = list(axes) if axes is not None else default_axis_columns(df)
    if "friction_model" not in cols:
        cols.insert(0, "friction_model")
    return cols


def _tied(groups: list[list[str]] | None, column: str) -> list[str]:
    """The columns zipped with ``column`` (they vary together with it)."""
    for group in groups or []:
        if column in group:
            return [c for c in group if c != column]
    return []


def stop_tension_columns(runs) -> tuple[str, str | None]:
    """The peak and lowest tension columns of a stop: the stop-phase ones (``t_max_stop_kn``,
    ``t_min_stop_kn``) where the runs have them, else the whole transient's."""
    peak = "t_max_stop_kn" if _numeric(runs, "t_max_stop_kn") is not None else "t_max_dyn_kn"
    low = "t_min_stop_kn" if _numeric(runs, "t_min_stop_kn") is not None else (
        "t_min_dyn_kn" if _numeric(runs, "t_min_dyn_kn") is not None else None)
    return peak, low


def peak_dynamic_tension_figure(runs, title: str = "", axes: list[str] | None = None,
                                groups: list[list[str]] | None = None):
    """Peak tension [kN] against the achieved ``stop_time_s`` [s], the lowest tension below.

    Stop-phase columns (``t_max_stop_kn``, ``t_min_stop_kn``) when the runs have them, else
    ``t_max_dyn_kn`` / ``t_min_dyn_kn``. A line per combination of the other varying axes (the
    stop-time axis itself is the x axis); a :data:`NO_TRANSIENT` figure when the study has no
    transient results.
    """
    title = title or "peak tension against stop time"
    df = _ok_rows(runs).copy()
    peak_col, low_col = stop_tension_columns(df)
    peak = _numeric(df, peak_col)
    if not len(df):
        return message_figure(no_rows_message(runs), title)
    if peak is None:
        return message_figure(NO_TRANSIENT, title)
    df[peak_col] = peak
    if low_col:
        df[low_col] = _numeric(df, low_col)
    stop = _numeric(df, "stop_time_s")
    if stop is None:  # the achieved stop time is missing: fall back to the commanded one
        stop = _numeric(df, "stop_time_target_s")
    if stop is None:
        return message_figure("no stop times in the results", title)
    df["x"] = stop
    cols = _model_first_axes(df, axes)
    tied = _tied(groups, "stop_time_target_s")
    others = varying(df, [c for c in cols if c not in ("stop_time_target_s", "stop_time_s",
                                                       "x", *tied)])
    others, notes = _one_per_zip_group(others, groups)
    unstopped = int(df["x"].isna().sum())
    if unstopped:
        # the engine's one rule: not at rest within the stop window of the stop command
        window = _numeric(df, "stop_window_s")
        within = (f" within {window.max():.0f} s of the stop command"
                  if window is not None else "")
        notes.append(f"{unstopped} runs that did not stop{within} have no stop time and are "
                     "not drawn")
    phase = "stop phase" if peak_col == "t_max_stop_kn" else "whole transient"
    return comparison_figure(df, "x", peak_col, others,
                             _tied_label("stop time achieved [s]", tied),
                             f"peak tension [kN] ({phase})", title, y2=low_col,
                             y2label=f"lowest tension [kN] ({phase})", ymin0=True,
                             inputs=[c for c in cols if c not in others], notes=notes)


#: Markers of :func:`phase_peaks_figure`, one per combination of the marker axes (then hollow).
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*", "<", ">")


def _palette(n: int):
    """``n`` distinct colours: tab10 up to 10, tab20 up to 20, else evenly along viridis."""
    plt = _plt()
    if n <= 10:
        return [plt.get_cmap("tab10")(i) for i in range(n)]
    if n <= 20:
        return [plt.get_cmap("tab20")(i) for i in range(n)]
    return [plt.get_cmap("viridis")(i / max(n - 1, 1)) for i in range(n)]


def _x_axis(df: pd.DataFrame, cols: list[str]) -> str | None:
    """The x axis of :func:`phase_peaks_figure`: the temperature, the stop time asked, the
    load, else the first varying axis (None: a single point per series)."""
    moving = varying(df, cols)
    for c in ("temperature_c", "stop_time_target_s", "load"):
        if c in moving:
            return c
    numeric = [c for c in moving if c != "friction_model" and _numeric(df, c) is not None
               and df[c].notna().all()]
    if numeric:
        return numeric[0]
    rest = [c for c in moving if c != "friction_model"]
    return rest[0] if rest else (moving[0] if moving else None)


def _phase_panels(df: pd.DataFrame) -> list[tuple[str, str]]:
    """``[(column, panel title)]``: per phase where the runs have them, else the cycle's."""
    out = [(c, t) for c, t in (("t_max_start_kn", "peak tension, start"),
                               ("t_max_stop_kn", "peak tension, stop"),
                               ("t_min_start_kn", "lowest tension, start"),
                               ("t_min_stop_kn", "lowest tension, stop"))
           if _numeric(df, c) is not None]
    if not out:
        out = [(c, t) for c, t in (("t_max_dyn_kn", "peak tension, whole transient"),
                                   ("t_min_dyn_kn", "lowest tension, whole transient"))
               if _numeric(df, c) is not None]
    return out


#: The dashes of the allowed-tension lines of :func:`phase_peaks_figure`, one per belt.
_ALLOWED_DASHES = ("--", (0, (6, 2, 1, 2)), ":", "-.", (0, (1, 4)))


def phase_peaks_figure(runs, title: str = "", axes: list[str] | None = None,
                       groups: list[list[str]] | None = None,
                       allowed_kn: float | list | None = None,
                       never_going: pd.Series | None = None):
    """Peak and lowest belt tension [kN] of the start and of the stop against a study axis.

    One point per run, never joined: runs with different values of the other axes are
    unrelated. Panels: the peak of the start and of the stop above, the lowest below
    (``t_max_start_kn``, ``t_max_stop_kn``, ``t_min_start_kn``, ``t_min_stop_kn``; the whole
    transient's ``t_max_dyn_kn`` / ``t_min_dyn_kn`` for runs without the phase columns). The x
    axis is the temperature, else the stop time asked, the load or the first varying axis
    (categories side by side, points of one category spread a little so none hides another).
    Colour: one per value of the friction model (or of the first other varying axis); marker:
    one per combination of the remaining varying axes (hollow after ten). Each colour and each
    marker has one legend entry. A red ring marks a run whose belt did not stop (no stop
    time; it ran away, or did not stop in its window), not one that never got going
    (``never_going``, a mask over ``runs``: the report's
    :func:`~beltstudy.service.web.verdicts.never_going`; it made no stop); a dashed line the
    tension the belt allows (``allowed_kn``: rating over the transient safety factor; a list
    of ``(kN, belts)`` for runs on belts that allow different tensions, a line each) and zero
    (slack).
    """
    plt = _plt()
    from matplotlib.lines import Line2D

    allowed = ([(float(allowed_kn), "")] if isinstance(allowed_kn, (int, float))
               else list(allowed_kn or []))
    allowed = [(v, b) for v, b in allowed if v and math.isfinite(v)]
    title = title or "peak and lowest tension of the start and the stop"
    df = _ok_rows(runs).copy()
    panels = _phase_panels(df)
    if not len(df):
        return message_figure(no_rows_message(runs), title)
    if not panels:
        return message_figure(NO_TRANSIENT, title)
    cols = _model_first_axes(df, axes)
    x = _x_axis(df, cols)
    others = varying(df, [c for c in cols if c != x and c not in _tied(groups, x or "")])
    others, notes = _one_per_zip_group(others, groups)
    colour_by, marker_by = (others[:1], others[1:])
    ckeys = sorted({tuple(_text(v) for v in r) for r in df[colour_by].itertuples(index=False)}
                   ) if colour_by else [()]
    mkeys = sorted({tuple(_text(v) for v in r) for r in df[marker_by].itertuples(index=False)}
                   ) if marker_by else [()]
    colours = dict(zip(ckeys, _palette(len(ckeys)), strict=True))
    marks = {k: (MARKERS[i % len(MARKERS)], (i // len(MARKERS)) % 2 == 1)
             for i, k in enumerate(mkeys)}
    if len(mkeys) > 2 * len(MARKERS):
        notes.append(f"{len(mkeys)} marker combinations: markers repeat after "
                     f"{2 * len(MARKERS)}")
    # x positions: numbers as they are, categories side by side; a small spread per series
    if x is None:
        xs_base, ticks = pd.Series(0.0, index=df.index), None
    elif (num := _numeric(df, x)) is not None and num.notna().all():
        xs_base, ticks = num, None  # every value a number ('auto' beside 3000: categories)
    else:
        cats = sorted(df[x].map(_text).unique())
        xs_base, ticks = df[x].map(_text).map({c: i for i, c in enumerate(cats)}), cats
    span = float(xs_base.max() - xs_base.min()) or 1.0
    n_series = len(ckeys) * len(mkeys)
    step = min(0.5 / max(n_series, 1), 0.08) * (span if ticks is None else 1.0)
    series_index = {(c, m): i for i, (c, m) in enumerate((c, m) for c in ckeys for m in mkeys)}
    ckey = df[colour_by].apply(lambda r: tuple(_text(v) for v in r), axis=1) if colour_by \
        else pd.Series([()] * len(df), index=df.index)
    mkey = df[marker_by].apply(lambda r: tuple(_text(v) for v in r), axis=1) if marker_by \
        else pd.Series([()] * len(df), index=df.index)
    offset = pd.Series([(series_index[(c, m)] - (n_series - 1) / 2) * step
                        for c, m in zip(ckey, mkey, strict=True)], index=df.index)
    stopped = df["stop_time_s"].notna() if "stop_time_s" in df.columns else None
    if stopped is not None and never_going is not None:
        stopped |= never_going.reindex(df.index, fill_value=False).astype(bool)
    ncols = 2 if len(panels) > 2 else len(panels)
    nrows = math.ceil(len(panels) / ncols)
    longest = max([len(", ".join(k)) for k in (*ckeys, *mkeys)]
                  + [len(", ".join(marker_by)) + 8, len("".join(colour_by)) + 8, 16])
    legend_in = min(0.065 * longest + 0.8, 5.0)  # the legend's column beside the panels
    fig, grid = plt.subplots(nrows, ncols,
                             figsize=(5.2 * ncols + legend_in + 0.3, 3.4 * nrows + 1.0),
                             squeeze=False, sharex=True)
    unstopped_drawn = False
    for k, (col, ptitle) in enumerate(panels):
        ax = grid[k // ncols][k % ncols]
        values = _numeric(df, col)
        for (c, m), part in df.groupby([ckey, mkey], sort=False):
            idx = part.index[values.loc[part.index].notna()]
            if not len(idx):
                continue
            marker, hollow = marks[m]
            colour = colours[c]
            ax.scatter(xs_base.loc[idx] + offset.loc[idx], values.loc[idx], s=30,
                       marker=marker, edgecolors=colour,
                       facecolors="none" if hollow else [colour], linewidths=1.2,
                       zorder=3, gid=repr((c, m)))
            if stopped is not None and "stop" in col:
                bad = [i for i in idx if not stopped.loc[i]]
                if bad:
                    ax.scatter(xs_base.loc[bad] + offset.loc[bad], values.loc[bad], s=150,
                               marker="o", facecolors="none", edgecolors="red",
                               linewidths=1.4, zorder=2)
                    unstopped_drawn = True
        if col.startswith("t_max"):
            for (value, _), dash in zip(allowed, _ALLOWED_DASHES, strict=False):
                ax.axhline(value, color="0.3", linestyle=dash, linewidth=0.9)
        if col.startswith("t_min"):
            ax.axhline(0.0, color="0.3", linestyle="--", linewidth=0.9)
        ax.set_title(ptitle, fontsize=10)
        ax.set_ylabel("belt tension [kN]")
        ax.grid(alpha=0.3)
        if ticks is not None:
            ax.set_xticks(range(len(ticks)), ticks)
        if k // ncols == nrows - 1 or k + ncols >= len(panels):
            ax.set_xlabel(_tied_label(axis_label(x), _tied(groups, x or "")) if x
                          else "all runs")
            ax.tick_params(axis="x", labelbottom=True)  # sharex numbers the last row only
    for k in range(len(panels), nrows * ncols):
        grid[k // ncols][k % ncols].set_axis_off()
    handles, labels = [], []
    if colour_by:
        handles.append(Line2D([], [], linestyle="none"))
        labels.append(f"colour: {colour_by[0]}")
        for c in ckeys:
            handles.append(Line2D([], [], linestyle="none", marker="s", markersize=8,
                                  markerfacecolor=colours[c], markeredgecolor=colours[c]))
            labels.append(", ".join(c))
    if marker_by:
        handles.append(Line2D([], [], linestyle="none"))
        labels.append("marker: " + ", ".join(marker_by))
        for m in mkeys:
            marker, hollow = marks[m]
            handles.append(Line2D([], [], linestyle="none", marker=marker, markersize=7,
                                  markerfacecolor="none" if hollow else "0.35",
                                  markeredgecolor="0.35"))
            labels.append(", ".join(m))
    if unstopped_drawn:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=11,
                              markerfacecolor="none", markeredgecolor="red"))
        labels.append("did not stop")
    for k, ((value, belts), dash) in enumerate(zip(allowed, _ALLOWED_DASHES, strict=False)):
        handles.append(Line2D([], [], color="0.3", linestyle=dash))
        labels.append(f"allowed {value:.0f} kN" + (f" ({belts})" if belts else "")
                      + (" / slack 0" if k == 0 else ""))
    if handles:
        fig.legend(handles, labels, loc="upper right", fontsize=8, frameon=True,
                   bbox_to_anchor=(0.995, 0.93))
    fig.suptitle(wrap_title(title, 90))
    if notes:
        fig.text(0.01, 0.005, wrap_title("; ".join(notes), 120), fontsize=8, color="0.35",
                 va="bottom")
    width, height = fig.get_size_inches()
    fig.tight_layout(rect=(0, 0.3 / height if notes else 0, 1.0 - legend_in / width,
                           1.0 - 0.45 / height))
    return fig


def ratio_figure(summary: dict, baseline: str = "cema", candidate: str = "nonlin", title: str = ""):
    """Candidate / baseline ratio per axis value: mean as a bar, min-max as the whisker.

    ``summary`` is the ``summary`` of :func:`beltstudy.service.store.query.compare` (``{metric:
    {"overall": stats, "by_axis": {axis: {value: stats}}}}``). One row per metric with data,
    one column per axis other than the friction model.
    """
    plt = _plt()
    title = title or f"{candidate} / {baseline} per axis value"
    rows = []
    for metric, item in summary.items():
        if item["overall"]["n"]:
            rows.append((metric, item))
    if not rows:
        return message_figure(f"no pairs of {candidate} and {baseline} runs with results", title)
    axes = sorted({a for _, item in rows for a in item["by_axis"]}) or ["overall"]
    fig, grid = plt.subplots(len(rows), len(axes), figsize=(3.6 * len(axes) + 1.5,
                                                            3.0 * len(rows) + 0.8),
                             squeeze=False)
    for i, (metric, item) in enumerate(rows):
        for j, axis in enumerate(axes):
            ax = grid[i][j]
            stats = item["by_axis"].get(axis) if axis != "overall" else {"all": item["overall"]}
            stats = {k: v for k, v in (stats or {}).items() if v["n"]}
            labels = list(stats)
            means = [stats[k]["mean"] for k in labels]
            lo = [max(stats[k]["mean"] - stats[k]["min"], 0.0) for k in labels]
            hi = [max(stats[k]["max"] - stats[k]["mean"], 0.0) for k in labels]
            x = np.arange(len(labels))
            ax.bar(x, means, yerr=[lo, hi], capsize=3, color="tab:blue", alpha=0.7)
            ax.axhline(1.0, color="0.3", linewidth=0.8)
            ax.set_xticks(x, labels, rotation=30 if len(labels) > 4 else 0, fontsize=8)
            ax.grid(alpha=0.3, axis="y")
            if i == len(rows) - 1:
                ax.set_xlabel(axis_label(axis))
            if j == 0:
                ax.set_ylabel(f"{metric} ratio")
    fig.suptitle(wrap_title(title))
    fig.tight_layout()
    return fig


def _positions(surface) -> np.ndarray:
    return np.unique(np.asarray(surface["s_m"], dtype=float))


def _probe_position(surface, positions: np.ndarray, at: float, value: float | None) -> float:
    """The sampled position that shows an extreme reported at ``at``: the nearest one, or,
    given the extreme's ``value``, of the nearest position on each side the one whose trace
    comes closest to it. An extreme at an element's end (the carry's last element meeting a
    drive pulley, ``t_max_dyn_at_m`` = 1800 m) lies between the two elements' centres, and
    the nearer centre may be the pulley's, on the other side of the tension step."""
    nearest = float(positions[np.argmin(np.abs(positions - at))])
    if value is None or not np.isfinite(value):
        return nearest
    below, above = positions[positions <= at], positions[positions >= at]
    sides = {float(below.max())} if len(below) else set()
    sides |= {float(above.min())} if len(above) else set()

    def miss(s: float) -> float:
        tension = _trace(surface, s)[1]
        return float(np.min(np.abs(tension - value))) if len(tension) else np.inf

    return min(sorted(sides), key=lambda s: (miss(s), abs(s - at)))


def _trace(surface, s: float):
    part = surface[np.isclose(surface["s_m"].astype(float), s)].sort_values("t_s")
    return part["t_s"].to_numpy(float), part["tension_kn"].to_numpy(float)


def _where_text(s: float, locate=None) -> str:
    """``carry, 1200 m from the tail`` for a loop position, with ``locate(s) -> (strand,
    distance from the tail)``; else the loop position."""
    if locate is None:
        return f"{s:.0f} m round the loop"
    strand, x = locate(s)
    if strand in ("carry", "return"):
        return f"{strand}, {x:.0f} m from the tail"
    return f"{strand} pulley"


def _eight_points(surface, locate=None):
    """Tension against time at eight positions spread evenly round the loop (long table)."""
    positions = _positions(surface)
    if len(positions) == 0:
        return []
    picks = positions[np.unique(np.linspace(0, len(positions) - 1, 8).round().astype(int))]
    return [(_where_text(s, locate), *_trace(surface, s)) for s in picks]


_KEY_POINTS = (
    ("t_head_in_kn", "head in (T1)"), ("t_head_out_kn", "head out (T2)"),
    ("t_tail_kn", "tail"), ("t_takeup_kn", "take-up"),
    ("t_max_kn", "loop maximum"), ("t_min_kn", "loop minimum"),
)  # fmt: skip


def transient_figure(timeseries, surface=None, title: str = "", extremes: dict | None = None,
                     locate=None, extremes_surface=None):
    """Tension at eight points round the loop against time, belt speed below (Fig. 4).

    ``surface`` is the long table (``t_s``, ``s_m``, ``tension_kn``): eight positions spread
    evenly round the loop, named by strand and distance from the tail when ``locate(s_m) ->
    (strand, distance from the tail [m])`` is given. ``extremes`` (``{"highest": s_m,
    "lowest": s_m}``, e.g. ``t_max_dyn_at_m`` and ``t_min_dyn_at_m``) add a probe at each of
    those positions (nearest point of ``extremes_surface``, default ``surface``; given as
    ``(s_m, value)`` the point on either side whose trace comes closest to the value), drawn
    bold; given as ``(s_m, value, t_s)`` the extreme itself is marked too, at its time (the
    probe's trace is sampled, and a short peak falls between its samples).
    Without a surface the key points of ``timeseries`` (SPEC section 5) are drawn. A
    :data:`NO_TRANSIENT` figure when there is no time series.
    """
    plt = _plt()
    title = title or "transient tensions and belt speed"
    has_ts = timeseries is not None and len(timeseries) and "t_s" in timeseries.columns
    has_sf = surface is not None and len(surface) and "s_m" in surface.columns
    if not has_ts and not has_sf:
        return message_figure(NO_TRANSIENT, title)
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(11, 7.0),
                                   gridspec_kw={"height_ratios": [2, 1]})
    if has_sf:
        for label, t, tension in _eight_points(surface, locate):
            ax1.plot(t, tension, label=label, linewidth=1.0)
        pool = extremes_surface if extremes_surface is not None and len(extremes_surface) \
            else surface
        positions = _positions(pool)
        for (name, at), color in zip((extremes or {}).items(), ("black", "tab:red"),
                                     strict=False):
            at, value, when = (tuple(at) + (None, None))[:3] if isinstance(at, tuple) else (
                at, None, None)
            if at is None or not np.isfinite(at) or not len(positions):
                continue
            s = _probe_position(pool, positions, float(at), value)
            t, tension = _trace(pool, s)
            ax1.plot(t, tension, color=color, linewidth=2.0, linestyle="--",
                     label=f"{name}: {_where_text(s, locate)}")
            if value is not None and when is not None and np.isfinite(value) \
                    and np.isfinite(when):
                # the extreme itself: the probe's trace is sampled at the surface's spacing
                # (1.3 s on a 30 m belt), and a peak of a fraction of a second between two
                # samples is not on it
                ax1.plot([when], [value], color=color, marker="o", markersize=6,
                         linestyle="none", label=f"{name} {gnum(value)} kN at t = {gnum(when)} s")
    else:
        ts = timeseries.sort_values("t_s")
        for column, label in _KEY_POINTS:
            values = _numeric(ts, column)
            if values is not None:
                ax1.plot(ts["t_s"], values, label=label, linewidth=1.0)
    ax1.set_ylabel("belt tension [kN]")
    ax1.grid(alpha=0.3)
    ax1.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7)
    fig.suptitle(wrap_title(title, 100))
    if has_ts:
        ts = timeseries.sort_values("t_s")
        for column, label in (("v_drive_m_s", "drive pulley"), ("v_tail_m_s", "tail pulley")):
            values = _numeric(ts, column)
            if values is not None:
                ax2.plot(ts["t_s"], values, label=label)
        ax2.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7)
    elif "velocity_m_s" in surface.columns:
        mean = surface.groupby("t_s")["velocity_m_s"].mean()
        ax2.plot(mean.index, mean.values, label="mean belt speed")
        ax2.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("belt speed [m/s]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    return fig
