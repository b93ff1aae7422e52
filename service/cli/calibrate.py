"""``beltstudy calibrate``: fit a friction model's parameters to measured steady power."""

from __future__ import annotations

import argparse
import csv
import difflib
import io
import re
from pathlib import Path

import yaml
from pydantic import ValidationError

from beltstudy.engine import InputError, format_validation_error
from beltstudy.engine.calibration import time_column_hint
from beltstudy.engine.conveyor import unit_twin
from beltstudy.engine.textfile import read_text
from beltstudy.engine.wording import gnum
from beltstudy.service.calibration import (
    MAX_ROWS,
    ROWS_FIX,
    CalibrationIn,
    MeasuredRow,
    run_calibration,
    too_many_rows,
    with_row_fixes,
)
from beltstudy.service.cli.common import dumps, model_option, parse_params
from beltstudy.service.door.messages import with_type_fixes
from beltstudy.service.errors import Invalid


def register(sub) -> None:
    p = sub.add_parser(
        "calibrate",
        help="fit friction model parameters to measured steady power or force (SPEC 7.3)",
        description="Fit the named parameters of MODEL to the measured steady states of "
        "CONVEYOR by least squares; standard errors, residuals, the names the data cannot "
        "identify and a models: block for a study (docs/uncertainty.md).",
    )
    p.add_argument("conveyor", help="conveyor file (YAML or JSON)")
    p.add_argument("--measured", required=True, metavar="FILE.csv",
                   help="one row per measurement: load, temperature_c, power_kw or te_kn "
                   "(optional speed_m_s, t_tight_kn)")
    p.add_argument("--model", required=True, help="friction model: din, cema, nonlin, ...")
    p.add_argument("--fit", action="append", required=True, metavar="NAME[=START]",
                   help="a parameter to fit, repeatable (e.g. f_carry, or mu_b=0.002 to start "
                   "there)")
    p.add_argument("--param", action="append", metavar="NAME=VALUE",
                   help="another parameter held at a value, repeatable")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


#: Largest measurement file read [bytes]: 200 rows of a few numbers are a few kilobytes.
MEASURED_MAX_BYTES = 1_000_000
#: Blank lines read beyond MAX_ROWS before the rows are counted.
_BLANK_ALLOWANCE = 1000


