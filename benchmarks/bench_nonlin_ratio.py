"""Non-Lin's run time over DIN's on the 288-run study (issue 29 item 4: at most 1.5).

The study is ``STUDY288`` of ``benchmarks/bench_study.py``. Its runs come in triples that differ
only in the friction model (din, cema, nonlin at one temperature, load, belt and stop time); in
this one process, each triple's three runs are timed one after another (``run_one`` with the
parse, as a worker runs it), the order of the models turned round each pass so that a drift of
the machine's speed falls on every model alike. Prints the median run time of each model and
the medians' ratios; figures are printed, never asserted (BENCHMARKS.md).

    .venv/bin/python benchmarks/bench_nonlin_ratio.py [--passes N]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_study import STUDY288, _one  # noqa: E402

from beltstudy.service.door.studyfile import resolve_study  # noqa: E402

MODELS = ("din", "cema", "nonlin")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--passes", type=int, default=2, help="passes over the study (default 2)")
    args = ap.parse_args()
    study = resolve_study(dict(STUDY288), studies_dir=ROOT / "studies")
    triples: dict[tuple, dict] = {}
    for r in study.runs:
        key = tuple(sorted((k, str(v)) for k, v in r.axes.items() if k != "friction_model"))
        triples.setdefault(key, {})[r.model] = r
    print(f"# bench_nonlin_ratio  {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}  "
          f"{platform.machine()}  cores={os.cpu_count()}  python {platform.python_version()}  "
          f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    first = next(iter(triples.values()))
    for m in MODELS:  # compiled and warm before the clock
        _one(first[m])
    times: dict[str, list[float]] = {m: [] for m in MODELS}
    for p in range(args.passes):
        order = MODELS if p % 2 == 0 else MODELS[::-1]
        for runs in triples.values():
            for m in order:
                t0 = time.perf_counter()
                _one(runs[m])
                times[m].append(time.perf_counter() - t0)
    med = {m: statistics.median(t) for m, t in times.items()}
    print(f"{len(triples)} triples x {args.passes} passes: median run time "
          + "  ".join(f"{m} {med[m] * 1e3:.2f} ms" for m in MODELS))
    print(f"  nonlin / din = {med['nonlin'] / med['din']:.3f} (issue 29: at most 1.5)   "
          f"cema / din = {med['cema'] / med['din']:.3f}")
    print(f"# load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
