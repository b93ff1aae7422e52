"""``beltstudy sweep-temperature``: power against temperature per friction model (Harrison 2008,
Fig. 2).

Every model at every temperature is one run of a steady study (``friction_model`` x
``temperature_c``), run on the service's Dask executor like ``beltstudy run`` (every core, the
conveyor's auto sizes held as one installed design); the command writes a CSV
(one row per model and temperature: power, Te and its parts) and a PNG in the style of the
paper's figure: power against temperature for every model on the left, and on the right the
Non-Lin parts (idler rotation, indentation, belt and material flexure) against temperature,
like the figure's right window.
"""

from __future__ import annotations

import argparse
import math
import os
import tempfile
from pathlib import Path

import pandas as pd

from beltstudy.engine import (
    TEMPERATURE_MAX_C,
    TEMPERATURE_MIN_C,
    InputError,
    get_model,
    resolve_auto_belt,
    run_cases,
)
from beltstudy.service.cli.common import (
    ELEMENTS_HELP,
    auto_elements,
    check_scenario_fields,
    elements_option,
    model_option,
    outside_store,
    parse_load,
    parse_model_params,
    read_conveyor,
    writing,
)
from beltstudy.service.settings import load_settings
from beltstudy.service.store.columns import components_from_row

#: Colours of the models in the figure (the same model always gets the same colour).
COLOURS = {"cema": "tab:red", "din": "tab:blue", "cmod": "tab:orange", "visco": "tab:purple",
           "nonlin": "black"}
NONLIN_PARTS = ("idler_rotation", "indentation", "belt_flexure", "material_flexure")
MAX_POINTS = 1000


def register(sub) -> None:
    p = sub.add_parser(
        "sweep-temperature",
        help="power against temperature for several friction models (paper Fig. 2)",
        description="Steady power of CONVEYOR against ambient temperature for each friction "
                    "model; writes a CSV and a PNG (Harrison 2008, Fig. 2) into --out.",
    )
    p.add_argument("conveyor", help="conveyor file (YAML or JSON)")
    p.add_argument("--models", default="cema,din,nonlin,visco,cmod",
                   help="comma-separated friction models (default: all five, %(default)s)")
    p.add_argument("--from", dest="t_from", type=float, default=-40.0,
                   help="first temperature [C] (default -40)")
    p.add_argument("--to", dest="t_to", type=float, default=40.0,
                   help="last temperature [C] (default 40)")
    p.add_argument("--step", type=float, default=5.0, help="temperature step [K] (default 5)")
    p.add_argument("--param", action="append", metavar="MODEL.NAME=VALUE",
                   help="model parameter, repeatable (e.g. din.f_carry=0.010)")
    p.add_argument("--load", default="full", help="full, empty, inclines, declines, a "
                   "fraction up to 1.3 or one fraction per carry section (1,0,0.5) (default: "
                   "%(default)s)")
    p.add_argument("--elements", type=elements_option, default=None, help=ELEMENTS_HELP)
    p.add_argument("-o", "--out", "--output", dest="out", required=True, metavar="DIR",
                   help="output directory (made when missing)")
    p.set_defaults(func=run)


def temperatures(t_from: float, t_to: float, step: float) -> list[float]:
    """The swept temperatures [C], ``t_from`` to ``t_to`` inclusive."""

    for name, val in (("--from", t_from), ("--to", t_to), ("--step", step)):
        if not math.isfinite(val):
            raise InputError(f"{name}: expected a finite number, got {val}")
    if step <= 0:
        raise InputError(f"--step: must be > 0 (got {step:g})")
    if t_to < t_from:
        raise InputError(f"--to ({t_to:g}) must not be below --from ({t_from:g})")
    for name, val in (("--from", t_from), ("--to", t_to)):
        if not TEMPERATURE_MIN_C <= val <= TEMPERATURE_MAX_C:
            raise InputError(f"{name}: temperatures run from {TEMPERATURE_MIN_C:g} to "
                             f"{TEMPERATURE_MAX_C:g} C, as in every scenario (got {val:g})")
    count = int(math.floor((t_to - t_from) / step + 1e-9)) + 1
    if count > MAX_POINTS:
        raise InputError(f"--step: {count} temperatures is too many (at most {MAX_POINTS})")
    last = round(t_from + (count - 1) * step, 9)
    if abs(last - t_to) > 1e-6 * max(1.0, abs(step)):
        # as a study's range: the end asked for is reached, or said
        raise InputError(f"--to {t_to:g} is not reached from --from {t_from:g} in steps of "
                         f"{step:g}: give --to {last:g} or {last + step:g}, or another step")
    return [round(t_from + i * step, 9) for i in range(count)]


