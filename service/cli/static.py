"""``beltstudy static``: steady running tensions of one conveyor for one friction model."""

from __future__ import annotations

import argparse
import math
import re
import time

from beltstudy.engine import (
    BELT_AUTO,
    STARTUP_FACTOR,
    InputError,
    auto_sizes,
    check_summary,
    installed_at_full_load,
    resolve_auto_belt,
    results,
    run_cases,
    run_message,
    select_belt,
    solve_steady,
    summary_fields,
    with_belt,
)
from beltstudy.engine.drives import apart
from beltstudy.service.charts import steady_profile_figure
from beltstudy.service.cli.common import (
    ELEMENTS_HELP,
    LOAD_HELP,
    auto_elements,
    check_output,
    check_scenario_fields,
    design_lines,
    drives_given,
    dumps,
    elements_option,
    model_option,
    parse_load,
    parse_params,
    read_conveyor,
    with_sag_at_rest,
    write_table,
    writing,
)

#: The steady fields of the table, in order (labels and units: :mod:`beltstudy.engine.results`; every
#: field is in ``--json``).
TABLE = ("te_kn", "power_kw", "t1_kn", "t2_kn", "t_max_kn", "t_max_at_m", "t_min_kn",
         "t_min_at_m", "sag_max_pct", "slip_margin", "slip_margin_start", "safety_factor",
         "belt_mass_kg_m", "load_mass_kg_m", "wave_speed_carry_m_s", "wave_speed_return_m_s")


def register(sub) -> None:
    p = sub.add_parser(
        "static",
        help="steady running tensions, power, take-up and checks of one conveyor",
        description="Steady running tensions of CONVEYOR for one friction model.",
    )
    p.add_argument("conveyor", help="conveyor file (YAML or JSON)")
    p.add_argument("--model", default="din", help="friction model: din (iso5048), cema, cmod, visco, nonlin "
                   "(default: %(default)s)")
    p.add_argument("--temperature-c", type=float, default=20.0, help="ambient temperature [C] (default: %(default)g)")
    p.add_argument("--param", action="append", metavar="NAME=VALUE",
                   help="friction model parameter, repeatable (e.g. f_carry=0.010)")
    p.add_argument("--load", default="full", help=f"{LOAD_HELP} (default: %(default)s)")
    p.add_argument("--elements", type=elements_option, default=None, help=ELEMENTS_HELP)
    p.add_argument("--no-sag-at-rest", dest="sag_at_rest", action="store_const",
                   const=False, default=None,
                   help="size an auto take-up for the sag limits running only (default: also "
                   "held at rest, a conservative reading beyond DIN 22101's running checks; "
                   "the file's takeup.sag_at_rest)")
    p.add_argument("--suggest-belt", action="store_true",
                   help="try every catalogue belt of the belt's kind (lightest first) and "
                   "print the lightest that passes the running and start-up safety factors, "
                   "with the table of candidates (docs/belts.md); the results are of the "
                   "file's belt, or of the choice with belt.type: auto")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--profile", metavar="FILE", help="write the tension along the loop "
                   "(.csv or .parquet)")
    p.add_argument("--plot", metavar="FILE.png", help="draw the profile with the tensions")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    args.elements = auto_elements(args.elements)
    conv = with_sag_at_rest(read_conveyor(args.conveyor), args.sag_at_rest)
    auto = conv.belt.type == BELT_AUTO
    fm = model_option(args.model)
    params = fm.params(parse_params(args.param, fm.name))
    load = parse_load(args.load)
    scn = check_scenario_fields(conv, temperature_c=args.temperature_c, load=load,
                                elements=args.elements)
    for option, path, exts in (("--profile", args.profile, (".csv", ".parquet")),
                               ("--plot", args.plot, (".png",))):
        if path and not path.endswith(exts):
            raise InputError(f"{path}: give a file ending in {' or '.join(exts)}")
        if path:
            check_output(path, option)
    t0 = time.perf_counter()
    given = drives_given(conv)
    conv, choice = _belt(conv, fm.name, params, args, load)
    # auto motors and brakes installed for the full load too, as a run installs them
    conv, installed = installed_at_full_load(conv, scn, model=fm.name, params=params)
    res = solve_steady(conv, model=fm.name, params=params, temperature_c=args.temperature_c,
                       load=load, n_elements=args.elements, settle=True)
    s = dict(res.summary)
    s.update(summary_fields(auto_sizes(conv, scn, model=fm.name, params=params, steady=res)))
    s.update(installed)
    if choice is not None and auto:
        run_message(s, choice)
    s["elapsed_s"] = time.perf_counter() - t0
    check_summary(s)
    s = {"conveyor": conv.name, "friction_model": fm.name,
         "temperature_c": args.temperature_c, "load": load, **s}
    if args.suggest_belt:
        s["belt_selection"] = _selection(choice)
    if args.profile:
        write_table(res.profile(), args.profile)
    if args.plot:
        fig = steady_profile_figure(res.profile(), title=(
            f"{conv.name}: {fm.name}, {args.temperature_c:g} C, load {load}"))
        with writing(args.plot):
            fig.savefig(args.plot, dpi=110)
    if args.json:
        print(dumps(s))
    else:
        if args.suggest_belt:
            print(_selection_table(choice))
        print(_table(s, given))
    return 0 if res.status != "failed" else 1


