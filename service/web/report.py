"""The design report of a study: one self-contained HTML page to hand to a client.

``GET /studies/{id}/report`` and ``beltstudy report ID -o FILE.html`` both call
:func:`build_report`. The page needs nothing else: its style is inline, its figures are PNGs
inside the page as ``data:`` URIs, it has no script and links nowhere, so it opens from a file
and prints cleanly to PDF from a browser (A4, tables and figures kept whole). Every value taken
from the study is escaped.

Contents: the conveyor and its capacity check; the design basis (every auto size, what set it
and at which case); the grid (axes, zip groups, merged points, model parameters); the
governing cases (largest and lowest tension, slip, sag, belt safety factor, take-up travel)
with the run that governs each; the comparison figures; the runs.
"""

from __future__ import annotations

import base64
import html
import math
import time
from typing import Any

import pandas as pd

from beltstudy.engine import (
    SAFETY_FACTOR_MIN,
    TRANSIENT_SAFETY_RATIO,
    build_loop,
    capacity,
    catalog,
    governed_at,
    parse_conveyor,
    resolve_belt,
)
from beltstudy.service.store import query
from beltstudy.service.studies import StudyService
from beltstudy.service.web import figures

__all__ = ["build_report", "GOVERNING", "REPORT_CSP"]

#: Content security policy of the report: no script, no fetches, images only from the page.
REPORT_CSP = ("default-src 'none'; img-src data:; style-src 'unsafe-inline'; base-uri 'none'; "
              "form-action 'none'; frame-ancestors 'none'")

#: The governing cases: (label, transient column, steady column, largest or smallest, unit,
#: position column of the transient, position column of the steady state).
GOVERNING = (
    ("largest belt tension", "t_max_dyn_kn", "t_max_kn", "max", "kN", "t_max_dyn_at_m",
     "t_max_at_m"),
    ("lowest belt tension", "t_min_dyn_kn", "t_min_kn", "min", "kN", "t_min_dyn_at_m",
     "t_min_at_m"),
    ("drive slip margin", "slip_margin_min_dyn", "slip_margin", "min", "-", None, None),
    ("largest sag", "sag_max_dyn_pct", "sag_max_pct", "max", "%", None, None),
    ("belt safety factor", "safety_factor_dyn", "safety_factor", "min", "-", None, None),
    ("take-up carriage travel", "takeup_travel_m", None, "max", "m", None, None),
)

CSS = """
body { font-family: "DejaVu Sans", Arial, sans-serif; font-size: 10.5pt; color: #111;
  margin: 1.5em auto; max-width: 60em; padding: 0 1em; }
h1 { font-size: 17pt; margin-bottom: 0.2em; }
h2 { font-size: 13pt; border-bottom: 1px solid #888; margin-top: 1.6em; }
h3 { font-size: 11pt; margin-bottom: 0.3em; }
.muted { color: #555; }
table { border-collapse: collapse; margin: 0.4em 0 0.8em; }
th, td { border: 1px solid #bbb; padding: 0.15em 0.5em; text-align: left; vertical-align: top; }
th { background: #eef1f5; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.warning td { background: #fff6da; }
tr.failed td { background: #fde8e8; }
figure { margin: 0.8em 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 9pt; color: #444; }
code { font-size: 9.5pt; }
.runs, .governing { font-size: 8.5pt; }
table.governing { width: 100%; }
td.num { white-space: nowrap; }
@page { size: A4; margin: 15mm 12mm; }
@media print {
  body { margin: 0; max-width: none; font-size: 9.5pt; }
  h2 { break-after: avoid; page-break-after: avoid; }
  table, figure, tr { break-inside: avoid; page-break-inside: avoid; }
  thead { display: table-header-group; }
  .runs, .governing { font-size: 7.5pt; }
}
"""

#: Marks a number cell of :func:`_table` (right-aligned).
NUM = "\x00"
#: Runs listed in the report's runs table (the Parquet has them all).
MAX_RUN_ROWS = 400


def _e(value: Any) -> str:
    return html.escape("" if value is None else str(value), quote=True)


def _num(value: Any, digits: int = 4) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    if isinstance(value, bool) or not isinstance(value, int | float):
        return _e(value)
    x = float(value)
    if x != 0 and (abs(x) >= 1e5 or abs(x) < 1e-3):
        return f"{x:.{digits}g}"
    return f"{x:,.{max(digits - len(str(int(abs(x)))), 0)}f}" if abs(x) >= 1 else f"{x:.{digits}g}"


