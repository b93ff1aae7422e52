"""``beltstudy calibrate``: fit a friction model's parameters to measured steady power."""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import yaml
from pydantic import ValidationError

from beltstudy.engine import InputError, format_validation_error, get_model
from beltstudy.service.calibration import CalibrationIn, run_calibration
from beltstudy.service.cli.common import dumps, parse_params


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


def read_measured(path: str) -> list[dict]:
    """The rows of a measurement CSV (cells as text; empty cells are missing)."""
    p = Path(path)
    if not p.is_file():
        raise InputError(f"{path}: file not found", field="--measured")
    with p.open(newline="", encoding="utf-8") as fh:
        rows = [{k.strip(): v for k, v in row.items() if k is not None and v not in (None, "")}
                for row in csv.DictReader(fh)]
    return rows


def run(args: argparse.Namespace) -> int:
    data = {"conveyor": str(Path(args.conveyor).resolve()),
            "measured": read_measured(args.measured), "model": get_model(args.model).name,
            "fit": args.fit, "params": parse_params(args.param, args.model)}
    try:
        body = CalibrationIn.model_validate(data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, CalibrationIn, prefix=f"{args.measured}: ")) from None
    out = run_calibration(body)
    if args.json:
        print(dumps(out))
    else:
        print(format_calibration(out))
    return 0 if out["status"] == "ok" else 1


def format_calibration(out: dict) -> str:
    """The fit as text: parameters, residuals, what is not identified, the models block."""
    lines = [f"calibration of {out['model']} on {out['conveyor']}: {out['status']} "
             f"(rms relative residual {100 * out['rms_relative']:.2f} %, {out['dof']} degrees "
             "of freedom)", "", "  parameter                 value          se      start"]
    for name, f in out["fit"].items():
        se = f"{f['se']:.4g}" if f["se"] is not None else "-"
        lines.append(f"  {name:<22} {f['value']:>10.6g} {se:>11} {f['start']:>10.4g}")
    lines += ["", "  row  measured      value      model   residual [%]"]
    for r in out["residuals"]:
        lines.append(f"  {r['row']:>3}  {r['measured']:<10} {r['value']:>9.4g} "
                     f"{r['model']:>10.4g} {100 * r['relative']:>+10.2f}")
    if out["not_identifiable"]:
        lines += ["", "not identifiable: " + ", ".join(out["not_identifiable"])]
    lines += [f"note: {n}" for n in out["notes"]]
    lines += ["", "models block for a study:",
              yaml.safe_dump({"models": out["models"]}, sort_keys=False).rstrip()]
    return "\n".join(lines)
