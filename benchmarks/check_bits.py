"""Bit-identity check of the transient engine: one SHA-256 over every output of a fixed set of
runs, per case and in total, to hold a change that must not move one bit (a speed-up of the
kernel) against the results of the code before it.

The cases:

* **study288**: the 288-run benchmark study (``bench_study.STUDY288``: the 2 km slope, 202
  elements, din / cema / nonlin, both belts, every load, temperature and stop time), the runs
  grouped by everything but their stop time and run as the service runs them
  (:func:`beltstudy.engine.run.run_group`: one shared start per group);
* **example**: every example conveyor (``studies/conveyors/*.yaml``) with din and nonlin,
  default elements, a coast, a controlled and (with brakes) a brake stop (:func:`run_one`);
* **kernel**: the whole cycles the kernel is tested against the numpy reference on
  (``tests/engine/dynamics/test_kernel.py``: slip in a start, a dol drive through a fluid
  coupling with its trip, brakes with ramps, curves and hold, a holdback, a carriage at its
  end stop, torque start, moving support, dual heads, exact and expanded laws) and the runs
  that end early (a runaway, a diverged shaft), by the kernel's own arrays;
* **hand**: the hand conveyor's holdback with a brake, a booster that slips, a dol start, a
  braked slide over a pulley (tests/engine/integration).

Every float is hashed by its bytes (arrays) or ``repr`` (numbers); only wall-clock fields
(``elapsed_s``, ``wall_s``) are skipped.

    .venv/bin/python benchmarks/check_bits.py [--save FILE] [--against FILE] [--only NAME]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SKIP = {"elapsed_s", "wall_s"}
#: ``--runs``: print a digest per run (to find the run that moved)
RUNS: list = []


def mark(h, label) -> None:
    """With ``--runs``: the digest so far, after the run ``label``."""
    if RUNS:
        print(f"    {label}: {h.copy().hexdigest()[:16]}")


def feed(h, value, name="") -> None:
    """Feed a value (records, dicts, sequences, arrays, numbers, strings) into hash h."""
    h.update(name.encode())
    if hasattr(value, "_fields"):
        for f in value._fields:
            feed(h, getattr(value, f), f".{f}")
    elif isinstance(value, dict):
        for k in sorted(value, key=str):
            if k in SKIP:
                continue
            feed(h, value[k], f"[{k}]")
    elif isinstance(value, (list, tuple)):
        h.update(f"<{type(value).__name__}{len(value)}>".encode())
        for i, v in enumerate(value):
            feed(h, v, f"[{i}]")
    elif isinstance(value, np.ndarray):
        h.update(f"{value.dtype.str}{value.dtype.descr}{value.shape}".encode())
        h.update(np.ascontiguousarray(value).tobytes())
    elif isinstance(value, np.void):
        feed(h, np.array(value))
    elif hasattr(value, "to_numpy") and hasattr(value, "columns"):  # a DataFrame
        for c in value.columns:
            feed(h, value[c].to_numpy(), f"<{c}>")
    else:
        h.update(repr(value).encode())


def transient_digest(h, tr) -> None:
    """Every output of a TransientResult."""
    feed(h, tr.status, "status")
    feed(h, tr.message, "message")
    feed(h, tr.warnings, "warnings")
    feed(h, tr.summary, "summary")
    feed(h, tr.series, "series")
    feed(h, tr.raw, "raw")
    feed(h, tr.trace_data, "trace")
    feed(h, tr.surface_data, "surface")
    feed(h, tr.envelope_data, "envelope")


def run_digest(h, r) -> None:
    """Every output of a RunResult (the summary and the transient's outputs)."""
    feed(h, r.summary, "run.summary")
    if r.transient is not None:
        transient_digest(h, r.transient)


# --------------------------------------------------------------------------------------
# the cases


def case_study288(h) -> int:
    from beltstudy.engine.conveyor import parse_conveyor, parse_scenario
    from beltstudy.engine.run import run_group
    from beltstudy.service.door.studyfile import resolve_study
    from benchmarks.bench_study import STUDY288

    study = resolve_study(STUDY288, studies_dir=ROOT / "studies")
    groups: dict = {}
    for spec in study.runs:
        scn = dict(spec.scenario)
        stop = dict(scn.get("stop") or {})
        stop.pop("time_s", None)
        scn["stop"] = stop
        key = json.dumps([spec.conveyor, scn, spec.model, spec.params], sort_keys=True,
                         default=str)
        groups.setdefault(key, []).append(spec)
    n = 0
    for key in groups:
        specs = groups[key]
        spec = specs[0]
        conv = parse_conveyor(spec.conveyor)
        scns = [parse_scenario(s.scenario) for s in specs]
        results = run_group(conv, scns, model=spec.model, params=spec.params or None)
        for s, r in zip(specs, results, strict=True):
            feed(h, s.axes, "axes")
            run_digest(h, r)
            mark(h, s.axes)
            n += 1
    return n


def case_example(h) -> int:
    from beltstudy.engine.conveyor import Scenario, load_conveyor
    from beltstudy.engine.run import run_one

    stops = [{"mode": "coast"}, {"mode": "controlled", "time_s": 20},
             {"mode": "brake", "time_s": 15}]
    n = 0
    for path in sorted((ROOT / "studies" / "conveyors").glob("*.yaml")):
        conv = load_conveyor(path)
        runs = [(model, stop) for model in ("din", "nonlin") for stop in stops
                if stop["mode"] != "brake" or conv.brakes]
        for model, stop in runs:
            scn = Scenario(start={"control": "s-curve", "time_s": 30}, run_s=10, stop=stop)
            try:
                r = run_one(conv, scn, model=model)
            except Exception as exc:  # an input the engine refuses: its words are the output
                feed(h, f"{type(exc).__name__}: {exc}", path.name)
                print(f"  {path.name} {model}: {type(exc).__name__}: {str(exc)[:120]}")
                continue
            feed(h, f"{path.name}{model}{stop}", "case")
            run_digest(h, r)
            mark(h, f"{path.name} {model} {stop}")
            n += 1
    return n


def _kernel_digest(h, sys) -> None:
    from beltstudy.engine.dynamics.simulate import decode, fresh_run

    kr = fresh_run(sys)
    kr.call()
    feed(h, kr.out, "out")
    feed(h, kr.state, "state")
    feed(h, (kr.model.shafts.vs, kr.model.shafts.slip, kr.model.drives.force,
             kr.model.drives.vm, kr.model.drives.ft), "final")
    transient_digest(h, decode(sys, kr, 0.0))


def case_kernel(h) -> int:
    from beltstudy.engine.conveyor import Scenario, parse_conveyor
    from beltstudy.engine.dynamics import DynamicsOptions, build_system
    from beltstudy.engine.statics import solve_steady
    from tests.conftest import hand_conveyor_dict
    from tests.engine.dynamics import test_kernel as tk

    n = 0
    extra = [("fabric-1km", {}, "nonlin", dict(start={"control": "s-curve", "time_s": 12}, run_s=3,
                                              stop={"mode": "coast"},
                                              options=dict(resistance_rtol=0.0))),
             ("slope-5pct", {}, "nonlin", dict(start={"control": "s-curve", "time_s": 12},
                                              run_s=3, stop={"mode": "controlled",
                                                             "time_s": 10}))]
    cases = [tuple(p.values[:4]) for p in tk.CASES] + extra
    for name, changes, model, scenario in cases:
        conv = tk.conveyor(name, **changes)
        scenario = dict(scenario)
        opts = DynamicsOptions(**scenario.pop("options", {}))
        scn = Scenario(**scenario)
        st = solve_steady(conv, model=model, load=scn.load, n_elements=40)
        feed(h, f"{name}{model}{scenario}", "case")
        _kernel_digest(h, build_system(conv, scn, st, opts))
        mark(h, f"{name} {model} {scenario}")
        n += 1
    ends = [(dict(profile=[{"length_m": 1000, "lift_m": -150}]), {}),
            (dict(drives=[{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                           "pulley_diameter_m": 1.0, "inertia_kg_m2": 2.0, "control": "dol",
                           "rated_power_kw": 240, "coupling": "fluid"}],
                  takeup={"type": "gravity", "position": "tail", "mass_kg": 16000}),
             dict(dt_s=0.013))]
    for changes, scenario in ends:
        conv = parse_conveyor(hand_conveyor_dict(**changes))
        scn = Scenario(elements=40, start={"time_s": 20}, run_s=10, stop={"mode": "coast"},
                       **scenario)
        feed(h, repr(changes), "case")
        _kernel_digest(h, build_system(conv, scn, solve_steady(conv, model="din",
                                                               n_elements=40)))
        mark(h, repr(changes))
        n += 1
    return n


def case_hand(h) -> int:
    from beltstudy.engine.conveyor import Scenario, parse_conveyor
    from beltstudy.engine.dynamics import DynamicsOptions, build_system, simulate
    from beltstudy.engine.run import run_one
    from beltstudy.engine.statics import solve_steady
    from tests.conftest import hand_conveyor_dict
    from tests.engine.conftest import hand_conv, hand_drive

    n = 0
    # a holdback with a brake on its shaft: a coast stop rolling back onto it
    conv = parse_conveyor(hand_conveyor_dict(holdback=True, brakes=[
        {"position": "head", "force_kn": 10.0, "delay_s": 0.0, "ramp_s": 0.0, "hold": True}]))
    r = run_one(conv, Scenario(elements=100, start={"time_s": 60}, run_s=10,
                               stop={"mode": "coast"}), model="din",
                options=DynamicsOptions(post_rest_s=60.0))
    run_digest(h, r)
    n += 1
    # a slipping booster at mid-carry, open-loop force start
    d = hand_conveyor_dict(drives=[
        {"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 0.5,
         "pulley_diameter_m": 1.0},
        {"wrap_deg": 90, "friction": 0.35, "share": 0.5, "pulley_diameter_m": 1.0,
         "position": "carry", "at_m": 500, "friction_kinetic": 0.25}])
    d["takeup"] = {"type": "gravity", "position": "tail", "mass_kg": 3000}
    conv = parse_conveyor(d)
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(run_s=30), st, DynamicsOptions(force_start_n=150e3))
    transient_digest(h, simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 6.0))
    n += 1
    # a dol start
    conv = hand_conv(drives=[hand_drive(control="dol", rated_power_kw=240, inertia_kg_m2=100)],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000})
    st = solve_steady(conv, model="din", n_elements=60)
    sysm = build_system(conv, Scenario(start={"time_s": 30}, run_s=10, elements=60), st)
    transient_digest(h, simulate(sysm, t_end_s=sysm.model.cycle.t_pre + 25.0))
    n += 1
    # a brake far stronger than the grip: the belt slides over the held pulley
    conv = hand_conv(drives=[hand_drive(friction_kinetic=0.25)],
                     brakes=[{"drive": 1, "force_kn": 400, "delay_s": 0.0, "ramp_s": 0.2}],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 8000})
    r = run_one(conv, Scenario(start={"time_s": 20}, run_s=5, record_dt_s=0.02,
                               stop={"mode": "brake", "time_s": 5}, elements=60), model="din")
    run_digest(h, r)
    n += 1
    return n