def _belt(conv, model: str, params, args, load):
    """The conveyor on the belt the run uses and the selection (None when there was none):
    ``belt.type: auto`` picks at the run's case (and full load,
    :func:`beltstudy.engine.beltselect.run_cases`); ``--suggest-belt`` tries every candidate."""
    cases = run_cases(conv, model, params, args.temperature_c, load, args.elements)
    if args.suggest_belt:
        choice = select_belt(conv, cases, every=True)
        return (with_belt(conv, choice.belt_id) if conv.belt.type == BELT_AUTO else conv), choice
    return resolve_auto_belt(conv, cases)


def _selection(choice) -> dict:
    """The selection as JSON: minima, choice, next lighter and every candidate."""
    return {"kind": choice.kind, "safety_factor_min": choice.safety_factor_min,
            "safety_factor_start_min": choice.safety_factor_start_min,
            "chosen": choice.belt_id, "passed": choice.passed,
            "next_lighter": choice.lighter.id if choice.lighter else None,
            "note": choice.note() or choice.warning(), "candidates": choice.table()}


def _sf_decimals(choice) -> int:
    """The decimals that print every candidate's safety factors apart from their minima as the
    numbers compare (:func:`beltstudy.engine.drives.apart`): a candidate at 6.5487 against a
    minimum of 6.549 read '6.55 fail' under 'minimum safety factor 6.55'."""
    d = 2
    for r in choice.table():
        if r["failed"]:
            continue
        for v, lim in ((r["safety_factor"], choice.safety_factor_min),
                       (r["safety_factor_start"], choice.safety_factor_start_min)):
            if v is not None and lim is not None:
                d = max(d, len(apart(float(v), float(lim))[0].partition(".")[2]))
    return d


def _selection_table(choice) -> str:
    d = _sf_decimals(choice)
    lines = [f"belt selection: {choice.kind} belts of the catalogue, lightest first; minimum "
             f"safety factor {choice.safety_factor_min:.{d}f} running, "
             f"{choice.safety_factor_start_min:.{d}f} at start-up (start-up force "
             f"{STARTUP_FACTOR:g} x Te)", "",
             "  belt        mass [kg/m]  rating [kN]  T_max [kN]  T_max start [kN]  "
             "SF running  SF start-up",
             ]
    for r in choice.table():
        mark = "pass" if r["passes"] else "fail"
        if r["belt"] == choice.belt_id:
            mark += "  <- " + ("choice" if choice.passed else "heaviest (none passes)")
        if r["failed"]:
            lines.append(f"  {r['belt']:<10} {r['mass_kg_m']:>12.2f} {r['rating_kn']:>12.0f}  "
                         f"steady solve failed: {r['failed']}")
            continue
        lines.append(f"  {r['belt']:<10} {r['mass_kg_m']:>12.2f} {r['rating_kn']:>12.0f} "
                     f"{r['t_max_kn']:>11.1f} {r['t_max_start_kn']:>17.1f} "
                     f"{r['safety_factor']:>11.{d}f} {r['safety_factor_start']:>12.{d}f}  {mark}")
    lines += ["", "  " + (choice.note() or choice.warning()), ""]
    return "\n".join(lines)