def _model_list(text: str) -> list:
    names = [s.strip() for s in text.split(",")]
    if not any(names):
        raise InputError("--models: give at least one model, e.g. --models din,nonlin")
    if not all(names):
        raise InputError(f"--models: an empty name in '{text}'; give the models comma-separated, "
                         "e.g. --models din,nonlin")
    out, seen = [], set()
    for name in names:
        fm = model_option(name, "--models")
        if fm.name not in seen:
            seen.add(fm.name)
            out.append(fm)
    return out


def sweep_study(conv, models, temps, params: dict, load, n_elements=None) -> dict:
    """The sweep as a steady study: a ``friction_model`` x ``temperature_c`` grid over the
    conveyor (inline), with the models' parameters."""
    scenario: dict = {"load": load}
    if n_elements is not None:
        scenario["elements"] = n_elements
    return {
        "name": "sweep-temperature",
        "conveyor": conv.model_dump(mode="json", by_alias=True),
        "scenario": scenario,
        "grid": {"friction_model": [fm.name for fm in models], "temperature_c": list(temps)},
        "models": {name: dict(values) for name, values in params.items()},
        "dynamics": False,
    }


def sweep(conv, models, temps, params: dict, load, n_elements=None):
    """Solve every (model, temperature) as one study on the service's Dask executor (every
    core, or ``BELTSTUDY_SCHEDULER``; the store in a temporary directory); return the long
    table as a DataFrame, models in the given order, temperatures ascending.

    As in every study, the conveyor's ``auto`` sizes (take-up, motors, brakes) are one
    installed design, the largest requirement over the swept models and temperatures."""
    # deferred: the service's Dask stack loads only for this command
    from beltstudy.service.studies import StudyService

    body = sweep_study(conv, models, temps, params, load, n_elements)
    with tempfile.TemporaryDirectory(prefix="beltstudy-sweep-") as tmp:
        settings = load_settings().model_copy(update={"data_dir": Path(tmp), "warm_start": False})
        service = StudyService(settings)
        try:
            st, _ = service.submit(body, confine=False)
            st = service.wait(st["id"], poll_s=0.1)
            runs = service.runs(st["id"])
        finally:
            service.close()
    if st["state"] != "done" or len(runs) != len(models) * len(temps):
        raise RuntimeError(f"the sweep study ended {st['state']}: {st.get('message') or ''}")
    by_case = {(r["friction_model"], float(r["temperature_c"])): r
               for r in runs.to_dict(orient="records")}
    rows = []
    for fm in models:
        for t in temps:
            r = by_case[(fm.name, float(t))]
            iterations = r["steady_iterations"]
            row = {"model": fm.name, "temperature_c": t, "power_kw": r["power_kw"],
                   "te_kn": r["te_kn"], "t_max_kn": r["t_max_kn"], "t_min_kn": r["t_min_kn"],
                   "sag_max_pct": r["sag_max_pct"],
                   "iterations": None if pd.isna(iterations) else int(iterations),
                   "status": r["status"], "message": r["message"]}
            for part, val in components_from_row(r).items():
                row[f"te_{part}_kn"] = val
            rows.append(row)
    return pd.DataFrame(rows)