def _table(head: list[str], rows: list[list[str]], cls: str = "", row_cls=None) -> str:
    out = [f'<table class="{cls}">' if cls else "<table>", "<thead><tr>"]
    out += [f"<th>{_e(h)}</th>" for h in head]
    out.append("</tr></thead><tbody>")
    for i, row in enumerate(rows):
        rc = row_cls(i) if row_cls else ""
        out.append(f'<tr class="{rc}">' if rc else "<tr>")
        for c in row:
            num = c.startswith(NUM)
            out.append(f"<td class=num>{c[1:]}</td>" if num else f"<td>{c}</td>")
        out.append("</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def _n(value: Any, digits: int = 4) -> str:
    """A number cell (right-aligned)."""
    return NUM + _num(value, digits)


def _png(make) -> str:
    data = figures.render(make, "png")
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def _figure(src: str, caption: str, alt: str) -> str:
    return (f'<figure><img src="{src}" alt="{_e(alt)}"><figcaption>{_e(caption)}'
            "</figcaption></figure>")


def _conveyor_section(conv: dict, fill: dict | None) -> str:
    belt = conv["belt"]
    mat = conv["material"]
    tu = conv["takeup"]
    length = sum(p["length_m"] for p in conv["profile"])
    lift = sum(p["lift_m"] for p in conv["profile"])
    rows = [
        ["name", _e(conv["name"])],
        ["length along the carry strand", f"{_num(length)} m"],
        ["net lift, tail to head", f"{_num(lift)} m"],
        ["design speed", f"{_num(conv['speed_m_s'])} m/s"],
        ["belt", _e(f"{belt.get('type') or 'custom'}, {belt['width_m']:g} m wide, compound "
                    f"{belt.get('compound', 'standard')}")],
        ["design capacity", f"{_num(mat['capacity_t_h'])} t/h at "
                            f"{_num(mat['density_t_m3'])} t/m³, surcharge "
                            f"{mat.get('surcharge_deg', 20):g}°"],
        ["carry idlers", _e(f"{conv['idlers']['carry'].get('rolls', 3)} rolls, trough "
                            f"{conv['idlers']['carry'].get('trough_deg', 0):g}°, spacing "
                            f"{conv['idlers']['carry']['spacing_m']:g} m")],
        ["take-up", _e(f"{tu['type']} at the {tu['position']}, "
                       + (f"mass {tu['mass_kg']}" + (" kg" if tu["mass_kg"] != "auto" else "")
                          if tu["type"] == "gravity" else
                          f"pretension {tu['pretension_kn']}"
                          + (" kN" if tu["pretension_kn"] != "auto" else ""))
                       + ("" if tu.get("sag_at_rest", True)
                          else "; sized for the sag limits running only"))],
        ["sag limits", _e(f"carry {conv['sag_limit_pct']['carry']:g} %, return "
                          f"{conv['sag_limit_pct']['return']:g} %")],
    ]
    if fill is not None:
        rows.append(["capacity check (ISO 5048)",
                     f"fill {_num(fill['fill_pct'], 3)} % of the cross-section at design speed "
                     f"({_num(fill['volume_flow_m3_h'])} of {_num(fill['capacity_m3_h'])} m³/h"
                     f"{', over 100 %: the design load does not fit' if fill['fill_pct'] > 100 else ''})"])
    out = [_table(["", ""], rows)]
    out.append("<h3>Profile (tail to head)</h3>")
    out.append(_table(["section", "length [m]", "lift [m]", "slope [%]"], [
        [str(i + 1), _n(p["length_m"]), _n(p["lift_m"]), _n(100 * p["lift_m"] / p["length_m"], 3)]
        for i, p in enumerate(conv["profile"])]))
    out.append("<h3>Drives and brakes</h3>")
    drows = [[f"drive {i + 1}", _e(d["position"]), _n(d["wrap_deg"]), _n(d["friction"]),
              _n(d["share"]), _e("auto" if d.get("rated_power_kw") is None
                                 else f"{d['rated_power_kw']:g}")]
             for i, d in enumerate(conv["drives"])]
    out.append(_table(["", "position", "wrap [°]", "friction", "share", "rated power [kW]"],
                      drows))
    if conv.get("brakes"):
        out.append(_table(["brake", "position", "force [kN]", "delay [s]"], [
            [str(i + 1), _e(b["position"]), _e(b["force_kn"]), _n(b["delay_s"])]
            for i, b in enumerate(conv["brakes"])]))
    return "".join(out)


def _design_section(study: dict) -> str:
    design = study.get("design")
    if design:
        case = "; ".join(f"{k} " + (", ".join(str(x) for x in v) if isinstance(v, list)
                                    else str(v)) for k, v in design.items())
        intro = (f"Every auto size is computed at the design cases <b>{_e(case)}</b> (every "
                 "combination of what is listed; what it does not name: the study's values), "
                 "the largest of each, and held for every run of its conveyor design.")
    else:
        intro = ("Every auto size is the largest requirement over the study's friction models "
                 "and temperatures at full load, computed once per conveyor design and held for "
                 "every run of it.")
    out = [f"<p>{intro} A brake is sized per stop time of the brake stops and held over the "
           "models, temperatures and loads; runs that do not stop on their brakes install the "
           "holding size.</p>"]
    designs = study.get("designs") or []
    if not designs:
        out.append("<p>The conveyor has no auto sizes: every size is given in the file.</p>")
        return "".join(out)
    rows = []
    for d in designs:
        where = ", ".join(f"{k}={v}" for k, v in d["axes"].items()) or "the conveyor"
        sizes = d["sizes"]
        tu = sizes.get("takeup")
        if tu:
            rows.append([_e(where), "take-up " + ("mass" if tu["unit"] == "kg" else
                                                  "pretension"),
                         _n(tu["value"], 6) + f" {tu['unit']}",
                         _e(governed_at(tu["governed_by"], tu.get("at", ""))),
                         _e(tu["case"])])
        for i, dr in enumerate(sizes.get("drives") or []):
            if dr:
                rows.append([_e(where), f"rated power, drive {i + 1}",
                             _n(dr["rated_power_kw"], 6) + " kW",
                             _e(governed_at(dr["governed_by"], dr.get("at", ""))),
                             _e(dr["case"])])
        brakes = sizes.get("brakes")
        if brakes:
            entries = [("held at rest (no brake stop)", brakes["holding"])] + [
                (f"brake stop in {t} s", e) for t, e in brakes["stop_time_s"].items()]
            for label, e in entries:
                rows.append([_e(where), f"brake force, {label}",
                             _n(sum(e["force_kn"]), 6) + " kN",
                             _e("+".join(dict.fromkeys(governed_at(g, e.get("at", ""))
                                                       for g in e["governed_by"]))),
                             _e(e["case"])])
        belt = sizes.get("belt")
        if belt:  # belt.type: auto, chosen once per design (docs/belts.md)
            rows.append([_e(where), "belt (type: auto)", _e(belt["type"]),
                         _e("lightest that passes" if belt["passed"] else
                            "none passes: the heaviest"), _e(belt["case"])])
    out.append(_table(["conveyor design", "size", "value", "governed by", "design case"],
                      rows))
    return "".join(out)


def _grid_section(study: dict, status: dict) -> str:
    rows = []
    for a in study.get("axes", []):
        group = "grid" if a.get("group") is None else f"zip group {a['group'] + 1}"
        rows.append([_e(a["name"]), _e(group), _e(", ".join(str(v) for v in a["values"]))])
    out = [_table(["axis", "in", "values"], rows)]
    merged = study.get("merged", 0)
    out.append(f"<p>{status['total']} runs from {study.get('grid_points', status['total'])} grid "
               f"points" + (f"; {merged} points whose resolved runs were identical (an axis that "
                            "does not change them) were merged" if merged else "") + ". "
               f"Friction model: {_e(study.get('model'))} unless an axis sets it; dynamics "
               f"{'on' if study.get('dynamics') else 'off'}.</p>")
    if study.get("models"):
        out.append(_table(["model", "parameters"], [
            [_e(m), _e(", ".join(f"{k}={v}" for k, v in p.items()) or "defaults")]
            for m, p in study["models"].items()]))
    return "".join(out)


def _locator(study: dict):
    """``s_m -> (strand, distance from the tail)`` on the study's conveyor (None if the
    conveyor cannot be read here)."""

    try:
        return build_loop(parse_conveyor(study["conveyor"]), 1.0).where
    except Exception:  # made by another engine version
        return None


def _where_on_loop(locate, at) -> str:
    if locate is None or at is None or (isinstance(at, float) and not math.isfinite(at)):
        return ""
    strand, x = locate(float(at))
    if strand in ("carry", "return"):
        return f"{strand}, {x:,.0f} m from the tail"
    return f"{strand} pulley"


def _limits(study: dict, runs: pd.DataFrame) -> dict[str, str]:
    """The limit each governing case is judged against, in numbers where the study has them."""
    conv = study["conveyor"]
    sag = conv["sag_limit_pct"]
    rating = pd.to_numeric(runs.get("belt_rating_kn"), errors="coerce") if len(runs) else None
    try:
        kind = resolve_belt(parse_conveyor(conv).belt).kind
    except Exception:  # a conveyor this engine cannot read, or belt.type: auto
        kind = catalog.KIND_OF_FILE.get(conv["belt"].get("kind") or "", "steel")
    sf = conv.get("safety_factor_min") or SAFETY_FACTOR_MIN.get(kind, 6.7)
    length = sum(p["length_m"] for p in conv["profile"])
    travel = conv["takeup"].get("travel_m") or 0.015 * length
    out = {
        "largest belt tension": (f"belt rating {rating.max():,.0f} kN" if rating is not None
                                 and rating.notna().any() else "belt rating"),
        "lowest belt tension": "above 0 (no slack) and the sag minimum",
        "drive slip margin": "at least 1",
        "largest sag": f"carry {sag['carry']:g} %, return {sag['return']:g} %",
        "belt safety factor": f"{sf:g} running, {TRANSIENT_SAFETY_RATIO * sf:.3g} transient",
        "take-up carriage travel": f"{travel:g} m of travel",
    }
    return out


def _governing_section(study: dict, runs: pd.DataFrame) -> str:
    ok = runs[runs["status"] != "failed"] if "status" in runs else runs
    axes = [a["column"] for a in study.get("axes", [])]
    if "friction_model" not in axes:
        axes.insert(0, "friction_model")
    axes = [a for a in axes if a in ok.columns]
    limits = _limits(study, runs)
    rows = []
    locate = _locator(study)
    for label, dyn, steady, pick, unit, at_dyn, at_steady in GOVERNING:
        col, at_col = dyn, at_dyn
        values = pd.to_numeric(ok[col], errors="coerce") if col in ok else None
        if values is None or not values.notna().any():
            col, at_col = steady, at_steady
            values = pd.to_numeric(ok[col], errors="coerce") if col and col in ok else None
        if values is None or not values.notna().any():
            continue
        idx = values.idxmax() if pick == "max" else values.idxmin()
        row = ok.loc[idx]
        at = row.get(at_col) if at_col else None
        point = "<br>".join(f"{_e(a)} = {_e(_text(row.get(a)))}" for a in axes)
        rows.append([_e(label), _n(values.loc[idx], 5) + f" {unit}",
                     _e(_where_on_loop(locate, at)), _e(limits.get(label, "")),
                     f"<code>{_e(row['run_id'])}</code><br>{_e(row.get('status'))}", point])
    if not rows:
        return "<p>No finished runs yet.</p>"
    return (_table(["case", "value", "where", "limit", "run", "its grid point"], rows,
                   "governing")
            + "<p class=muted>Values from the column of the transient where the study ran it "
            "(t_max_dyn_kn, t_min_dyn_kn, slip_margin_min_dyn, sag_max_dyn_pct, "
            "safety_factor_dyn, takeup_travel_m), else the steady one; an axis shown as "
            "<i>any</i> does not change that run.</p>")


def _text(value: Any) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "any"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def _runs_section(study: dict, runs: pd.DataFrame) -> str:
    axes = [a["column"] for a in study.get("axes", [])]
    if "friction_model" not in axes:
        axes.insert(0, "friction_model")
    results = [c for c in ("power_kw", "t_max_kn", "t_min_kn", "t_max_dyn_kn", "t_min_dyn_kn",
                           "safety_factor", "takeup_mass_kg", "fill_pct") if c in runs
               and pd.to_numeric(runs[c], errors="coerce").notna().any()]
    shown = runs.sort_values(axes, kind="stable").head(MAX_RUN_ROWS) if len(runs) else runs
    rows, classes = [], []
    for _, r in shown.iterrows():
        rows.append([f"<code>{_e(r['run_id'])}</code>"] + [_e(_text(r.get(a))) for a in axes]
                    + [_n(r.get(c)) for c in results] + [_e(r.get("status")),
                                                         _e(r.get("message"))])
        classes.append(r.get("status"))
    out = [_table(["run", *axes, *results, "status", "message"], rows, "runs",
                  row_cls=lambda i: classes[i] if classes[i] in ("warning", "failed") else "")]
    if len(runs) > MAX_RUN_ROWS:
        out.append(f"<p class=muted>The first {MAX_RUN_ROWS} of {len(runs)} runs; all of them "
                   "are in the study's Parquet (<code>GET /studies/{id}/runs</code>).</p>")
    return "".join(out)


def _accuracy_section(study: dict, service: StudyService, study_id: str) -> str:
    """The error of each result column over the study's accuracy sample (the error bars of
    ``accuracy: {sample: ...}``), or why there is none."""
    asked = study.get("accuracy")
    if not asked:
        return ("<p class=muted>No error bars: the study has no <code>accuracy: {sample: "
                "...}</code> (beltstudy simulate checks a single run by default).</p>")
    acc, cols = service.accuracy(study_id)
    if not len(cols):
        return "<p class=muted>No sampled run has finished yet.</p>"
    rows = [[f"<code>{_e(r['column'])}</code>", _e(r["unit"]), _n(r["runs"]),
             _n(r["value_median"]), _n(r["err_median"]), _n(r["err_max"]),
             _n(r["err_rel_max_pct"], 3)] for r in query.records_to_json(cols)]
    return (f"<p>Error bars of {len(acc)} sampled runs (sample {_e(asked.get('sample'))}, "
            f"seed {_e(asked.get('seed', 0))}): each run repeated on a mesh half and one "
            "twice as fine, the step following the mesh; Richardson extrapolation where the "
            "observed order allows, else the spread (docs/dynamics.md, Error bars). The "
            "value at a finer mesh lies within value +- error. The accuracy table is "
            "<code>GET /studies/{id}/accuracy</code>.</p>"
            + _table(["column", "unit", "runs", "value (median)", "error (median)",
                      "error (largest)", "largest error / value [%]"], rows, "runs"))


def build_report(service: StudyService, study_id: str) -> str:
    """The design report of a study as one self-contained HTML page."""

    doc = service.store.read(study_id)
    status = service.status(study_id)
    study = doc["study"]
    runs = service.store.read_runs(study_id)
    try:
        cap = capacity(parse_conveyor(study["conveyor"]))
        fill = {"fill_pct": cap.fill_pct, "volume_flow_m3_h": cap.volume_flow_m3_h,
                "capacity_m3_h": cap.capacity_m3_h}
    except Exception:  # a conveyor this engine cannot read: the rest of the report still helps
        fill = None
    name = doc.get("name", study_id)
    when = time.strftime("%Y-%m-%d %H:%M", time.gmtime(doc.get("finished_at")
                                                        or doc.get("updated_at") or time.time()))
    figs = []
    for plot, caption in (
        ("power-temperature", "Power at the drive pulleys against temperature: a line per "
                              "combination of the other axes."),
        ("peak-dynamic-tension", "Peak and lowest belt tension of the stop against the stop "
                                 "time achieved."),
        ("ratio", "Candidate / baseline friction model ratio per axis value (bar: mean, "
                  "whisker: smallest to largest)."),
    ):
        if plot == "peak-dynamic-tension" and not study.get("dynamics"):
            continue
        if plot == "ratio" and ("friction_model" not in runs or
                                runs["friction_model"].nunique() < 2):
            continue
        figs.append(_figure(_png(figures.study_figure(service, study_id, plot)), caption, plot))
    counts = runs["status"].value_counts().to_dict() if len(runs) else {}
    state = (f"{status['state']}, {status['done']} of {status['total']} runs finished"
             + (f" ({', '.join(f'{v} {k}' for k, v in counts.items())})" if counts else ""))
    parts = [
        "<!doctype html><html lang=en><head><meta charset=utf-8>",
        f'<meta http-equiv="Content-Security-Policy" content="{REPORT_CSP}">',
        f"<title>Design report · {_e(name)}</title><style>{CSS}</style></head><body>",
        f"<h1>Design report: {_e(name)}</h1>",
        f"<p class=muted>study <code>{_e(study_id)}</code> · {_e(state)} · engine "
        f"{_e(doc.get('engine_version'))} · {_e(when)} UTC</p>",
        f"<p>{_e(study.get('description', ''))}</p>" if study.get("description") else "",
        "<h2>1. Conveyor</h2>",
        f"<p class=muted>from {_e(study.get('conveyor_source', 'inline'))}; conveyor axes of "
        "the grid change it per design (section 2).</p>",
        _conveyor_section(study["conveyor"], fill),
        "<h2>2. Design basis</h2>",
        _design_section(study),
        "<h2>3. The grid</h2>",
        _grid_section(study, status),
        "<h2>4. Governing cases</h2>",
        "<p>The run that sets each design quantity, over every finished run (transient values "
        "where the study ran the transient, else steady ones).</p>",
        _governing_section(study, runs),
        "<h2>5. Comparison</h2>",
        "".join(figs) or "<p>No figures: no finished runs yet.</p>",
        "<h2>6. Runs</h2>",
        _runs_section(study, runs),
        "<h2>7. Error of each column</h2>",
        _accuracy_section(study, service, study_id),
        "</body></html>",
    ]
    return "".join(parts)