CASES = {"study288": case_study288, "example": case_example, "kernel": case_kernel,
         "hand": case_hand}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--save", help="write the digests to this JSON file")
    ap.add_argument("--against", help="compare with the digests in this JSON file")
    ap.add_argument("--only", choices=sorted(CASES), action="append")
    ap.add_argument("--runs", action="store_true", help="print a digest after every run")
    args = ap.parse_args()
    if args.runs:
        RUNS.append(True)
    digests = {}
    total = hashlib.sha256()
    for name, fn in CASES.items():
        if args.only and name not in args.only:
            continue
        h = hashlib.sha256()
        t0 = time.perf_counter()
        runs = fn(h)
        digests[name] = h.hexdigest()
        total.update(digests[name].encode())
        print(f"{name:10s} {runs:3d} runs  {digests[name]}  ({time.perf_counter() - t0:.1f} s)",
              flush=True)
    digests["total"] = total.hexdigest()
    print(f"{'total':10s}           {digests['total']}")
    if args.save:
        Path(args.save).write_text(json.dumps(digests, indent=1) + "\n")
        print(f"saved to {args.save}")
    if args.against:
        ref = json.loads(Path(args.against).read_text())
        bad = [k for k in digests if ref.get(k) != digests[k]]
        if bad:
            print("MISMATCH: " + ", ".join(bad))
            sys.exit(1)
        print(f"identical to {args.against}")


if __name__ == "__main__":
    main()
