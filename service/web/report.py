"""The design report of a study: one self-contained HTML page to hand to a client.

``GET /studies/{id}/report`` and ``beltstudy report ID -o FILE.html`` both call
:func:`build_report`. The page needs nothing else: its style is inline, its figures are PNGs
inside the page as ``data:`` URIs, it has no script and links nowhere, so it opens from a file
and prints cleanly to PDF from a browser (A4, tables and figures kept whole). Every value taken
from the study is escaped.

Contents, verdicts first: (1) the verdicts, a governing case for every design quantity the
runs carry (:data:`beltstudy.service.web.verdicts.VERDICTS`: power and utilisation per drive,
belt safety factor, T_max and T_min per phase, take-up, brakes, the stop, slip, sag, pulleys,
idlers, the vertical and horizontal curves) with its limit and how many runs are past it; (2) every run that did not pass, grouped
by cause (:data:`~beltstudy.service.web.verdicts.CAUSES`: failed, ran away, did not stop,
never got going, overloaded a drive, slipped, ...), each group with its count and the figures that show it;
(3) the start and stop peaks against the study's axes; then the conveyor and its capacity
check, the design basis, the grid, the comparison figures, the runs and the error bars.
Every number goes through :func:`beltstudy.service.web.numbers.eng` (``16 886 kg``).
"""

from __future__ import annotations

import base64
import html
import math
import re
import time
from typing import Any

import pandas as pd

from beltstudy.engine import (
    BELT_AUTO,
    SAFETY_FACTOR_MIN,
    TRANSIENT_SAFETY_RATIO,
    build_loop,
    capacity,
    catalog,
    governed_at,
    parse_conveyor,
    resolve_belt,
    with_belt,
)
from beltstudy.engine import results as result_fields
from beltstudy.engine.conveyor import place
from beltstudy.service import charts
from beltstudy.service.store import query
from beltstudy.service.studies import StudyService
from beltstudy.service.web import figures
from beltstudy.service.web.numbers import eng
from beltstudy.service.web.uncertainty import uncertainty_section
from beltstudy.service.web.verdicts import (
    cause_groups,
    finding_clauses,
    never_going,
    said_clauses,
    study_limits,
    verdict_rows,
)

__all__ = ["build_report", "report_html", "REPORT_CSP", "CSS"]

#: Content security policy of the report: no script, no fetches, images only from the page.
REPORT_CSP = ("default-src 'none'; img-src data:; style-src 'unsafe-inline'; base-uri 'none'; "
              "form-action 'none'; frame-ancestors 'none'")

#: The page's style: A4 in print, each numbered section from a new page, table headers
#: repeated on every page, rows never split, cells that wrap rather than widen a table past
#: the page (docs/report_pdf.py checks every table against the page width).
CSS = """
body { font-family: "DejaVu Sans", Arial, sans-serif; font-size: 10.5pt; color: #111;
  margin: 1.5em auto; max-width: 64em; padding: 0 1em; }
h1 { font-size: 17pt; margin-bottom: 0.2em; }
h2 { font-size: 13pt; border-bottom: 1px solid #888; margin-top: 1.6em; }
h3 { font-size: 11pt; margin: 1em 0 0.3em; }
.muted { color: #555; }
table { border-collapse: collapse; margin: 0.4em 0 0.8em; max-width: 100%; }
th, td { border: 1px solid #bbb; padding: 0.15em 0.45em; text-align: left; vertical-align: top;
  overflow-wrap: anywhere; }
th { background: #eef1f5; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap;
  overflow-wrap: normal; }
td.num .muted { white-space: normal; overflow-wrap: normal; }
td code.id { font-size: 7pt; word-break: break-all; }
td.ax { white-space: nowrap; overflow-wrap: normal; }
tr.warning td { background: #fff6da; }
tr.failed td, td.fails { background: #fde8e8; }
td.passes { background: #e8f6e8; }
tr.group th { background: #dde3ea; text-align: left; }
figure { margin: 0.8em 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; box-sizing: border-box; }
figcaption { font-size: 9pt; color: #444; }
code { font-size: 9pt; }
.runs, .verdicts, .causes { font-size: 8.5pt; }
table.verdicts, table.causes, table.runs { width: 100%; }
.run { font-size: 7.5pt; color: #444; }
details summary { cursor: pointer; }
.print-full { display: none; }
tr.print-row { display: none; }
ul.causes-list { margin: 0.3em 0 0.8em; }
@page { size: A4; margin: 14mm 12mm; }
@media print {
  body { margin: 0; max-width: none; padding: 0; font-size: 9pt; }
  h2 { break-after: avoid; page-break-after: avoid; }
  h2.section { break-before: page; page-break-before: always; }
  h3 { break-after: avoid; page-break-after: avoid; }
  table { break-inside: auto; }
  tr, figure { break-inside: avoid; page-break-inside: avoid; }
  thead { display: table-header-group; }
  .runs, .verdicts, .causes { font-size: 7.5pt; }
  details summary { list-style: none; }
  details summary::-webkit-details-marker { display: none; }
  details.fold-print { display: none; }
  .print-full { display: inline; }
  tr.print-row { display: table-row; }
  tr.print-row td { padding-left: 1.5em; }
  tr.has-print-rows { break-after: avoid; page-break-after: avoid; }
  table.split th:last-child, table.split tr:not(.print-row) > td:last-child { display: none; }
}
"""

#: Marks a number cell of :func:`_table` (right-aligned).
NUM = "\x00"
#: Marks a row of :func:`_table` that only print shows: one clause of the row above it,
#: across the table (a failure group's row with three drives' overload clauses, 2 386
#: characters, printed in its last column 1 775 px tall, more than an A4 page).
PRINT_ROW = "print-row"
#: Runs listed in the report's runs table (the Parquet has them all).
MAX_RUN_ROWS = 400
#: Runs listed per failure group (the runs table and the Parquet have them all).
MAX_CAUSE_ROWS = 60
#: Characters of a message shown before the rest folds into a <details> element.
MESSAGE_CHARS = 90
#: What a folded message of the runs table says in print, where its fold stays closed.
SAID_POINTER = "(the rest: every clause in the run's own words in section 10)"
#: Result columns of the runs table (the first six the runs carry, so the table fits a page):
#: the transient's per phase when the study ran it, else the steady ones.
RUN_COLUMNS = ("power_kw", "t_max_start_kn", "t_max_stop_kn", "t_min_stop_kn",
               "t_max_dyn_kn", "t_min_dyn_kn", "stop_time_s", "t_max_kn", "t_min_kn",
               "safety_factor", "takeup_mass_kg", "fill_pct")
#: Most result columns of the runs table.
RUN_COLUMNS_MAX = 6


def _e(value: Any) -> str:
    return html.escape("" if value is None else str(value), quote=True)