def read_measured(path: str, lines: list[int] | None = None) -> list[dict]:
    """The rows of a measurement CSV (cells as text; empty cells are missing).

    Read as UTF-8 (a byte order mark, as Excel's "CSV UTF-8" writes, is dropped) or UTF-16
    with its byte order mark. The header is checked once: comma-separated, every column
    once, every column one of :class:`MeasuredRow`'s fields (the nearest named otherwise).
    ``lines``: filled with each row's line in the file (blank lines are skipped)."""
    p = Path(path)
    if not p.is_file():
        try:
            read_text(p, path)  # says why: a folder, not a regular file, not found
        except InputError as exc:
            raise InputError(str(exc), field="--measured") from None
    size = p.stat().st_size
    if size > MEASURED_MAX_BYTES:
        raise InputError(
            f"{path}: {gnum(size / 1e6, 3)} MB; a calibration reads at most {MAX_ROWS} rows, "
            f"far less than {MEASURED_MAX_BYTES / 1e6:g} MB: give the steady states to fit "
            "(one row each)")
    text = read_text(p, path)
    reader = csv.reader(io.StringIO(text, newline=""))
    records = []
    cut = False  # whether the file holds more records than were read
    try:
        for record in reader:
            records.append(record)
            if len(records) > MAX_ROWS + 1 + _BLANK_ALLOWANCE:
                cut = True
                break  # more rows than a calibration takes: said below by the row count
    except csv.Error as exc:
        raise InputError(f"{path}: line {reader.line_num}: not a CSV row ({exc}); give one "
                         "number per cell, comma-separated") from None
    if not any(any(cell.strip() for cell in r) for r in records):
        raise InputError(f"{path}: empty: give a header line (load,temperature_c,power_kw) and "
                         "one row per measured steady state below it")
    header = [name.strip() for name in records[0]]
    # one column holding the names: another separator. A spreadsheet's copy and paste gives
    # tabs ('load<TAB>temperature_c<TAB>power_kw' was told "unknown column ...; did you mean
    # 'temperature_c'?", a rename that cannot help); a European CSV export gives ';'
    sep = next((said for s, said in ((";", "';'"), ("\t", "tabs"))
                if len(header) == 1 and s in records[0][0]), None)
    if sep is not None:
        raise InputError(
            f"{path}: line 1: the columns are separated by {sep}; "
            "the file must be comma-separated with a decimal point (e.g. "
            "'load,temperature_c,power_kw' then '0.5,12,417.5'): export it as CSV with ',' "
            "between columns")
    valid = list(MeasuredRow.model_fields)
    if not any(name in valid or difflib.get_close_matches(name, valid, n=1, cutoff=0.5)
               for name in header):
        # no column of a measured-data file at all: not that file (a conveyor's YAML given
        # to --measured was refused column by column, from its comment line)
        what = (" (it looks like a YAML or JSON file)"
                if Path(str(path)).suffix.lower() in (".yaml", ".yml", ".json") else "")
        raise InputError(
            f"{path}: line 1 names none of the measured-data columns ({', '.join(valid)}): "
            f"--measured takes a CSV file{what} whose first line names them, e.g. "
            "'load,temperature_c,power_kw', and one row per measured steady state below it")
    problems = [f"{path}: line 1: {p}" for p in _header_problems(header, valid)]
    if not problems:  # the columns every row needs, said once for the header
        problems += [f"{path}: line 1: no column '{name}'; every row needs its {what}"
                     for name, what in (("load", "load case (full, empty or a fraction of the "
                                         "design load)"), ("temperature_c", "ambient "
                                         "temperature [C]")) if name not in header]
        if "power_kw" not in header and "te_kn" not in header:
            problems.append(f"{path}: line 1: no column 'power_kw' or 'te_kn'; give the "
                            "measured power at the drive pulleys [kW] or the peripheral force "
                            "[kN] (or both)")
    if problems:
        raise InputError("; ".join(problems))
    rows = []
    data = [r for r in records[1:] if any(cell.strip() for cell in r)]
    if not data:  # POST /calibrations' words (NO_ROWS), with where the rows would be
        raise InputError(f"{path}: no measured rows below the header (line 1); {ROWS_FIX}")
    if len(data) > MAX_ROWS:
        raise InputError(f"{path}: {too_many_rows(None if cut else len(data))}")
    for line, record in enumerate(records[1:], start=2):
        if not any(cell.strip() for cell in record):
            continue  # a blank line
        if any(cell.strip() for cell in record[len(header):]):
            raise InputError(f"{path}: line {line}: {len(record)} cells, but the header names "
                             f"{len(header)} columns; give one cell per column"
                             f"{_decimal_comma_hint(record)}")
        row = {name: cell for name, cell in zip(header, record, strict=False)
               if cell.strip() != ""}
        _refuse_decimal_commas(row, f"{path}: line {line}")
        rows.append(row)
        if lines is not None:
            lines.append(line)
    return rows


