"""One start, many stops: the 288-run study's runs one at a time against the worker's grouped
path (issue 29 item 1).

The study is ``STUDY288`` of ``benchmarks/bench_study.py`` (the 2 km slope, 202 elements, din,
cema, nonlin x 4 temperatures x 4 stop times x 3 loads x 2 belts): its four stop times share a
start. In alternating rounds, in this one process at the same niceness, it times

* **alone**: :func:`beltstudy.service.dask.tasks.run_spec` of every run, one after another
  (what a worker did before);
* **grouped**: :func:`beltstudy.service.dask.tasks.run_specs` of the whole study (the runs that
  differ only in their stop share one simulated rest, start and run:
  :func:`beltstudy.engine.run.run_group`);

and prints the runs/s of each round and the ratio of the best rounds. It also checks on the
way that every grouped row equals its run alone (but ``elapsed_s``). Figures are printed,
never asserted (BENCHMARKS.md).

    .venv/bin/python benchmarks/bench_shared_start.py [--rounds N]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _same(a: dict, b: dict) -> bool:
    for k, v in a.items():
        if k == "elapsed_s":
            continue
        w = b.get(k)
        if isinstance(v, float) and math.isnan(v):
            if not (isinstance(w, float) and math.isnan(w)):
                return False
        elif v != w:
            return False
    return set(a) == set(b)


def main() -> int:
    from bench_study import STUDY288

    from beltstudy.service.dask.tasks import run_spec, run_specs, start_candidate
    from beltstudy.service.door.studyfile import resolve_study

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    study = resolve_study(STUDY288, base_dir=ROOT / "studies")
    runs = study.runs
    groups = len({start_candidate(r) for r in runs})
    load = os.getloadavg()
    print(f"# bench_shared_start  {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}  "
          f"{platform.machine()}  cores={os.cpu_count()}  python {platform.python_version()}  "
          f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    print(f"study288: {len(runs)} runs, {groups} shared starts")
    for spec in runs[:: max(1, len(runs) // 6)]:  # warm: imports, every model's first run
        run_spec(spec)
    alone_rates, grouped_rates = [], []
    identical = True
    for r in range(args.rounds):
        t0 = time.perf_counter()
        alone = [run_spec(s, "b")[0] for s in runs]
        alone_rates.append(len(runs) / (time.perf_counter() - t0))
        t0 = time.perf_counter()
        grouped = [row for row, _ in run_specs(runs, "b")]
        grouped_rates.append(len(runs) / (time.perf_counter() - t0))
        identical &= all(_same(g, a) for g, a in zip(grouped, alone, strict=True))
        print(f"  round {r + 1}: alone {alone_rates[-1]:.1f} runs/s, grouped "
              f"{grouped_rates[-1]:.1f} runs/s")
    best_a, best_g = max(alone_rates), max(grouped_rates)
    print(f"  best: alone {best_a:.1f} runs/s, grouped {best_g:.1f} runs/s = "
          f"{best_g / best_a:.2f} x")
    print(f"  every grouped row equals its run alone (but elapsed_s): {identical}")
    load = os.getloadavg()
    print(f"  load average after {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
