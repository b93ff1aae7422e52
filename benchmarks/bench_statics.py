"""Steady-solve benchmark: the 16.8 km overland with 2000 elements, every friction model.

Times ``solve_steady`` (loop build, law build, fixed point, summary) for din, cema, cmod,
visco and nonlin, best of several repeats after a warm-up, and prints the times and the
ratios to din measured in the same run. Acceptance (issue 4): nonlin <= 5 x din.

Run: ``.venv/bin/python benchmarks/bench_statics.py [--repeats N] [--elements N]``.
"""

from __future__ import annotations

import argparse
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from beltstudy.engine.conveyor import load_conveyor  # noqa: E402
from beltstudy.engine.statics import solve_steady  # noqa: E402

MODELS = ("din", "cema", "cmod", "visco", "nonlin")
CONVEYOR = ROOT / "studies" / "conveyors" / "overland-16km.yaml"
LIMIT = 5.0


def best_time(conv, model: str, n: int, repeats: int) -> tuple[float, int]:
    """Best wall time of ``repeats`` solves [s] and the iteration count."""
    res = solve_steady(conv, model=model, n_elements=n)  # warm-up (imports, caches)
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = solve_steady(conv, model=model, n_elements=n)
        best = min(best, time.perf_counter() - t0)
    return best, res.iterations


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--elements", type=int, default=2000)
    args = ap.parse_args(argv)
    conv = load_conveyor(CONVEYOR)
    print(f"steady solve of {CONVEYOR.name}, {args.elements} elements, best of {args.repeats}")
    print(f"python {platform.python_version()} on {platform.machine()}")
    times = {}
    print(f"\n  {'model':<8}{'time [ms]':>12}{'x din':>9}{'iterations':>12}")
    for model in MODELS:
        t, it = best_time(conv, model, args.elements, args.repeats)
        times[model] = t
        print(f"  {model:<8}{t * 1e3:12.2f}{t / times['din']:9.2f}{it:12d}")
    ratio = times["nonlin"] / times["din"]
    ok = ratio <= LIMIT
    print(f"\nnonlin / din = {ratio:.2f} (acceptance <= {LIMIT:g}: {'ok' if ok else 'FAILED'})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