def _header_problems(header: list[str], valid: list[str]) -> list[str]:
    """What is wrong with each column name of a measurement CSV's header (``valid``: the
    columns it takes): given twice, a time or date column (calibration takes steady states, not
    a time series), an empty last column (a trailing ',' as Excel writes it), an unknown name
    (its unit twin or the nearest valid one)."""
    problems = []
    for i, name in enumerate(header):
        if name in header[:i] and name:
            problems.append(f"column '{name}' given twice (columns {header.index(name) + 1} "
                            f"and {i + 1}); give each column once")
        elif not name and not any(header[i:]):
            k = len(header) - i
            problems.append(f"the last {'column has' if k == 1 else f'{k} columns have'} no "
                            "name (a trailing ',' on each line, as a spreadsheet writes an "
                            f"empty last column): remove the empty last column{'s' * (k > 1)}")
            break
        elif not name:
            problems.append(f"column {i + 1} has no name; name it ({', '.join(valid)}) or "
                            "remove it")
        elif name not in valid:
            timed = time_column_hint(name)
            close = difflib.get_close_matches(name, valid, n=1, cutoff=0.5)
            hint = (timed or unit_twin(name, valid) or (
                f"did you mean '{close[0]}'?" if close else f"valid columns: {', '.join(valid)}"))
            problems.append(f"unknown column '{name}'; {hint}")
    return problems


#: A cell written with a decimal comma: digits, one comma, digits (``620,3``).
_DECIMAL_COMMA = re.compile(r"[+-]?\d+,\d+")


def _decimal_comma_hint(record: list[str]) -> str:
    """A hint for a row with more cells than the header where every cell is a number: the
    numbers are likely written with a decimal comma (``0,5,10,620``: 0,5 split in two)."""
    if all(re.fullmatch(r"\s*[+-]?\d+\s*", c) or not c.strip() for c in record):
        return ("; a decimal comma splits a number in two ('0,5' for 0.5 reads as the cells "
                "0 and 5): write the numbers with a decimal point, e.g. "
                "'load,temperature_c,power_kw' then '0.5,12,417.5' (export the CSV with '.' as "
                "the decimal separator)")
    return ""


def _refuse_decimal_commas(row: dict[str, str], where: str) -> None:
    """A quoted number with a decimal comma (``"620,3"``) is refused naming its column and
    the number with a decimal point; ``load`` is left alone (``"0.5,1"`` is one fraction per
    carry section, and a two-section ``"1,0"`` is a load)."""
    for name, cell in row.items():
        if name != "load" and _DECIMAL_COMMA.fullmatch(cell.strip()):
            raise InputError(
                f"{where}: {name} '{cell.strip()}' is written with a decimal comma; write "
                f"{cell.strip().replace(',', '.')} (the file must be comma-separated with a "
                "decimal point: export it as CSV with '.' as the decimal separator)")


def _at_line(message: str, path: str, lines: list[int]) -> str:
    """A message about ``measured.K...`` (or ``PATH: measured.K...``) with the file and the
    row's line in it: ``PATH: line N: measured.K...``."""
    text = message.removeprefix(f"{path}: ")
    m = re.match(r"measured\.(\d+)\b", text)
    if m and int(m.group(1)) < len(lines):
        return f"{path}: line {lines[int(m.group(1))]}: {text}"
    return message if message.startswith(f"{path}: ") else f"{path}: {text}"


def _by_source(message: str, path: str, lines: list[int]) -> str:
    """Each problem of a message named where it was written: a ``measured.K...`` one with the
    file and the row's line (:func:`_at_line`), a ``params.NAME`` one as the command line's
    ``--param NAME``, the others (``fit``, ``model``: the command line's too) as they are."""
    out = []
    for part in re.split(r"; (?=[A-Za-z_][\w.\[\]]*: )", message):
        if part.startswith("measured"):
            out.append(_at_line(part, path, lines))
        elif part.startswith("params."):
            out.append("--param " + part.removeprefix("params."))
        else:
            out.append(part)
    return "; ".join(out)


