"""Figures shared by the CLI, the REST routes and the pages (matplotlib, Agg backend).

Every function returns a matplotlib Figure; callers save it as PNG or SVG.
"""

from __future__ import annotations

import numpy as np


def _plt():
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
        ax1.set_title(title)
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


def message_figure(message: str, title: str = "", figsize=(8, 4.5)):
    """A figure holding only ``message`` (no data to draw) and an optional title."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=figsize)
    ax.set_axis_off()
    ax.text(0.5, 0.5, message, ha="center", va="center", fontsize=13, color="0.3",
            wrap=True, transform=ax.transAxes)
    if title:
        ax.set_title(title)
    return fig


def _numeric(df, column: str):
    import pandas as pd

    if column not in df.columns:
        return None
    values = pd.to_numeric(df[column], errors="coerce")
    return values if values.notna().any() else None


def _ok_rows(runs):
    if "status" in runs.columns:
        return runs[runs["status"] != "failed"]
    return runs


def power_temperature_figure(runs, title: str = "", temperature_c: float | None = None):
    """Power at the drive pulleys against temperature, per friction model and load (Fig. 2).

    ``runs`` is the runs table (SPEC section 4). A line per (``friction_model``, ``load``);
    where other axes vary, each point is the mean over them. Without a ``temperature_c``
    axis every run sits at ``temperature_c`` [deg C] (the scenario's).
    """
    import pandas as pd

    plt = _plt()
    df = _ok_rows(runs).copy()
    power = _numeric(df, "power_kw")
    if not len(df) or power is None:
        return message_figure("no steady results yet", title or "power against temperature")
    df["power_kw"] = power
    if "temperature_c" not in df.columns:
        df["temperature_c"] = float(temperature_c if temperature_c is not None else 20.0)
    df["temperature_c"] = pd.to_numeric(df["temperature_c"], errors="coerce")
    if "friction_model" not in df.columns:
        df["friction_model"] = "model"
    groups = ["friction_model"] + (["load"] if "load" in df.columns else [])
    fig, ax = plt.subplots(figsize=(8, 4.8))
    styles = ("-", "--", ":", "-.")
    loads = sorted(df["load"].astype(str).unique()) if "load" in df.columns else [""]
    for key, group in df.groupby(groups, sort=True):
        key = key if isinstance(key, tuple) else (key,)
        model = str(key[0])
        load = str(key[1]) if len(key) > 1 else ""
        curve = group.groupby("temperature_c")["power_kw"].mean().sort_index()
        label = f"{model}, load {load}" if load else model
        ax.plot(curve.index, curve.values, marker="o", label=label,
                linestyle=styles[loads.index(load) % len(styles)] if load else "-")
    ax.set_xlabel("temperature [°C]")
    ax.set_ylabel("power at the drive pulleys [kW]")
    ax.set_title(title or "power against temperature per friction model and load")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return fig


def peak_dynamic_tension_figure(runs, title: str = ""):
    """Peak dynamic tension ``t_max_dyn_kn`` [kN] against the achieved ``stop_time_s`` [s].

    One series per friction model; a :data:`NO_TRANSIENT` figure when the study has no
    transient results (``dynamics: false``, or no dynamic run finished yet).
    """
    plt = _plt()
    title = title or "peak dynamic tension against stop time"
    df = _ok_rows(runs).copy()
    peak = _numeric(df, "t_max_dyn_kn")
    stop = _numeric(df, "stop_time_s")
    if not len(df) or peak is None:
        return message_figure(NO_TRANSIENT, title)
    df["t_max_dyn_kn"] = peak
    if stop is None:  # the achieved stop time is missing: fall back to the commanded one
        stop = _numeric(df, "stop_time_target_s")
    if stop is None:
        return message_figure("no stop times in the results", title)
    df["x"] = stop
    df = df.dropna(subset=["x", "t_max_dyn_kn"])
    if "friction_model" not in df.columns:
        df["friction_model"] = "model"
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for model, group in df.groupby("friction_model", sort=True):
        curve = group.groupby("x")["t_max_dyn_kn"].max().sort_index()
        ax.plot(curve.index, curve.values, marker="o", label=str(model))
    ax.set_xlabel("stop time [s]")
    ax.set_ylabel("peak dynamic tension [kN]")
    ax.set_ylim(bottom=0.0)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return fig


def ratio_figure(summary: dict, baseline: str = "cema", candidate: str = "nonlin", title: str = ""):
    """Candidate / baseline ratio per axis value: mean as a bar, min-max as the whisker.

    ``summary`` is the ``summary`` of :func:`service.results.compare` (``{metric:
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
                ax.set_xlabel(axis)
            if j == 0:
                ax.set_ylabel(f"{metric} ratio")
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def _eight_points(surface):
    """Tension against time at eight positions spread evenly round the loop (long table)."""
    positions = np.unique(np.asarray(surface["s_m"], dtype=float))
    if len(positions) == 0:
        return []
    picks = positions[np.unique(np.linspace(0, len(positions) - 1, 8).round().astype(int))]
    out = []
    for s in picks:
        part = surface[np.isclose(surface["s_m"].astype(float), s)].sort_values("t_s")
        out.append((f"s = {s:.0f} m", part["t_s"].to_numpy(float),
                    part["tension_kn"].to_numpy(float)))
    return out


_KEY_POINTS = (
    ("t_head_in_kn", "head in (T1)"), ("t_head_out_kn", "head out (T2)"),
    ("t_tail_kn", "tail"), ("t_takeup_kn", "take-up"),
    ("t_max_kn", "loop maximum"), ("t_min_kn", "loop minimum"),
)  # fmt: skip


def transient_figure(timeseries, surface=None, title: str = ""):
    """Tension at eight points round the loop against time, belt speed below (Fig. 4).

    ``surface`` is the long table (``t_s``, ``s_m``, ``tension_kn``): eight positions spread
    evenly round the loop. Without it the key points of ``timeseries`` (SPEC section 5) are
    drawn. A :data:`NO_TRANSIENT` figure when there is no time series.
    """
    plt = _plt()
    title = title or "transient tensions and belt speed"
    has_ts = timeseries is not None and len(timeseries) and "t_s" in timeseries.columns
    has_sf = surface is not None and len(surface) and "s_m" in surface.columns
    if not has_ts and not has_sf:
        return message_figure(NO_TRANSIENT, title)
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(9, 6.5),
                                   gridspec_kw={"height_ratios": [2, 1]})
    if has_sf:
        for label, t, tension in _eight_points(surface):
            ax1.plot(t, tension, label=label, linewidth=1.0)
    else:
        ts = timeseries.sort_values("t_s")
        for column, label in _KEY_POINTS:
            values = _numeric(ts, column)
            if values is not None:
                ax1.plot(ts["t_s"], values, label=label, linewidth=1.0)
    ax1.set_ylabel("belt tension [kN]")
    ax1.grid(alpha=0.3)
    ax1.legend(loc="upper right", fontsize=7, ncol=2)
    ax1.set_title(title)
    if has_ts:
        ts = timeseries.sort_values("t_s")
        for column, label in (("v_drive_m_s", "drive pulley"), ("v_tail_m_s", "tail pulley")):
            values = _numeric(ts, column)
            if values is not None:
                ax2.plot(ts["t_s"], values, label=label)
        ax2.legend(loc="upper right", fontsize=7)
    elif "velocity_m_s" in surface.columns:
        mean = surface.groupby("t_s")["velocity_m_s"].mean()
        ax2.plot(mean.index, mean.values, label="mean belt speed")
        ax2.legend(loc="upper right", fontsize=7)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("belt speed [m/s]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    return fig
