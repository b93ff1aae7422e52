"""``beltstudy simulate``: the transient start-run-stop cycle of one conveyor (Euler-X).

Scenario fields given on the command line override the scenario file; everything is
validated as a SPEC section 2 scenario, so mistakes name the field and exit with status 2.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
import pandas as pd

from beltstudy.engine import InputError, Scenario, parse_scenario
from beltstudy.engine import results as R
from beltstudy.engine.conveyor import scenario_fields
from beltstudy.service.charts import transient_figure
from beltstudy.service.cli.common import (
    ELEMENTS_HELP,
    LOAD_HELP,
    check_output,
    design_lines,
    drives_given,
    dumps,
    elements_option,
    model_option,
    parse_load,
    parse_params,
    read_conveyor,
    step_option,
    with_sag_at_rest,
    write_table,
    writing,
)
from beltstudy.service.door.messages import with_type_fixes
from beltstudy.service.door.parse import expect_kind
from beltstudy.service.door.parse import load_mapping as door_load_mapping

#: Steady fields of the table (labels and units: :mod:`beltstudy.engine.results`, the two tensions
#: marked steady); the transient, per phase, slack and per-drive blocks show every field of
#: their groups. ``--json`` prints every field.
STEADY_TABLE = ("te_kn", "power_kw", "t1_kn", "t2_kn", "t_max_kn", "t_min_kn")
STEADY_LABELS = {"t_max_kn": "maximum tension (steady)", "t_min_kn": "minimum tension (steady)"}
#: per drive i: the steady then the transient per-drive fields
DRIVE_FIELDS = (R.STEADY_DRIVE.fields + R.TRANSIENT_DRIVE.fields + R.DRIVE_POWER.fields
                + R.DRIVE_LOAD.fields)


def _rows(fields) -> list[tuple[str, str, str]]:
    return [(f.name, f.label, f.unit) for f in fields]


STEADY_FIELDS = [(k, STEADY_LABELS.get(k, R.field(k).label), R.field(k).unit)
                 for k in STEADY_TABLE]
TRANSIENT_FIELDS = _rows(R.TRANSIENT)
PHASE_FIELDS = _rows(R.PHASE)
SLACK_FIELDS = _rows(R.SLACK)
CURVE_FIELDS = _rows(R.CURVES_TRANSIENT)

#: The scenario a command line without --scenario runs (SPEC section 2 defaults).
DEFAULT_SCENARIO = Scenario()


def _scenario_default(value) -> str:
    """The help's default of a scenario option: the scenario file's field, else ``value``."""
    return f"(default: the scenario file's, else {value})"


def register(sub) -> None:
    p = sub.add_parser(
        "simulate",
        help="transient start, run and stop of one conveyor (Euler-X)",
        description="Simulate the rest -> start -> run -> stop -> rest cycle of CONVEYOR "
                    "(seed paper section 3). Command-line scenario fields override the "
                    "scenario file.",
    )
    p.add_argument("conveyor", help="conveyor file (YAML or JSON)")
    p.add_argument("--model", default="din", help="friction model: din, cema, cmod, visco, "
                   "nonlin (default: %(default)s)")
    p.add_argument("--temperature-c", type=float, default=None,
                   help="ambient temperature [C] "
                   + _scenario_default(f"{DEFAULT_SCENARIO.temperature_c:g}"))
    p.add_argument("--scenario", metavar="SCENARIO.yaml", help="scenario file (SPEC section 2)")
    p.add_argument("--param", action="append", metavar="NAME=VALUE",
                   help="friction model parameter, repeatable (e.g. f_carry=0.010)")
    scn = DEFAULT_SCENARIO
    p.add_argument("--load", default=None,
                   help=f"{LOAD_HELP} {_scenario_default(scn.load)}")
    p.add_argument("--start-control", choices=["s-curve", "linear", "torque"], default=None,
                   help="the vfd drives' start: an s-curve or linear speed reference, or torque (the "
                   "force limit ramped up over the start time) "
                   + _scenario_default(scn.start.control))
    p.add_argument("--start-time-s", type=float, default=None,
                   help=f"start time [s] {_scenario_default(f'{scn.start.time_s:g}')}")
    p.add_argument("--run-s", type=float, default=None,
                   help=f"steady running time [s] {_scenario_default(f'{scn.run_s:g}')}")
    p.add_argument("--stop-mode", choices=["coast", "brake", "controlled"], default=None,
                   help="coast (power failure), brake (coast and the brakes) or controlled "
                   f"(the drives ease the belt down) {_scenario_default(scn.stop.mode)}")
    p.add_argument("--stop-time-s", type=float, default=None,
                   help="target stop time [s], read by the brake and controlled stops "
                   + _scenario_default(f"{scn.stop.time_s:g}"))
    p.add_argument("--formulation", choices=["relative", "support"], default=None,
                   help="relative (drive force from a speed controller) or support (drive "
                        f"pulley motion imposed) {_scenario_default(scn.formulation)}")
    p.add_argument("--elements", type=elements_option, default=None,
                   help=ELEMENTS_HELP.replace("(default:", "(default: the scenario file's, "
                                              "else"))
    p.add_argument("--dt-s", type=step_option, default=None, help="fixed time step [s] or auto "
                   "(default: the scenario file's, else automatic, half the stability limit)")
    p.add_argument("--record-dt-s", type=float, default=None, help="time-series spacing [s] "
                   + _scenario_default(f"{DEFAULT_SCENARIO.record_dt_s:g}"))
    p.add_argument("--no-sag-at-rest", dest="sag_at_rest", action="store_const",
                   const=False, default=None,
                   help="size an auto take-up for the sag limits running only (default: also "
                   "held at rest; the file's takeup.sag_at_rest)")
    p.add_argument("--no-remedy", action="store_true", help="when a drive slips in the start, "
                   "do not rerun the start to find the take-up and start time that avoid it "
                   "(nor the cycle for a slip in the stop or a transient sag past its limit)")
    p.add_argument("--no-check", dest="check", action="store_false",
                   help="skip the error bars (by default the run is repeated on a mesh half "
                   "and twice as fine, about 5 x the run's time, and each deciding figure "
                   "gets <figure>_err; a verdict within its error of the limit says "
                   "marginal)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--timeseries", metavar="FILE", help="write the SPEC section 5 key-point "
                   "time series (.parquet or .csv)")
    p.add_argument("--plot", metavar="FILE.png", help="tension at eight points round the loop "
                   "and where it is highest and lowest, against time, with the belt speed "
                   "below (the paper's Fig. 4)")
    p.set_defaults(func=run)


def build_scenario(args: argparse.Namespace):
    """The scenario file (if any) with the command-line fields on top, validated."""

    data: dict = {}
    if args.scenario:
        raw = door_load_mapping(args.scenario)
        expect_kind(raw, "scenario", str(args.scenario))
        data, _ = scenario_fields(raw, f"{args.scenario}: ")
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in data.items()}
    if any(k in data and not isinstance(data[k], dict) for k in ("start", "stop")):
        # 'start: null' or 'stop: [1]': refused naming the field, as POST /studies refuses it
        # (it was read as no start, or the command line's --start-time-s written into it)
        return _parse_scenario(data)
    start = data.setdefault("start", {})
    stop = data.setdefault("stop", {})
    over = {
        ("temperature_c",): args.temperature_c,
        ("start", "control"): args.start_control,
        ("start", "time_s"): args.start_time_s,
        ("run_s",): args.run_s,
        ("stop", "mode"): args.stop_mode,
        ("stop", "time_s"): args.stop_time_s,
        ("formulation",): args.formulation,
        ("elements",): args.elements,
        ("dt_s",): args.dt_s,
        ("record_dt_s",): args.record_dt_s,
    }
    flags = {}  # the scenario field -> the option that set it
    for path, value in over.items():
        if value is None:
            continue
        target = {"start": start, "stop": stop}.get(path[0], data) if len(path) == 2 else data
        target[path[-1]] = value
        flags["scenario." + ".".join(path)] = _option(path)
    if args.load is not None:
        data["load"] = parse_load(args.load)
        flags["scenario.load"] = "--load"
    if not start:
        data.pop("start")
    if not stop:
        data.pop("stop")
    try:
        return _parse_scenario(data)
    except InputError as exc:
        # a value the command line gave is named by its option, as `static` names it (the
        # scenario file's own fields keep their scenario path)
        text = str(exc)
        for field, option in flags.items():
            text = text.replace(f"{field}:", f"{option}:")
        raise InputError(text) from None


def _option(path: tuple) -> str:
    """The command-line option of a scenario field path: ``--start-time-s`` for
    ``("start", "time_s")``, ``--run-s`` for ``("run_s",)``, ``--stop-mode`` for
    ``("stop", "mode")``."""
    return "--" + "-".join(path).replace("_", "-")


def _parse_scenario(data: dict):
    """The scenario validated; a value of the wrong type with its fix (``temperature_c: 20
    C``: write the number alone, in C), as the study door says it."""
    try:
        return parse_scenario(data, prefix="scenario.")
    except InputError as exc:
        raise InputError(with_type_fixes(str(exc), data, Scenario, "scenario.")) from None


def traces_long(traces: pd.DataFrame) -> pd.DataFrame:
    """The probe traces (``t_s`` and ``T@<s>m`` columns) as a long table for the figure."""
    parts = []
    for col in traces.columns:
        if not col.startswith("T@"):
            continue
        s = float(col[2:-1])
        parts.append(pd.DataFrame({"t_s": traces["t_s"].to_numpy(), "s_m": s,
                                   "tension_kn": traces[col].to_numpy()}))
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(
        columns=["t_s", "s_m", "tension_kn"])


def run(args: argparse.Namespace) -> int:
    # deferred: the transient engine (numba) loads only for this command
    from beltstudy.engine.run import run_one

    conv = with_sag_at_rest(read_conveyor(args.conveyor), args.sag_at_rest)
    fm = model_option(args.model)
    params = fm.params(parse_params(args.param, fm.name))
    for option, path, exts in (("--timeseries", args.timeseries, (".csv", ".parquet")),
                               ("--plot", args.plot, (".png",))):
        if path and not path.endswith(exts):
            raise InputError(f"{path}: give a file ending in {' or '.join(exts)}")
        if path:
            check_output(path, option)
    scn = build_scenario(args)
    from beltstudy.engine.warmth import COMPILE_LINE, kernel_cold

    if kernel_cold():  # one line before the wait, on stderr (stdout stays the result)
        print(f"{COMPILE_LINE}: a minute or more on a busy machine", file=sys.stderr,
              flush=True)
    res = run_one(conv, scn, model=fm.name, params=params, dynamics=True,
                  remedy=not args.no_remedy, check=args.check,
                  say=lambda line: print(line, file=sys.stderr, flush=True))
    s = {"conveyor": conv.name, "friction_model": fm.name,
         "temperature_c": scn.temperature_c, "load": scn.load,
         "stop_mode": scn.stop.mode, "formulation": scn.formulation, **res.summary}
    if args.timeseries and res.timeseries is not None:
        write_table(res.timeseries, args.timeseries)
    if args.plot:
        surface = traces_long(res.transient.traces) if res.transient is not None else None
        extremes = {"highest tension": (s.get("t_max_dyn_at_m"), s.get("t_max_dyn_kn"),
                                        s.get("t_max_dyn_time_s")),
                    "lowest tension": (s.get("t_min_dyn_at_m"), s.get("t_min_dyn_kn"),
                                       s.get("t_min_dyn_time_s"))}
        locate = res.steady.loop.where if res.steady is not None else None
        fig = transient_figure(res.timeseries, surface, title=(
            f"{conv.name}: {fm.name}, {scn.temperature_c:g} C, load {scn.load}, "
            f"{start_words(conv, scn)}, {scn.stop.mode} stop"),
            extremes=extremes, locate=locate, extremes_surface=res.surface)
        with writing(args.plot):
            fig.savefig(args.plot, dpi=110)
    if args.json:
        print(dumps(s))
    else:
        print(_table(s, drives_given(conv)))
    return 0 if s["status"] != "failed" else 1


def start_words(conv, scn) -> str:
    """The start as the run made it, for the plot's title: ``s-curve start 60 s`` for vfd
    drives, which follow the scenario's start curve; ``dol start`` (with the coupling) when
    every drive is a motor on the line, which does not read ``start.time_s`` (docs/drives.md)
    and starts as its torque curve and coupling let it."""
    drives = list(conv.drives)
    if drives and all(d.control == "dol" for d in drives):
        couplings = sorted({d.coupling for d in drives} - {"none"})
        named = ", ".join(c.replace("_", " ") + " coupling" for c in couplings)
        return f"dol start ({named})" if named else "dol start"
    words = f"{scn.start.control} start {scn.start.time_s:g} s"
    if any(d.control == "dol" for d in drives):
        words += " (vfd drives; the dol drives on the line)"
    return words


def _fmt(val) -> str:
    """A table value in 12 characters: three decimals, or three significant figures below
    0.01, where three decimals keep one figure or none (a short belt's time step, 2.3e-4 s,
    read "0.000 s"; a halved step of 0.0005 s read "0.001 s", as the automatic 0.000809 s
    did). A count (an integer: the elements used) prints as one."""
    if isinstance(val, int | np.integer) and not isinstance(val, bool):
        return f"{int(val):>12d}"
    if isinstance(val, float | np.floating):
        x = float(val)
        if x != 0.0 and abs(x) < 0.01:
            return f"{x:>12.3g}"
        return f"{x:>12.3f}"
    return f"{val!s:>12}"


def _table(s: dict, given: list[bool] | None = None) -> str:
    lines = [f"{s['conveyor']}  model={s['friction_model']}  temperature={s['temperature_c']:g} C"
             f"  load={s['load']}  stop={s['stop_mode']}  formulation={s['formulation']}",
             f"belt {s.get('belt_type_used')}", ""]

    for title, fields in (("steady", STEADY_FIELDS), ("transient", TRANSIENT_FIELDS)):
        lines.append(f"  {title}")
        for key, label, unit in fields:
            if key in s and s[key] is not None:
                lines.append(f"    {label:<38} {_fmt(s[key])} {unit}")
        lines.append("")
        if title == "steady":
            lines += design_lines(s, drives_given=given)
            lines.append("")
    for title, fields in (("per phase (start: start command to stop command; stop: from "
                           "the stop command)", PHASE_FIELDS), ("slack", SLACK_FIELDS)):
        lines.append(f"  {title}")
        for key, label, unit in fields:
            if key in s and s[key] is not None:
                lines.append(f"    {label:<38} {_fmt(s[key])} {unit}")
        lines.append("")
    if s.get("liftoff_max_kn_over") is not None:  # a concave curve (docs/routes.md)
        lines.append("  lift-off at concave curves (negative: the margin left)")
        lines += [f"    {label:<38} {_fmt(s[key])} {unit}" for key, label, unit in CURVE_FIELDS
                  if s.get(key) is not None]
        lines.append("")
    lines += drive_lines(s)
    lines += error_lines(s)
    lines.append(f"  status: {s['status']}" + (f"  ({s['message']})" if s["message"] else ""))
    return "\n".join(lines)


def drive_lines(s: dict) -> list[str]:
    """The per-drive table (SPEC 6.4): steady tight and slack side and slip margin, transient
    largest force and power, smallest slip margin, time slipping and belt length slipped."""
    drives = []
    i = 1
    while f"drive{i}_t_tight_kn" in s:
        drives.append(i)
        i += 1
    if not drives:
        return []
    head = "    drive " + "".join(f"{f.label:>11}" for f in DRIVE_FIELDS)
    units = "          " + "".join(f"{'[' + f.unit + ']':>11}" for f in DRIVE_FIELDS)
    lines = ["  per drive (steady: tight, slack, margin; transient: the rest)", head, units]
    for i in drives:
        cells = []
        for f in DRIVE_FIELDS:
            val = s.get(f.name.format(i=i))
            cells.append(f"{val:>11.3f}" if isinstance(val, float | int) else f"{'-':>11}")
        lines.append(f"    {i:>5} " + "".join(cells))
    lines.append("")
    return lines


def error_lines(s: dict) -> list[str]:
    """The error bars (``<figure>_err``, ``<figure>_converged``) of a checked run: each figure,
    its bar and the converged estimate, then the meshes and the methods."""
    if "accuracy_elements" not in s:
        return []
    lines = [f"  error bars (meshes {s['accuracy_elements']} elements; the value at a finer "
             "mesh lies within +-)",
             f"    {'figure':<26} {'value':>12} {'+-':>10} {'converged':>12}"]
    for key in s:
        if not key.endswith("_err") or s[key] is None:
            continue
        name = key[:-4]
        conv = s.get(f"{name}_converged")
        unit = R.field(key).unit
        lines.append(f"    {name:<26} {s.get(name, float('nan')):>12.4g} {s[key]:>10.3g} "
                     f"{'-' if conv is None else format(conv, '.4g'):>12} {unit}")
    lines.append(f"    methods: {s['accuracy_methods']}")
    lines.append("")
    return lines