def _pitch(idler_set: dict) -> str:
    """An idler set's pitch as the file gives it: ``spacing S m`` or ``N sets``."""
    if idler_set.get("spacing_m") is not None:
        return f"spacing {idler_set['spacing_m']:g} m"
    return f"{idler_set['count']} sets along the route"


def _place(item: dict) -> str:
    """A drive's or take-up's position: ``head``, ``tail`` or ``carry at 1000 m``."""
    return place(item["position"], item.get("at_m"))


def _brake_place(brake: dict, drives: list[dict]) -> str:
    """A brake's place: ``head`` or ``tail``, or the drive whose shaft it brakes
    (``drive 2 (carry at 700 m)`` for ``drive: 2``)."""
    n = brake.get("drive")
    if n is None:
        return brake["position"]
    return f"drive {n} ({_place(drives[n - 1])})" if 0 < n <= len(drives) else f"drive {n}"


def _num(value: Any, digits: int = 4, unit: str = "") -> str:
    """A number in engineering format (:func:`eng`), escaped."""
    return _e(eng(value, unit, digits))


def _table(head: list[str], rows: list[list[str]], cls: str = "", row_cls=None) -> str:
    """An HTML table: ``head`` is text (escaped), ``rows`` are cells of markup (a cell
    starting with :data:`NUM` is a right-aligned number, one holding ``\x01CLASS\x01`` at
    its start gets that class), a heading spanning the table (a str) or a clause that only
    print shows (a ``(PRINT_ROW, markup)`` tuple, spanning every column but the last, which
    a ``split`` table hides in print)."""
    out = [f'<table class="{cls}">' if cls else "<table>", "<thead><tr>"]
    out += [f"<th>{_e(h)}</th>" for h in head]
    out.append("</tr></thead><tbody>")
    for i, row in enumerate(rows):
        if isinstance(row, str):  # a group heading spanning the table
            out.append(f'<tr class="group"><th colspan="{len(head)}">{row}</th></tr>')
            continue
        if isinstance(row, tuple):  # PRINT_ROW: a clause that only print shows, spanning
            out.append(f'<tr class="print-row"><td colspan="{len(head) - 1}">{row[1]}</td></tr>')
            continue
        rc = row_cls(i) if row_cls else ""
        out.append(f'<tr class="{rc}">' if rc else "<tr>")
        for c in row:
            cls_ = ""
            if c.startswith("\x01"):
                cls_, c = c[1:].split("\x01", 1)
            if c.startswith(NUM):
                out.append(f'<td class="num {cls_}">{c[1:]}</td>')
            else:
                out.append(f'<td class="{cls_}">{c}</td>' if cls_ else f"<td>{c}</td>")
        out.append("</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def _n(value: Any, digits: int = 4, unit: str = "") -> str:
    """A number cell (right-aligned)."""
    return NUM + _num(value, digits, unit)


def _unit(column: str) -> str:
    """The unit of a result column (its field in engine/results.py, else its name's end)."""
    try:
        unit = result_fields.field(column).unit
        return "" if unit in ("-", "text") else unit
    except KeyError:
        pass
    for end, unit in (("_kn", "kN"), ("_kw", "kW"), ("_knm", "kNm"), ("_kg", "kg"),
                      ("_m_s", "m/s"), ("_m", "m"), ("_s", "s"), ("_pct", "%"), ("_h", "h"),
                      ("_n", "N")):
        if column.endswith(end):
            return unit
    return ""


def _message_cell(message: Any, chars: int = MESSAGE_CHARS, print_full: bool = False,
                  pointer: str = "") -> str:
    """A message that keeps its row short: the first ``chars`` characters, the rest folded
    into a ``<details>`` element. A closed ``<details>`` does not print, so with
    ``print_full`` the whole text is also given in a span that only print shows (the report
    has no script to open the folds): what would avoid a limit, at the end of a long clause,
    is on the PDF too. ``pointer``: where else the report has the whole text, said after a
    fold in print only (the runs table's section 8 points to section 10)."""
    text = "" if message is None or (isinstance(message, float) and math.isnan(message)) \
        else str(message)
    if len(text) <= chars:
        return _e(text)
    cut = text.rfind(" ", 0, chars)
    cut = cut if cut > chars // 2 else chars
    if print_full:
        return (f"<details class=fold-print><summary>{_e(text[:cut])} …</summary>"
                f"{_e(text[cut:])}</details><span class=print-full>{_e(text)}</span>")
    return (f"<details><summary>{_e(text[:cut])} …</summary>{_e(text[cut:])}</details>"
            + (f"<span class=print-full>{_e(pointer)}</span>" if pointer else ""))


def _png(make) -> str:
    data = figures.render(make, "png")
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def _figure(src: str, caption: str, alt: str) -> str:
    return (f'<figure><img src="{src}" alt="{_e(alt)}"><figcaption>{_e(caption)}'
            "</figcaption></figure>")


def _given(value: Any, unit: str) -> str:
    """A size as the file gives it: ``auto``, or its number as the report writes numbers
    (``2 400 kg``, not ``2400.0 kg``), to six figures so a given size reads as given."""
    return str(value) if isinstance(value, str) else eng(value, unit, 6)


def _conveyor_section(conv: dict, fill: dict | None) -> str:
    belt = conv["belt"]
    mat = conv["material"]
    tu = conv["takeup"]
    length = sum(p["length_m"] for p in conv["profile"])
    lift = sum(p["lift_m"] for p in conv["profile"])
    rows = [
        ["name", _e(conv["name"])],
        ["length along the carry strand", _num(length, unit="m")],
        ["net lift, tail to head", _num(lift, unit="m")],
        ["design speed", _num(conv['speed_m_s'], unit="m/s")],
        ["belt", _e(f"{belt.get('type') or 'custom'}, {belt['width_m']:g} m wide, compound "
                    f"{belt.get('compound', 'standard')}")],
        ["design capacity", f"{_num(mat['capacity_t_h'], unit='t/h')} at "
                            f"{_num(mat['density_t_m3'], unit='t/m³')}, surcharge "
                            f"{mat.get('surcharge_deg', 20):g}°"],
        ["carry idlers", _e(f"{conv['idlers']['carry'].get('rolls', 3)} rolls, trough "
                            f"{conv['idlers']['carry'].get('trough_deg', 0):g}°, "
                            + _pitch(conv['idlers']['carry']))],

        ["take-up", _e(f"{tu['type']} at the {_place(tu)}, "
                       + (f"mass {_given(tu['mass_kg'], 'kg')}" if tu["type"] == "gravity"
                          else f"pretension {_given(tu['pretension_kn'], 'kN')}")
                       + ("" if tu.get("sag_at_rest", True)
                          else "; sized for the sag limits running only"))],
        ["sag limits", _e(f"carry {conv['sag_limit_pct']['carry']:g} %, return "
                          f"{conv['sag_limit_pct']['return']:g} %")],
    ]
    if mat.get("feed"):
        rows.append(["feed points", _e("; ".join(
            f"{f['share']:g} of the capacity at {f['at_m']:g} m"
            + (f", skirts {f['skirt_length_m']:g} m" if f.get("skirt_length_m") else "")
            for f in mat["feed"]))])
    if fill is not None:
        rows.append(["capacity check (ISO 5048)",
                     f"fill {_num(fill['fill_pct'], 3, '%')} of the cross-section at design speed "
                     f"({_num(fill['volume_flow_m3_h'])} of {_num(fill['capacity_m3_h'], unit='m³/h')}"
                     f"{', over 100 %: the design load does not fit' if fill['fill_pct'] > 100 else ''})"])
    out = [_table(["", ""], rows)]
    out.append("<h3>Profile (tail to head)</h3>")
    out.append(_table(["section", "length [m]", "lift [m]", "slope [%]"], [
        [str(i + 1), _n(p["length_m"]), _n(p["lift_m"]), _n(100 * p["lift_m"] / p["length_m"], 3)]
        for i, p in enumerate(conv["profile"])]))
    out.append("<h3>Drives and brakes</h3>")
    drows = [[f"drive {i + 1}", _e(_place(d)), _n(d["wrap_deg"]), _n(d["friction"]),
              _n(d["share"]), _e("auto") if d.get("rated_power_kw") is None
              else _n(d["rated_power_kw"])]
             for i, d in enumerate(conv["drives"])]
    out.append(_table(["", "position", "wrap [°]", "friction", "share", "rated power [kW]"],
                      drows))
    if conv.get("brakes"):
        out.append(_table(["brake", "position", "force [kN]", "delay [s]"], [
            [str(i + 1), _e(_brake_place(b, conv["drives"])), _n(b["force_kn"]),
             _n(b["delay_s"])]
            for i, b in enumerate(conv["brakes"])]))
    return "".join(out)


def _held(runs: pd.DataFrame | None, axes: dict, governed: str, column: str, unit: str
          ) -> str:
    """What the runs of one conveyor design (``axes``) say of an auto size: nothing when they
    hold it; where every one of them has it ``given`` (a grid or sample axis sets the size per
    run, e.g. a sampled ``takeup.mass_kg``), that the size was not held and what the runs
    used. The design basis said 'take-up mass 17 020 kg ... held for every run' of a study
    whose 512 runs each had their sampled mass, 15 736 to 18 244 kg."""
    if runs is None or not len(runs) or governed not in runs or column not in runs:
        return ""
    part = runs
    for k, val in axes.items():
        if k in part:
            part = part[part[k].astype(str) == str(val)]
    gov = part[governed].dropna().astype(str)
    if not len(gov) or not (gov == "given").all():
        return ""
    used = pd.to_numeric(part[column], errors="coerce").dropna()
    span = ("" if not len(used) else f": {eng(used.min(), unit)}" if used.min() == used.max()
            else f": {eng(used.min(), unit)} to {eng(used.max(), unit)}")
    return (f"; not held: each of its {len(part)} runs sets its own ({governed} given, "
            f"{column}{span})")


def _design_section(study: dict, runs: pd.DataFrame | None = None) -> str:
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
        # a grid axis of an auto field (takeup.mass_kg: [4100, 3000]) gives that size per run
        set_by = [a.get("name", "") for a in study.get("axes") or []
                  if str(a.get("name", "")).split(".")[0] in ("takeup", "drives", "brakes",
                                                               "belt")]
        given = (f"given in the file or set per run by the study's grid axes "
                 f"({', '.join(set_by)}: each run's own value is in its row)" if set_by
                 else "given in the file")
        out.append(f"<p>The conveyor has no auto sizes: every size is {_e(given)}.</p>")
        return "".join(out)
    rows = []
    for d in designs:
        where = ", ".join(f"{k}={v}" for k, v in d["axes"].items()) or "the conveyor"
        ax = d["axes"]
        sizes = d["sizes"]
        tu = sizes.get("takeup")
        if tu:
            rows.append([_e(where), "take-up " + ("mass" if tu["unit"] == "kg" else
                                                  "pretension"),
                         _n(tu["value"], 5, tu["unit"]),
                         _e(governed_at(tu["governed_by"], tu.get("at", ""))
                            + _held(runs, ax, "takeup_governed_by",
                                    "takeup_mass_kg" if tu["unit"] == "kg"
                                    else "takeup_pretension_kn", tu["unit"])),
                         _e(tu["case"])])
        for i, dr in enumerate(sizes.get("drives") or []):
            if dr:
                rows.append([_e(where), f"rated power, drive {i + 1}",
                             _n(dr["rated_power_kw"], 5, "kW"),
                             _e(governed_at(dr["governed_by"], dr.get("at", ""))
                                + _held(runs, ax, "rated_power_governed_by",
                                        f"drive{i + 1}_rated_power_kw", "kW")),
                             _e(dr["case"])])
        brakes = sizes.get("brakes")
        if brakes:
            entries = [("held at rest (no brake stop)", brakes["holding"])] + [
                (f"brake stop in {t} s", e) for t, e in brakes["stop_time_s"].items()]
            for label, e in entries:
                rows.append([_e(where), f"brake force, {label}",
                             _n(sum(e["force_kn"]), 5, "kN"),
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
        rows.append([_e(a["name"]), _e(group), _e(", ".join(_text(v) for v in a["values"]))])
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
    """``s_m -> (strand, distance from the tail)`` on the study's conveyor, an auto belt on
    its design's (None if the conveyor cannot be read here)."""

    try:
        return build_loop(_on_design_belt(study), 1.0).where
    except Exception:  # made by another engine version
        return None


def _where_on_loop(locate, at) -> str:
    if locate is None or at is None or (isinstance(at, float) and not math.isfinite(at)):
        return ""
    try:
        strand, x = locate(float(at))
    except (TypeError, ValueError):
        return ""
    if strand in ("carry", "return"):
        return f"{strand}, {eng(x, 'm', 3)} from the tail"
    return f"{strand} pulley"


def _sf_min(study: dict) -> float:
    """The belt safety factor the study is judged against (the conveyor's, else DIN 22101's
    for its belt kind)."""
    conv = study["conveyor"]
    try:
        kind = resolve_belt(parse_conveyor(conv).belt).kind
    except Exception:  # a conveyor this engine cannot read, or belt.type: auto
        kind = catalog.KIND_OF_FILE.get(conv["belt"].get("kind") or "", "steel")
    return float(conv.get("safety_factor_min") or SAFETY_FACTOR_MIN.get(kind, 6.7))


def _sf_of_runs(study: dict):
    """The belt safety factor each run is judged against: the conveyor's
    ``safety_factor_min`` (a grid axis of it: the run's own), else DIN 22101's minimum for
    the kind of the belt the run used (``belt_type_used``: a ``belt_type`` axis mixing steel
    cord and fabric judges each run by its own belt, 6.7 or 10, as the engine's warnings do),
    else the conveyor's (:func:`_sf_min`). Returns ``runs -> Series``."""
    given = study["conveyor"].get("safety_factor_min")
    default = _sf_min(study)
    kinds = {k: b.kind for k, b in catalog.belts().items()}

    def of(runs: pd.DataFrame) -> pd.Series:
        out = pd.Series(default, index=runs.index, dtype=float)
        if not given and "belt_type_used" in runs:
            kind = runs["belt_type_used"].map(lambda t: kinds.get(t) if isinstance(t, str)
                                              else None)
            known = kind.notna()
            out[known] = kind[known].map(lambda k: SAFETY_FACTOR_MIN.get(k, default))
        own = (pd.to_numeric(runs["safety_factor_min"], errors="coerce")
               if "safety_factor_min" in runs else None)
        return out if own is None else own.fillna(out)
    return of


def _axes(study: dict, runs: pd.DataFrame) -> list[str]:
    """The axis columns that name a run: the study's axes, the friction model first."""
    axes = [a["column"] for a in study.get("axes", [])]
    if "friction_model" not in axes:
        axes.insert(0, "friction_model")
    return [a for a in axes if a in runs.columns]


def _text(value: Any) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "any"
    if isinstance(value, float | int) and not isinstance(value, bool):
        return eng(value, "", 6)
    return str(value)


def _run_cell(row: pd.Series, axes: list[str]) -> str:
    """A run as the report names it: its axis values, then its id."""
    point = " · ".join(f"{_e(a)} {_e(_text(row.get(a)))}" for a in axes)
    return f"{point}<br><span class=run>run <code>{_e(row.get('run_id'))}</code></span>"


def _verdict_cell(r: dict) -> str:
    """Within the limit, past it in some runs, or no limit to judge against; and how many
    runs are marginal on it (the figure within its error bar of the limit)."""
    cell = _verdict_words(r)
    k = r.get("marginal") or 0
    if k:
        cell += f"; marginal in {k} run{'s' if k != 1 else ''} (section 2)"
    return cell


def _verdict_words(r: dict) -> str:
    v = r["verdict"]
    if r["missing"]:
        away = r.get("ran_away") or 0
        both = ("all of them ran away" if away == r["missing"]
                else f"{away} of them ran away")
        return (f"\x01fails\x01{r['missing']} of {r['n']} runs {_e(v.null_worst)}"
                + (f" ({both}, section 2)" if away else ""))
    if r["limit"] is None and not r.get("ok_col") and v.limit != "sag":
        return "<span class=muted>no limit</span>"
    if r["limit"] is None and r.get("ok_col") and r.get("ok_judged") == 0 and not r["past"]:
        # a plain or take-up pulley: its diameter is the loop's estimate, its minimum is
        # reported and not judged (``pulley{j}_diameter_min_ok`` null in every run)
        return ("<span class=muted>not judged: the file gives no diameter for this pulley "
                "(docs/checks.md)</span>")
    if r["past"] and v.limit == "travel":
        return (f"\x01fails\x01the whole travel used (the carriage at its end stops) in "
                f"{r['past']} of {r['n']} runs")
    if r["past"]:
        # a pulley that slips holds its margin at the limit itself (it passes all its grip):
        # "1 against 1, past the limit" read as a contradiction without the why
        held = (v.said and isinstance(r["value"], float) and isinstance(r["limit"], float)
                and (r["value"] >= r["limit"] if v.worst == "min" else r["value"] <= r["limit"]))
        return (f"\x01fails\x01past the limit in {r['past']} of {r['n']} runs"
                + (": a drive pulley slipped in each (while it slips its margin reads the "
                   "limit itself, the grip all used; the time slipping rows say how long)"
                   if held else ""))
    if r["limit"] is None and v.limit == "sag" and not r.get("ok_col"):
        return "\x01passes\x01within the limits of each strand (no run warns)"
    return f"\x01passes\x01within ({r['n']} runs)"


#: The verdicts the engine calls marginal when their error bar reaches the limit
#: (engine/accuracy.py ``marginal_verdicts``), as the report's verdict rows show them.
MARGINAL_JUDGED = frozenset({"t_min_dyn_kn", "t_min_start_kn", "t_min_stop_kn",
                             "slack_max_m", "sag_max_dyn_pct", "slip_margin_min_dyn",
                             "safety_factor_dyn", "takeup_endstop_speed_m_s",
                             "liftoff_max_kn_over"})


def _apart(value: Any, limit: Any, digits: int = 4) -> int:
    """The significant digits that write a value and its limit apart when they differ: a
    slip margin of 0.99996 against 1 read '1' and '1', past the limit yet shown equal to it.
    Four where they already read apart (or either is missing); at most twelve."""
    if value is None or limit is None or value == limit:
        return digits
    while digits < 12 and eng(value, "", digits) == eng(limit, "", digits):
        digits += 1
    return digits


def _verdicts_section(study: dict, runs: pd.DataFrame, bars: pd.DataFrame | None = None
                      ) -> str:
    """The verdict table: every design quantity the runs carry, its worst value over the
    finished runs, its limit, how many runs are past it and the run that governs it; where
    the governing run is in the accuracy sample (``bars``), its value's error bar."""
    sf = _sf_min(study)
    words = ("the conveyor's minimum" if study["conveyor"].get("safety_factor_min")
             else "DIN 22101 minimum")
    rows_ = verdict_rows(runs, study_limits(study, sf, TRANSIENT_SAFETY_RATIO, words,
                                            sf_of=_sf_of_runs(study)))
    if not rows_:
        # every run failed: no figure to judge (not 'yet': the study may be done)
        failed = int((runs["status"] == "failed").sum()) if "status" in runs else 0
        if failed and failed == len(runs):
            return (f"<p>All {failed} finished runs failed: no figure to judge. Their "
                    "messages are under <em>Runs that did not pass</em>.</p>")
        return "<p>No finished runs yet.</p>"
    axes = _axes(study, runs)
    locate = _locator(study)
    rows, group = [], None
    for r in rows_:
        v = r["verdict"]
        if v.group != group:
            group = v.group
            rows.append(_e(group))
        if v.worst == "text":
            rows.append([_e(r["label"]), _e(r["value"]), "", "<span class=muted>–</span>",
                         _run_cell(r["row"], axes), ""])
            continue
        digits = _apart(r["value"], r["limit"])
        value = (_e(v.null_worst) if r["missing"] else _e(r["value_text"])
                 if r.get("value_text") else _n(r["value"], digits, v.unit))
        err = run_bars(bars, r["row"].get("run_id")).get(r["column"]) if not r["missing"] \
            else None
        if err is not None:
            # a bar of a figure in % is in percentage points, not a fraction of the figure
            bar = (f"{_num(err, 3, '')} percentage points" if v.unit == "%"
                   else _num(err, 3, v.unit))
            value += (f"<br><span class=muted>± {bar} (the error bar of this sampled run, "
                      "section 9)")
            said = str(r["row"].get("message") or "")
            # the limits the engine judged it against: the row's, or each strand's sag limit
            # (the row has none where they differ: the engine took the strand of the peak)
            sag = (study["conveyor"].get("sag_limit_pct") or {}) if r["limit"] is None \
                and v.limit == "sag" else {}
            lims = ([r["limit"]] if r["limit"] is not None
                    else [float(x) for x in (sag.get("carry"), sag.get("return"))
                          if x is not None] if len(sag) == 2 else [])
            if (r["column"] in MARGINAL_JUDGED and r["past"] and r["value"] is not None
                    and lims and all(abs(r["value"] - lim) <= err for lim in lims)
                    and f"marginal: {r['column']} " not in said):
                # the bar reaches the limit, yet the run names no marginal verdict: the engine
                # (engine/accuracy.py ``_marginal``) calls none where every mesh of the check
                # fails, each finer one further past the limit (no mesh flips it)
                value += ("; it reaches the limit, yet every mesh of the check is past it, "
                          "each finer one further, so the verdict holds and is not marginal")
            value += "</span>"
        limit = (_n(r["limit"], digits, v.unit) if r["limit"] is not None else "")
        if r["limit_text"]:
            limit += (f"<br><span class=muted>{_e(r['limit_text'])}</span>" if limit
                      else f"<span class=muted>{_e(r['limit_text'])}</span>")
        where = _where_on_loop(locate, r["row"].get(v.at)) if v.at else ""
        worst = "largest" if v.worst == "max" else "smallest"
        if r.get("relative"):  # the limit differs between runs: the worst against its own
            worst = f"{worst} against its own limit:"
        rows.append([f"{_e(r['label'])}<br><span class=muted>{worst} "
                     f"<code>{_e(r['column'])}</code></span>",
                     value, limit, _verdict_cell(r),
                     _run_cell(r["row"], axes), _e(where)])
    return (_table(["quantity", "value", "limit", "verdict", "governing run", "where"], rows,
                   "verdicts")
            + "<p class=muted>Over every run that finished (a failed run has no values; it "
            "is listed in section 2). A quantity is shown when the runs carry its column; the "
            "governing run has the worst value (for a stop, a run that did not stop). Limits: "
            f"belt safety factor {eng(sf, '', 3)} running and "
            f"{eng(TRANSIENT_SAFETY_RATIO * sf, '', 3)} transient (DIN 22101), the tension "
            "they allow from the belt's rating, no slack (lowest tension above 0), a slip "
            "margin of at least 1, the rated power of the drives, the conveyor's sag limits "
            "and take-up travel, the CEMA rating and L10 basis of the carry idlers' class "
            "(docs/checks.md).</p>")


def _cause_table(cause, part: pd.DataFrame, cols: list[str], axes: list[str]) -> str:
    shown = part.sort_values(axes, kind="stable").head(MAX_CAUSE_ROWS) if axes else \
        part.head(MAX_CAUSE_ROWS)
    rows = []
    for _, r in shown.iterrows():
        said = finding_clauses(r.get("message"), cause.words)
        extra = cause.explain(r) if cause.explain else ""
        if extra and not any(extra in c for c in said):
            said.insert(0, extra)
        said = said or [r.get("message") or ""]
        rows.append([f"<code class=id>{_e(r.get('run_id'))}</code>"]
                    + ["\x01ax\x01" + _e(_text(r.get(a))) for a in axes]
                    + [_n(r.get(c), 4) for c in cols]
                    + [_message_cell("; ".join(said), 2 * MESSAGE_CHARS)])
        # in print the last column is hidden and each clause is a row across the table
        # under the run's figures: a row then never outgrows a page
        rows += [(PRINT_ROW, _e(c)) for c in said if c]
    head = ["run", *axes, *[f"{c} [{_unit(c)}]" if _unit(c) else c for c in cols],
            "what the run says"]
    out = _table(head, rows, "causes split",
                 row_cls=lambda i: ("has-print-rows" if i + 1 < len(rows)
                                    and isinstance(rows[i + 1], tuple) else ""))
    if len(part) > MAX_CAUSE_ROWS:
        out += (f"<p class=muted>The first {MAX_CAUSE_ROWS} of {len(part)}; section 8 and "
                "the study's Parquet have them all.</p>")
    return out


def _causes_section(study: dict, runs: pd.DataFrame) -> str:
    """Every run that did not pass, grouped by cause, each group with its count."""
    groups = cause_groups(runs)
    if not groups:
        return (f"<p>Every one of the {len(runs)} runs finished, stopped, stayed within its "
                "drives' rating and did not slip.</p>")
    axes = _axes(study, runs)
    items = "".join(f"<li><b>{len(part)}</b> of {len(runs)} runs {_e(cause.title)}</li>"
                    for cause, part, _ in groups)
    out = [f"<ul class=causes-list>{items}</ul>",
           "<p class=muted>A run with several causes is listed under each.</p>"]
    for cause, part, cols in groups:
        out.append(f"<h3>{_e(cause.title[0].upper() + cause.title[1:])}: {len(part)} "
                   f"run{'s' if len(part) != 1 else ''}</h3>")
        if cause.note:
            out.append(f"<p class=muted>{_e(cause.note)}</p>")
        out.append(_cause_table(cause, part, cols, axes))
    return "".join(out)


def _runs_section(study: dict, runs: pd.DataFrame) -> str:
    """The runs (the first :data:`MAX_RUN_ROWS`), their axis values, first results, status
    and message. A message folds past :data:`MESSAGE_CHARS`; a closed fold does not print,
    so in print the fold points to section 10, which has every clause of the run in its own
    words (:func:`said_whole`), or, for a run whose clauses section 10 does not list, prints
    the message whole."""
    axes = _axes(study, runs)
    whole = said_whole(runs)
    results = [c for c in RUN_COLUMNS if c in runs
               and pd.to_numeric(runs[c], errors="coerce").notna().any()]
    if "t_max_start_kn" in results:  # the phases say more than the whole cycle
        results = [c for c in results if c not in ("t_max_dyn_kn", "t_min_dyn_kn")]
    results = results[:RUN_COLUMNS_MAX]
    shown = runs.sort_values(axes, kind="stable").head(MAX_RUN_ROWS) if len(runs) else runs
    rows, classes = [], []
    for _, r in shown.iterrows():
        rows.append([f"<code class=id>{_e(r['run_id'])}</code>"] + ["\x01ax\x01" + _e(_text(r.get(a))) for a in axes]
                    + [_n(r.get(c)) for c in results]
                    + [f"<b>{_e(r.get('status'))}</b> " + (
                        _message_cell(r.get("message"), pointer=SAID_POINTER)
                        if r.get("run_id") in whole
                        else _message_cell(r.get("message"), print_full=True))])
        classes.append(r.get("status"))
    head = ["run", *axes, *[f"{c} [{_unit(c)}]" if _unit(c) else c for c in results],
            "status and message"]
    out = [_table(head, rows, "runs",
                  row_cls=lambda i: classes[i] if classes[i] in ("warning", "failed") else "")]
    if len(runs) > MAX_RUN_ROWS:
        out.append(f"<p class=muted>The first {MAX_RUN_ROWS} of {len(runs)} runs; all of them "
                   "are in the study's Parquet (<code>GET /studies/{id}/runs</code>).</p>")
    return "".join(out)


#: A number inside a message clause (``12.3``, ``-0.5``, ``1,234``, ``2.5e-05``): the kind of a
#: clause is its words with every number replaced.
_NUMBER = re.compile(r"[-+]?\d[\d,]*(?:\.\d+)?(?:e[-+]?\d+)?", re.IGNORECASE)
#: Kinds of clause listed (the rest counted).
MAX_KINDS = 300
#: Run ids per row of the last section: a wording said by more runs goes on in rows below it,
#: so that no row outgrows a quarter of an A4 page in print (docs/report_pdf.py, 250 px).
IDS_PER_ROW = 24


def clause_wordings(runs: pd.DataFrame) -> list[tuple[str, list[str], list[tuple[str, list]]]]:
    """Every clause of every run's message (:func:`said_clauses`: a finding with its fix), by
    kind (its words with the numbers as ``#``), most runs first: ``(kind, run ids, wordings)``,
    the wordings each run's own words with the runs that say exactly them, most runs first
    (a brake stop's 'at most about 15.7 kN in all' of one run and '7.81 kN' of another are
    one kind and two wordings). Nothing a run says is left out, however many runs the study
    has."""
    kinds: dict[str, tuple[list, dict[str, list]]] = {}
    if not len(runs) or "message" not in runs:
        return []
    for run_id, message in zip(runs["run_id"], runs["message"], strict=True):
        for _finding, clause in said_clauses(message):
            text = clause.strip()
            ids, texts = kinds.setdefault(_NUMBER.sub("#", text), ([], {}))
            if not ids or ids[-1] != run_id:
                ids.append(run_id)
            said_by = texts.setdefault(text, [])
            if not said_by or said_by[-1] != run_id:
                said_by.append(run_id)
    out = [(key, ids, sorted(texts.items(), key=lambda tw: -len(tw[1])))  # stable: first said
           for key, (ids, texts) in kinds.items()]
    return sorted(out, key=lambda item: (-len(item[1]), item[0]))


def clause_kinds(runs: pd.DataFrame) -> list[tuple[str, list[str], str]]:
    """Every clause of every run's message, by kind (:func:`clause_wordings`), most runs
    first: ``(kind, run ids, the first run's clause)``."""
    return [(key, ids, next(t for t, part in wordings if ids[0] in part))
            for key, ids, wordings in clause_wordings(runs)]


def said_whole(runs: pd.DataFrame) -> set:
    """The runs whose every clause the last section lists with the run's own words (the
    kinds within :data:`MAX_KINDS`): the runs table may fold their messages in print too."""
    wordings = clause_wordings(runs)
    if len(wordings) <= MAX_KINDS:
        return set(runs["run_id"]) if len(runs) and "run_id" in runs else set()
    cut = {i for _, ids, _ in wordings[MAX_KINDS:] for i in ids}
    return set(runs["run_id"]) - cut


def _said_section(runs: pd.DataFrame) -> str:
    """Every kind of warning, note and failure the runs' messages hold, and under it every
    run's own words with every run that says them: the part of the messages the runs table
    (its folds, its first rows) and the failure groups (their causes) do not show. The
    printed report showed each kind in its first run's words with five run ids ('and 3
    more'), so another run's figures (the brake force of 7.81 kN that would have met its
    stop) were on no page of the PDF: a wording is now a row of its own, its runs all named
    (:data:`IDS_PER_ROW` to a row), its text whole in print."""
    kinds = clause_wordings(runs)
    if not kinds:
        return f"<p>None of the {len(runs)} runs has a warning, a note or a failure.</p>"
    rows = []
    every = set(runs["run_id"])
    for _key, ids, wordings in kinds[:MAX_KINDS]:
        for text, said_by in wordings:
            count = (str(len(said_by)) if len(wordings) == 1
                     else f"{len(said_by)} of {len(ids)}")
            if len(every) > 1 and set(said_by) == every:
                chunks = [f"every run ({len(said_by)})"]
            else:
                chunks = [" ".join(f"<code class=id>{_e(i)}</code>"
                                   for i in said_by[k:k + IDS_PER_ROW])
                          for k in range(0, len(said_by), IDS_PER_ROW)]
            rows.append([NUM + count, chunks[0],
                         _message_cell(text, 2 * MESSAGE_CHARS, print_full=True)])
            rows += [[NUM, more, "<span class=muted>(the same words: more runs)</span>"]
                     for more in chunks[1:]]
    out = [f"<p>Each kind of clause in the {len(runs)} runs' messages (the same words with "
           "other numbers), each in every run's own words: runs that say the same words "
           "share a row, which names them all; <em>3 of 12</em>: three of the twelve runs "
           "that say this kind of clause say it in these words.</p>",
           _table(["runs", "run ids", "what they say"], rows, "causes")]
    if len(kinds) > MAX_KINDS:
        rest = sum(len(ids) for _, ids, _ in kinds[MAX_KINDS:])
        out.append(f"<p class=muted>The {MAX_KINDS} kinds said by most runs of {len(kinds)}; "
                   f"the other {len(kinds) - MAX_KINDS} are said {rest} times in all (the "
                   "study's Parquet has every message).</p>")
    return "".join(out)


#: Sampled runs listed with their error bars (the accuracy table has them all).
MAX_BAR_RUNS = 60


def _bar_text(column: str, value: Any, err: Any) -> str:
    """``t_max_dyn_kn 36.24 ± 0.0391 kN``: a figure of a run with its error bar."""
    unit = _unit(column)
    return f"{column} {eng(value, '', 4)} ± {eng(err, unit, 3)}"


def run_bars(acc: pd.DataFrame, run_id: Any) -> dict[str, float]:
    """The error bar of each figure of one sampled run (``{column: err}``), empty for a run
    outside the accuracy sample."""
    if acc is None or not len(acc) or "run_id" not in acc:
        return {}
    row = acc[acc["run_id"] == run_id]
    if not len(row):
        return {}
    row = row.iloc[0]
    return {c[:-4]: float(row[c]) for c in acc.columns
            if c.endswith("_err") and pd.notna(row[c])}


def accuracy_html(study: dict, runs: pd.DataFrame, acc: pd.DataFrame, cols: pd.DataFrame) -> str:
    """The error of each result column over the study's accuracy sample, then every sampled
    run (the first :data:`MAX_BAR_RUNS`) with each figure's value and error bar, its meshes
    and each figure's method (a ``growing`` or ``spread`` figure is not converging on these
    meshes: its bar is wide and has no converged value)."""
    asked = study.get("accuracy")
    if not asked:
        return ("<p class=muted>No error bars: the study has no <code>accuracy: {sample: "
                "...}</code> (beltstudy simulate checks a single run by default).</p>")
    if not len(cols):
        return "<p class=muted>No sampled run has finished yet.</p>"
    rows = [[f"<code>{_e(r['column'])}</code>", _e(r["unit"]), _n(r["runs"]),
             _n(r["value_median"]), _n(r["err_median"]), _n(r["err_max"]),
             _n(r["err_rel_max_pct"], 3)] for r in query.records_to_json(cols)]
    out = [f"<p>Error bars of {len(acc)} sampled runs (sample {_e(asked.get('sample'))}, "
           f"seed {_e(asked.get('seed', 0))}): each run repeated on a mesh half and one "
           "twice as fine, the step following the mesh; Richardson extrapolation where the "
           "observed order allows, else the spread (docs/dynamics.md, Error bars). The "
           "value at a finer mesh lies within value +- error. The accuracy table is "
           "<code>GET /studies/{id}/accuracy</code>.</p>",
           _table(["column", "unit", "runs", "value (median)", "error (median)",
                   "error (largest)", "largest error / value [%]"], rows, "runs")]
    axes = _axes(study, runs)
    by_id = runs.set_index("run_id") if len(runs) and "run_id" in runs else None
    sampled = acc
    if by_id is not None and axes:
        order = by_id.reindex(acc["run_id"])[axes].reset_index()
        sampled = acc.assign(**{f"_ax{k}": order[a].to_numpy() for k, a in enumerate(axes)})
        sampled = sampled.sort_values([f"_ax{k}" for k in range(len(axes))], kind="stable")
    prows = []
    for _, a in sampled.head(MAX_BAR_RUNS).iterrows():
        run = by_id.loc[a["run_id"]] if by_id is not None and a["run_id"] in by_id.index \
            else pd.Series(dtype=object)
        bars = run_bars(acc, a["run_id"])
        figures_ = "; ".join(_bar_text(c, run.get(c), e) for c, e in bars.items()
                             if pd.notna(run.get(c)))
        prows.append([f"<code class=id>{_e(a['run_id'])}</code>"]
                     + ["\x01ax\x01" + _e(_text(run.get(ax))) for ax in axes]
                     + [_e(a.get("accuracy_elements")),
                        _message_cell(figures_, 2 * MESSAGE_CHARS, print_full=True),
                        _message_cell(a.get("accuracy_methods"), 2 * MESSAGE_CHARS,
                                      print_full=True)])
    out.append("<h3>Each sampled run</h3>")
    out.append(_table(["run", *axes, "meshes [elements]", "figure ± error bar",
                       "method of each figure"], prows, "causes"))
    if len(acc) > MAX_BAR_RUNS:
        out.append(f"<p class=muted>The first {MAX_BAR_RUNS} of {len(acc)} sampled runs; the "
                   "accuracy table has them all.</p>")
    return "".join(out)


def _accuracy_section(study: dict, service: StudyService, study_id: str
                      ) -> tuple[str, pd.DataFrame]:
    """The error bars section and the study's accuracy table (empty without a sample)."""
    if not study.get("accuracy"):
        return accuracy_html(study, pd.DataFrame(), pd.DataFrame(), pd.DataFrame()), \
            pd.DataFrame()
    acc, cols = service.accuracy(study_id)
    return accuracy_html(study, service.store.read_runs(study_id), acc, cols), acc


def _figures(doc: dict, runs: pd.DataFrame, study: dict) -> tuple[str, str]:
    """The start and stop peaks (section 3) and the comparison figures (section 7)."""
    peaks = ""
    if study.get("dynamics"):
        allowed = _allowed_lines(study, runs)
        axes = [a["column"] for a in study.get("axes", [])]
        groups: dict[int, list[str]] = {}
        for a in study.get("axes", []):
            if a.get("group") is not None:
                groups.setdefault(a["group"], []).append(a["column"])
        def make():
            return charts.phase_peaks_figure(
                runs, f"{doc.get('name', '')}: peak and lowest tension of the start and the "
                "stop", axes=axes, groups=list(groups.values()), allowed_kn=allowed,
                never_going=never_going(runs))

        peaks = _figure(_png(make), "Peak and lowest belt tension of the start and of the "
                        "stop, a point per run (never joined): colour and marker name the run's "
                        "axis values, a red ring a run whose belt did not stop; dashed: the "
                        "tension the belt allows (rating over the transient safety factor) "
                        "and zero (slack).", "start and stop peaks")
    figs = []
    for plot, caption in (
        ("power-temperature", "Power at the drive pulleys against temperature: a line per "
                              "combination of the other axes."),
        ("ratio", "Candidate / baseline friction model ratio per axis value (bar: mean, "
                  "whisker: smallest to largest)."),
    ):
        if plot == "ratio" and ("friction_model" not in runs or
                                runs["friction_model"].nunique() < 2):
            continue
        if plot == "power-temperature" and _single_temperature(runs):
            # every run at one temperature: a column of points at one x tells nothing (the
            # start and stop peaks of section 3 are drawn against the study's axes)
            continue
        figs.append(_figure(_png(figures.figure_of(doc, runs, plot)), caption, plot))
    return peaks, "".join(figs)


def _allowed_lines(study: dict, runs: pd.DataFrame) -> list[tuple[float, str]]:
    """The tensions the belts of ``runs`` allow in a transient [kN], each with its label: the
    rating over the transient safety factor of each run's belt (:func:`_sf_of_runs`), one
    line per distinct value, named by its belts where the runs used more than one
    (a ``belt_type`` axis of ST1000 and EP800/4: 224 kN and 120 kN, not one line of the
    weaker rating over the steel factor)."""
    if "belt_rating_kn" not in runs:
        return []
    ok = runs[runs["status"] != "failed"] if "status" in runs else runs
    rating = pd.to_numeric(ok["belt_rating_kn"], errors="coerce")
    allowed = (rating / (TRANSIENT_SAFETY_RATIO * _sf_of_runs(study)(ok))).round(6)
    keep = allowed.notna()
    if not keep.any():
        return []
    belt = (ok["belt_type_used"].astype(str) if "belt_type_used" in ok
            else pd.Series("", index=ok.index))
    lines = []
    for value, part in allowed[keep].groupby(allowed[keep]):
        names = sorted(set(belt.loc[part.index]) - {"", "nan", "None"})
        lines.append((float(value), ", ".join(names)))
    if len(lines) == 1:
        return [(lines[0][0], "")]
    return lines


def _single_temperature(runs: pd.DataFrame) -> bool:
    """Whether every run of ``runs`` ran at one temperature (no ``temperature_c`` axis, or
    one value of it): power against temperature is then a column of points at one x."""
    if "temperature_c" not in runs:
        return True
    return pd.to_numeric(runs["temperature_c"], errors="coerce").dropna().nunique() < 2


def _on_design_belt(study: dict):
    """The study's conveyor, parsed; a ``belt.type: auto`` on the belt its (first) design
    chose (docs/belts.md): the belt an auto conveyor's runs ran on (raises when none chose
    one, or the conveyor cannot be read here)."""
    conv = parse_conveyor(study["conveyor"])
    if conv.belt.type == BELT_AUTO:
        chosen = [d["sizes"]["belt"]["type"] for d in study.get("designs") or []
                  if (d.get("sizes") or {}).get("belt")]
        if not chosen:
            raise ValueError("belt.type: auto and no design chose a belt")
        conv = with_belt(conv, chosen[0])
    return conv


def _fill(study: dict) -> dict | None:
    """The capacity check of the study's conveyor (ISO 5048 cross-section at design speed);
    a ``belt.type: auto`` on the belt its design chose (docs/belts.md), as its runs'
    ``fill_pct``; None for a conveyor this engine cannot read (the rest of the report still
    helps) or an auto belt no design chose."""
    try:
        cap = capacity(_on_design_belt(study))
    except Exception:
        return None
    return {"fill_pct": cap.fill_pct, "volume_flow_m3_h": cap.volume_flow_m3_h,
            "capacity_m3_h": cap.capacity_m3_h}


def report_html(doc: dict, runs: pd.DataFrame, status: dict, accuracy: str = "",
                bars: pd.DataFrame | None = None) -> str:
    """The design report of a stored study document ``doc`` (as the store keeps it: name,
    ``study``, engine version, times) and its ``runs`` table, as one HTML page. ``status``:
    ``state``, ``done``, ``total``; ``accuracy``: the error bars section's markup
    (:func:`accuracy_html`), ``bars``: the study's accuracy table (a governing run in it
    shows its error bar in the verdicts)."""
    study_id = doc.get("id", "")
    study = doc["study"]
    fill = _fill(study)
    name = doc.get("name", study_id)
    when = time.strftime("%Y-%m-%d %H:%M", time.gmtime(doc.get("finished_at")
                                                        or doc.get("updated_at") or time.time()))
    peaks, figs = _figures(doc, runs, study) if len(runs) else ("", "")
    counts = runs["status"].value_counts().to_dict() if len(runs) else {}
    state = (f"{status['state']}, {status['done']} of {status['total']} runs finished"
             + (f" ({', '.join(f'{v} {k}' for k, v in counts.items())})" if counts else ""))

    no_runs = "<p>No finished runs yet.</p>"
    sections = [
        ("Verdicts", "<p>The run that governs each design quantity, its value against the "
         "limit, and how many runs are past that limit.</p>"
         + (_verdicts_section(study, runs, bars) if len(runs) else no_runs)),
        ("Runs that did not pass", _causes_section(study, runs) if len(runs) else no_runs),
        ("Start and stop peaks", peaks or (
            "<p>No transient: the study ran the steady state only (dynamics: false).</p>"
            if not study.get("dynamics") else no_runs)),
        ("Conveyor", f"<p class=muted>from {_e(study.get('conveyor_source', 'inline'))}; "
         "conveyor axes of the grid change it per design (section 5).</p>"
         + _conveyor_section(study["conveyor"], fill)),
        ("Design basis", _design_section(study, runs)),
        ("The grid", _grid_section(study, status)),
        ("Comparison", figs or ("<p>No figures: no finished runs yet.</p>" if not len(runs)
                                else "<p>No comparison figure: the study runs one friction "
                                "model at one temperature (power against temperature and the "
                                "model ratio need two of either); section 3 draws the start "
                                "and stop peaks against its axes.</p>")),
        ("Runs", _runs_section(study, runs)),
        ("Error of each column", accuracy),
        ("Everything the runs say", _said_section(runs) if len(runs) else no_runs),
    ]
    if study.get("sample"):  # a sampled study (SPEC 7.2): what the samples say
        sections.append(("Uncertainty of the sampled inputs", uncertainty_section(
            study, runs, _table, _n, _png, _figure) if len(runs) else no_runs))
    parts = [
        "<!doctype html><html lang=en><head><meta charset=utf-8>",
        f'<meta http-equiv="Content-Security-Policy" content="{REPORT_CSP}">',
        f"<title>Design report · {_e(name)}</title><style>{CSS}</style></head><body>",
        f"<h1>Design report: {_e(name)}</h1>",
        f"<p class=muted>study <code>{_e(study_id)}</code> · {_e(state)} · engine "
        f"{_e(doc.get('engine_version'))} · {_e(when)} UTC · conveyor "
        f"{_e(study['conveyor'].get('name'))}</p>",
        f"<p>{_e(study.get('description', ''))}</p>" if study.get("description") else "",
    ]
    for k, (title, body) in enumerate(sections, start=1):
        cls = "" if k == 1 else ' class="section"'
        parts.append(f'<section id="s{k}"><h2{cls}>{k}. {_e(title)}</h2>{body}</section>')
    parts.append("</body></html>")
    return "".join(parts)


def build_report(service: StudyService, study_id: str) -> str:
    """The design report of a study as one self-contained HTML page."""

    doc = dict(service.store.read(study_id))
    doc.setdefault("id", study_id)
    section, acc = _accuracy_section(doc["study"], service, study_id)
    return report_html(doc, _in_grid_order(service, study_id), service.status(study_id),
                       section, bars=acc)


def _in_grid_order(service: StudyService, study_id: str) -> pd.DataFrame:
    """The study's stored runs in the order of its grid (the store keeps them in the order
    they finished): a verdict's governing run among runs tied on its value is then the same
    in every report of the same rows (the overland design study's named one of two tied
    coast stops, whichever had finished first). Run id order where the study cannot be
    expanded here (another engine version)."""
    runs = service.store.read_runs(study_id)
    if not len(runs):
        return runs
    try:
        order = {r.run_id: i for i, r in enumerate(service.resolved(study_id).runs)}
    except Exception:  # a study this engine cannot expand: still one order
        order = {}
    place = runs["run_id"].map(lambda r: order.get(r, len(order)))
    return (runs.assign(_place=place).sort_values(["_place", "run_id"], kind="stable")
            .drop(columns="_place").reset_index(drop=True))
