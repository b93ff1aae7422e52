"""Running-phase fuzz: do random conveyors settle while running, and does every run that does
not say so?

The 120 designs of the seeded generator of ``tests/engine/integration/test_run_random_designs``
(seeds 0-119, a capacity that overfills its belt halved as the test does: 1-4 profile
sections, 1-3 drives at either end, vfd and dol, fluid couplings, gravity and fixed take-ups,
brakes, holdback), each run with its own model, load and start but a long running phase (``--run-s``, default 600 s) and a coast stop, on 40 elements.

A run is judged unsettled here, independently of the engine's own check, when its mean belt
speed over the last ``--tail-s`` seconds (default 120 s) of the running phase swings (highest
less lowest) by more than ``--swing`` of design speed (default 0.02), or a drive's force there
swings about its mean by more than ``SETTLE_FORCE`` of its rated force. Every unsettled run must
carry the engine's ``not settled while running`` warning (PHYSICS 5.2,
``beltstudy.engine.dynamics.simulate.running_warnings``); runs that warn but are settled over
the tail (a swing that decayed late in the running phase) are listed too.

Prints one line per run that is unsettled, warns, or overspeeds, then the counts; exits 1 when
an unsettled run lacks the warning.

Run: ``NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/fuzz_running.py [--n 120]`` from the
repository root (a few minutes after compilation).
"""

from __future__ import annotations

import argparse
import random
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from beltstudy.engine.conveyor import Scenario, parse_conveyor  # noqa: E402
from beltstudy.engine.dynamics.simulate import SETTLE_FORCE  # noqa: E402
from beltstudy.engine.run import run_one  # noqa: E402
from tests.engine.integration.test_run_random_designs import _design, _within_fill  # noqa: E402

WARNING = "not settled while running"


def judge(seed: int, run_s: float, tail_s: float, swing_max: float) -> dict:
    """One design with a long running phase: its tail swing and what the run said."""
    conv, model, scenario = _within_fill(_design(random.Random(seed)))
    scenario = dict(scenario, run_s=run_s, stop={"mode": "coast"}, elements=40)
    c = parse_conveyor(conv)
    r = run_one(c, Scenario(**scenario), model=model)
    s = r.summary
    out = {"seed": seed, "status": s["status"], "message": s.get("message") or "",
           "drives": "+".join(f"{d.control}/{d.position}" for d in c.drives),
           "belt": c.belt.type, "length_m": round(c.length_m), "swing": None}
    tr = r.transient
    if tr is None or tr.status == "failed":
        return out
    ts = r.timeseries
    t_cmd = tr.system.stop_command_s
    tail = (ts["t_s"] > t_cmd - tail_s) & (ts["t_s"] <= t_cmd)
    v = ts["v_mean_m_s"][tail].to_numpy()
    ran = len(v) > 1 and "ran away" not in out["message"]
    out["swing"] = float(np.ptp(v)) / c.speed_m_s if ran else None
    rated = tr.system.model.drives.rated
    # the drives' force swings about their mean, over their rated force
    out["force_swing"] = max(0.5 * float(np.ptp(ts[f"f_drive{i + 1}_kn"][tail].to_numpy()))
                             * 1e3 / rated[i] for i in range(len(c.drives))) if ran else None
    out["unsettled"] = bool(ran and (out["swing"] > swing_max
                                     or out["force_swing"] > SETTLE_FORCE))
    out["warned"] = WARNING in out["message"]
    out["overspeed"] = "overspeed in the start" in out["message"]
    return out


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=120, help="designs (seeds 0 to n-1)")
    p.add_argument("--run-s", type=float, default=600.0, help="running phase [s]")
    p.add_argument("--tail-s", type=float, default=120.0, help="judged window [s]")
    p.add_argument("--swing", type=float, default=0.02, help="unsettled above this fraction")
    a = p.parse_args()
    t0 = time.perf_counter()
    rows = []
    for seed in range(a.n):
        row = judge(seed, a.run_s, a.tail_s, a.swing)
        rows.append(row)
        if row.get("unsettled") or row.get("warned") or row.get("overspeed"):
            sw = f"{100 * row['swing']:.1f} %" if row["swing"] is not None else "-"
            if row.get("force_swing") is not None:
                sw += f", forces +-{100 * row['force_swing']:.0f} % of rated"
            flags = [k for k in ("unsettled", "warned", "overspeed") if row.get(k)]
            print(f"seed {seed:3d} {row['drives']:<28s} {row['belt']:<9s} {row['length_m']:5d} m "
                  f"tail swing {sw:>7s}  {' '.join(flags)}", flush=True)
    judged = [r for r in rows if r.get("swing") is not None]
    unsettled = [r for r in judged if r["unsettled"]]
    silent = [r for r in unsettled if not r["warned"]]
    print(f"{len(rows)} designs, {len(judged)} judged ({len(rows) - len(judged)} failed or ran "
          f"away), {len(unsettled)} unsettled over the last {a.tail_s:g} s of a {a.run_s:g} s "
          f"running phase, {len(silent)} of them without the warning; "
          f"{sum(r['warned'] for r in judged)} warned, "
          f"{sum(r['overspeed'] for r in judged)} overspeed warnings; "
          f"{time.perf_counter() - t0:.0f} s")
    for r in silent:
        print(f"  silent: seed {r['seed']}: {r['message'][:300]}")
    return 1 if silent else 0


if __name__ == "__main__":
    sys.exit(main())