def figure(df, title: str):
    """Power against temperature per model, and the Non-Lin parts (paper Fig. 2)."""
    # deferred: matplotlib loads only when a figure is drawn
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    has_nonlin = (df["model"] == "nonlin").any()
    ncols = 2 if has_nonlin else 1
    fig, axes = plt.subplots(1, ncols, figsize=(6.5 * ncols, 4.8), squeeze=False)
    ax = axes[0, 0]
    for model, grp in df.groupby("model", sort=False):
        ax.plot(grp["temperature_c"], grp["power_kw"], marker="o", ms=3,
                color=COLOURS.get(model), lw=2.2 if model == "nonlin" else 1.5,
                label=model)
    ax.set_xlabel("ambient temperature [C]")
    ax.set_ylabel("power at the drive pulleys [kW]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best")
    if has_nonlin:
        ax2 = axes[0, 1]
        nl = df[df["model"] == "nonlin"]
        for part, style in zip(NONLIN_PARTS, ("-", "--", "-.", ":"), strict=True):
            col = f"te_{part}_kn"
            if col in nl:
                ax2.plot(nl["temperature_c"], nl[col].fillna(0.0), style, lw=1.8,
                         label=part.replace("_", " "))
        din = df[df["model"] == "din"]
        if len(din) and "te_main_carry_kn" in din:
            main = (din["te_main_carry_kn"] + din["te_main_return_kn"]).to_numpy()
            ax2.plot(din["temperature_c"], main, color=COLOURS["din"], lw=1.0,
                     label="din main (carry + return)")
        ax2.set_xlabel("ambient temperature [C]")
        ax2.set_ylabel("Non-Lin running resistance parts [kN]")
        ax2.set_title("Non-Lin parts of Te")
        ax2.set_ylim(bottom=0.0)
        ax2.grid(alpha=0.3)
        ax2.legend(loc="best")
    fig.tight_layout()
    return fig


def run(args: argparse.Namespace) -> int:
    args.elements = auto_elements(args.elements)
    conv = read_conveyor(args.conveyor)
    models = _model_list(args.models)
    temps = temperatures(args.t_from, args.t_to, args.step)
    load = parse_load(args.load)
    check_scenario_fields(load=load, elements=args.elements)
    raw = parse_model_params(args.param)

    params: dict[str, dict] = {}
    names = {fm.name for fm in models}
    for model, values in raw.items():
        fm = get_model(model)
        if fm.name not in names:
            raise InputError(f"--param {model}.*: model '{fm.name}' is not in --models "
                             f"({', '.join(sorted(names))})")
        fm.params(values)  # validate now: unknown names fail before any solving
        params[fm.name] = values
    out = Path(args.out)
    outside_store(out, "--out", "files")  # before the folder is made: none in the store
    if out.exists() and not out.is_dir():
        raise InputError(f"--out {out}: exists and is not a directory")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {out}: cannot make the folder: {exc.strerror or exc}") from None
    if not os.access(out, os.W_OK):
        raise InputError(f"--out {out}: no permission to write in this folder")

    # belt.type: auto: one belt for the whole sweep, the lightest passing at every case
    conv, choice = resolve_auto_belt(conv, [
        c for fm in models for t in temps
        for c in run_cases(conv, fm.name, params.get(fm.name), t, load, args.elements)])
    if choice is not None:
        print(choice.note() or "warning: " + choice.warning())
    df = sweep(conv, models, temps, params, load, args.elements)
    load_tag = (load if isinstance(load, str) else
                "load" + "-".join(f"{x:g}" for x in (load if isinstance(load, list) else [load])))
    stem = f"{_safe(conv.name)}-{load_tag}"
    csv_path = out / f"{stem}.csv"
    png_path = out / f"{stem}.png"
    with writing(csv_path):
        df.to_csv(csv_path, index=False)
    title = f"{conv.name}, load {load}"
    fig = figure(df, title)
    with writing(png_path):
        fig.savefig(png_path, dpi=110)
    print(_table(df))
    print(f"\nwrote {csv_path} and {png_path}")
    failed = df[df["status"] == "failed"]
    if len(failed):
        print(f"{len(failed)} runs failed: {failed.iloc[0]['message']}")
        return 1
    return 0


def _safe(name: str) -> str:
    return "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in name) or "conveyor"


def _table(df) -> str:
    wide = df.pivot(index="temperature_c", columns="model", values="power_kw")
    wide = wide[list(dict.fromkeys(df["model"]))]
    lines = ["power [kW] against temperature [C]", "",
             "  T [C] " + "".join(f"{m:>11}" for m in wide.columns)]
    for t, row in wide.iterrows():
        lines.append(f"{t:7.1f} " + "".join(f"{v:11.1f}" for v in row))
    return "\n".join(lines)