def run(args: argparse.Namespace) -> int:
    lines: list[int] = []
    data = {"conveyor": str(Path(args.conveyor).resolve()),
            "measured": read_measured(args.measured, lines), "model": model_option(args.model).name,
            "fit": args.fit, "params": parse_params(args.param, args.model)}
    try:
        body = CalibrationIn.model_validate(data)
    except ValidationError as exc:
        # each problem with the fix POST /calibrations gives ("580 kW": the number alone; a
        # missing temperature: what to give)
        message = with_type_fixes(format_validation_error(exc, CalibrationIn), data,
                                  CalibrationIn)
        raise InputError(_by_source(with_row_fixes(message), args.measured, lines)) from None
    try:
        out = run_calibration(body, params_field="--param ")
    except Invalid as exc:
        if "measured" not in exc.message.split(":")[0]:
            raise
        raise Invalid(_at_line(exc.message, args.measured, lines)) from None
    out = _rows_with_lines(out, lines)
    if args.json:
        print(dumps(out))
    else:
        print(format_calibration(out))
    return 0 if out["status"] == "ok" else 1


def _rows_with_lines(out: dict, lines: list[int]) -> dict:
    """The fit's words and residuals with each row's line in the file beside its number (the
    fit counts the rows from 0, as ``measured.K``; the file's errors and an editor count its
    lines from 1 with the header on line 1, so row 3 is line 5): ``row 3 (line 5: load 0.8,
    -10 C)``, ``rows 2 and 5 (lines 4 and 7) read ...``; each residual gets its ``line``."""

    def line(k: str) -> str:
        return str(lines[int(k)]) if int(k) < len(lines) else "?"

    def words(text: str) -> str:
        text = re.sub(r"\brows (\d+) and (\d+) read\b",
                      lambda m: f"rows {m[1]} and {m[2]} (lines {line(m[1])} and "
                                f"{line(m[2])}) read", text)
        return re.sub(r"\brow (\d+) \(", lambda m: f"row {m[1]} (line {line(m[1])}: ", text)

    out = dict(out)
    out["message"] = words(out["message"])
    out["notes"] = [words(n) for n in out["notes"]]
    out["residuals"] = [{**r, "line": int(line(str(r["row"])))}
                        if str(r["row"]).isdigit() and int(r["row"]) < len(lines) else r
                        for r in out["residuals"]]
    return out


def format_calibration(out: dict) -> str:
    """The fit as text: parameters, residuals, what is not identified, the models block."""
    lines = [f"calibration of {out['model']} on {out['conveyor']}: {out['status']} "
             f"(rms relative residual {100 * out['rms_relative']:.2f} %, {out['dof']} degrees "
             "of freedom)", f"  {out['message']}", "",
             "  parameter                 value          se      start   95 % interval"]
    for name, f in out["fit"].items():
        se = f"{gnum(f['se'])}" if f["se"] is not None else "-"
        ci = f.get("ci95")
        ci = f"{gnum(ci[0])} to {gnum(ci[1])}" if ci else "-"
        lines.append(f"  {name:<22} {f['value']:>10.6g} {se:>11} {f['start']:>10.4g}   {ci}")
    lines += ["", "  row  line  measured      value      model   residual [%]"]
    for r in out["residuals"]:
        lines.append(f"  {r['row']:>3}  {r.get('line', ''):>4}  {r['measured']:<10} "
                     f"{r['value']:>9.4g} {r['model']:>10.4g} {100 * r['relative']:>+10.2f}")
    if out["not_identifiable"]:
        lines += ["", "not identifiable: " + ", ".join(out["not_identifiable"])]
    lines += [f"note: {n}" for n in out["notes"]]
    # a fit that warns (readings in MW, a parameter at its bound, not identified) is not a
    # block to paste as it is: a 5.2e-17 f_carry from readings in MW was offered as one
    head = ("models block for a study:" if out["status"] == "ok" else
            f"models block for a study (the fit's status is {out['status']}: read the message "
            "and notes above before you use it):")
    block = yaml.safe_dump({"models": out["models"]}, sort_keys=False).rstrip()
    if out["status"] != "ok":
        block = "\n".join("# " + ln for ln in block.splitlines())
    lines += ["", head, block]
    return "\n".join(lines)