def _unit(f) -> str:
    return "-" if f.unit == "text" else f.unit


def _table(s: dict, given: list[bool] | None = None) -> str:
    lines = [f"{s['conveyor']}  model={s['friction_model']}  temperature={s['temperature_c']:g} C"
             f"  load={s['load']}", f"belt {s.get('belt_type_used')}", ""]
    for key in TABLE:
        val = s.get(key)
        if val is None:
            continue
        f = results.field(key)
        lines.append(f"  {f.label:<36} {val:>12.3f} {_unit(f)}")
    lines.append("")
    lines += design_lines(s, drives_given=given)
    lines.append("")
    lines.append("  Te components [kN]")
    for name, val in s["te_components_kn"].items():
        lines.append(f"    {name:<34} {val:>12.3f}")
    lines.append("")
    drives = []
    while f"drive{len(drives) + 1}_t_tight_kn" in s:
        drives.append(len(drives) + 1)
    if drives:
        lines.append("  per drive pulley          tight [kN]   slack [kN]   slip margin [-]"
                     "   power needed [kW]   utilisation [-]")
        for i in drives:
            need, util = s.get(f"drive{i}_power_required_kw"), s.get(f"drive{i}_utilisation")
            lines.append(f"    drive {i:<16} {s[f'drive{i}_t_tight_kn']:>12.3f} "
                         f"{s[f'drive{i}_t_slack_kn']:>12.3f} {s[f'drive{i}_slip_margin']:>14.3f}"
                         f" {'-' if need is None else format(need, '.1f'):>19}"
                         f" {'-' if util is None else format(util, '.3f'):>17}")
        lines.append("")
    lines += _check_lines(s)
    lines += _curve_lines(s)
    lines += _hcurve_lines(s)
    lines.append(f"  status: {s['status']}" + (f"  ({s['message']})" if s["message"] else ""))
    return "\n".join(lines)


def _hcurve_lines(s: dict) -> list[str]:
    """The horizontal curves (docs/routes.md): each curve's tension band and the run's."""
    lines, k = [], 1
    if "hcurve1_ok" not in s:
        return lines
    lines.append(f"  {'horizontal curves (docs/routes.md)':<36}{'T min [kN]':>13}"
                 f"{'T max [kN]':>13}{'run [kN]':>20}{'in curve':>10}")
    while f"hcurve{k}_ok" in s:
        run = f"{s[f'hcurve{k}_t_low_kn']:.1f} to {s[f'hcurve{k}_t_high_kn']:.1f}"
        lines.append(f"    {'curve ' + str(k):<34}{s[f'hcurve{k}_tension_min_kn']:>13.1f}"
                     f"{s[f'hcurve{k}_tension_max_kn']:>13.1f}{run:>20}"
                     f"{'yes' if s[f'hcurve{k}_ok'] else 'NO':>10}")
        k += 1
    lines.append("")
    return lines


