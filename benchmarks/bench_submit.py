"""Study submission benchmark: resolving a 20 000-run study (the service's largest).

Times ``resolve_study`` (validation, expansion of every grid point, design basis, run ids) of a
study with one conveyor axis of 20 000 values on the 2 km example, best of several repeats,
and, in the same run, the same with each grid point's conveyor built as a deep copy of the
whole conveyor (``copy.deepcopy`` then set, the expansion before paths were copied on write),
and prints the ratio. Both must give the same study id (checked).

Run: ``.venv/bin/python benchmarks/bench_submit.py [--repeats N]``.
"""

from __future__ import annotations

import argparse
import copy
import datetime
import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from beltstudy.service.door.studyfile import resolve_study  # noqa: E402
from beltstudy.service.grid import expand  # noqa: E402
from beltstudy.service.grid.axes import with_paths  # noqa: E402

STUDY = {
    "name": "bench-submit-20000",
    "conveyor": "conveyors/slope-5pct.yaml",
    "grid": {"takeup.mass_kg": {"start": 10000, "stop": 29999, "step": 1}},
    "dynamics": False,
}


def deepcopy_paths(base: dict, sets) -> dict:
    """The baseline: the whole conveyor deep-copied for every grid point, then set."""
    data = copy.deepcopy(base)
    for path, value in sets:
        node = data
        for key in path[:-1]:
            if not isinstance(key, int) and node.get(key) is None:
                node[key] = {}
            node = node[key]
        node[path[-1]] = copy.deepcopy(value)
    return data


def best(repeats: int) -> tuple[float, str, int]:
    t_best, sid, total = float("inf"), "", 0
    for _ in range(repeats):
        t0 = time.perf_counter()
        study = resolve_study(STUDY, studies_dir=ROOT / "studies")
        t_best = min(t_best, time.perf_counter() - t0)
        sid, total = study.id, study.total
    return t_best, sid, total


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"# bench_submit  {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC  "
          f"{platform.machine()}  python {platform.python_version()}  load average {load}")
    resolve_study(STUDY, studies_dir=ROOT / "studies")  # imports and caches warm
    t_new, sid_new, total = best(args.repeats)
    expand.with_paths = deepcopy_paths
    try:
        t_old, sid_old, _ = best(args.repeats)
    finally:
        expand.with_paths = with_paths
    assert sid_new == sid_old, (sid_new, sid_old)
    print(f"  {total} runs, study id {sid_new} (the same both ways)")
    print(f"  copy on write (the service)   {t_new:6.2f} s  {t_new / total * 1e6:6.1f} us/run")
    print(f"  deep copy per point (before)  {t_old:6.2f} s  {t_old / total * 1e6:6.1f} us/run")
    print(f"  ratio before / now            {t_old / t_new:6.2f}")


if __name__ == "__main__":
    main()