def _check_lines(s: dict) -> list[str]:

    """The design checks (docs/checks.md): each pulley's minimum diameter and resultant, then
    the transitions, the carry idlers and the holdback."""
    lines, j = [], 1
    if "pulley1_name" not in s:
        return lines
    names = []
    while f"pulley{len(names) + 1}_name" in s:
        names.append(s[f"pulley{len(names) + 1}_name"])
    w = max(24, *(len(n) for n in names))  # a booster's name is longer: keep the columns
    lines.append("  design checks (docs/checks.md)" + " " * (w - 24)
                 + "   D min [m]   D ok   resultant [kN]")
    while f"pulley{j}_name" in s:
        d_min, ok = s[f"pulley{j}_diameter_min_m"], s[f"pulley{j}_diameter_min_ok"]
        lines.append(f"    pulley {j}: {s[f'pulley{j}_name']:<{w}} "
                     f"{'-' if d_min is None else f'{d_min:.3f}':>7} "
                     f"{'-' if ok is None else ('yes' if ok else 'NO'):>6} "
                     f"{s[f'pulley{j}_resultant_kn']:>14.1f}")
        j += 1
    for key in ("transition_head_m", "transition_tail_m", "idler_load_carry_n",
                "idler_load_roll_n", "idler_l10_h", "holdback_torque_knm"):
        if s.get(key) is not None:
            f = results.field(key)
            # a bearing life is known to a few per cent at best: whole hours
            fmt = ".0f" if key == "idler_l10_h" else ".3f"
            lines.append(f"    {f.label:<34} {s[key]:>12{fmt}} {_unit(f)}")
    lines.append("")
    return lines


def _convex_too_tight(s: dict, k: int) -> str | None:
    """The radius of convex curve k as its warning gives it, where the run warns that it is
    below the radius its edge strain or centre line needs (``curves._convex_words``); None
    where it is not warned of."""
    found = re.search(rf"curve {k} \(convex, R ([^ ]+) m at [^)]*\): the troughed belt's",
                      s.get("message") or "")
    return None if found is None else found.group(1)


def _curve_lines(s: dict) -> list[str]:
    """The vertical curves (docs/routes.md, part (c)): per curve its kind, place, steady
    tension, lift-off tension (concave) and the radius it needs, a convex curve whose radius is
    below that marked; under a concave curve the same at start-up (the steady start-up walk of
    ``slip_margin_start``)."""
    lines, k = [], 1
    if "curve1_kind" not in s:
        return lines
    lines.append("  vertical curves (docs/routes.md)   at [m]   T [kN]   lift-off T [kN]"
                 "   lifts   R min [m]")
    while f"curve{k}_kind" in s:
        lift, r_min = s[f"curve{k}_liftoff_tension_kn"], s[f"curve{k}_radius_min_m"]
        convex = s[f"curve{k}_kind"] == "convex"
        lifts = "-" if convex else ("YES" if s[f"curve{k}_liftoff"] else "no")
        tight = _convex_too_tight(s, k) if convex else None
        lines.append(f"    curve {k}: {s[f'curve{k}_kind']:<21} {s[f'curve{k}_at_m']:>8.0f} "
                     f"{s[f'curve{k}_tension_kn']:>8.1f} "
                     f"{'-' if lift is None else f'{lift:.1f}':>17} "
                     f"{lifts:>7} "
                     f"{'-' if r_min is None else f'{math.ceil(r_min):.0f}':>11}"
                     + ("" if tight is None else f"   TOO TIGHT: R {tight} m (edge strain or "
                        "centre slack, see status)"))
        t_start = s.get(f"curve{k}_tension_start_kn")
        if t_start is not None and lift is not None:
            r_start = s[f"curve{k}_radius_min_start_m"]
            lines.append(f"      at start-up (rigid-body estimate) {t_start:>8.1f} "
                         f"{lift:>17.1f} "
                         f"{'YES' if s[f'curve{k}_liftoff_start'] else 'no':>7} "
                         f"{math.ceil(r_start):>11.0f}")
        t_rest = s.get(f"curve{k}_tension_rest_kn")
        if t_rest is not None and lift is not None:
            r_rest = s[f"curve{k}_radius_min_rest_m"]
            lines.append(f"      held at rest (estimate)           {t_rest:>8.1f} "
                         f"{lift:>17.1f} "
                         f"{'YES' if s[f'curve{k}_liftoff_rest'] else 'no':>7} "
                         f"{math.ceil(r_rest):>11.0f}")
        k += 1
    lines.append("")
    return lines
