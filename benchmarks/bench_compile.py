"""The transient kernel's cold compile: numba's own inliner against the one-memo copy
(``engine/dynamics/inliner.py``), in alternating rounds of the same run.

Each compile is its own process with a fresh, empty ``NUMBA_CACHE_DIR`` (numba then compiles
every function of the engine), running the tests' warm-up run (the hand conveyor on a dozen
elements). "numba" puts numba's ``InlineWorker.inline_ir`` back before anything compiles;
"one memo" keeps the package's. Prints each compile's wall time, ``run_cycle``'s own
``compiler_lock`` and ``llvm_lock`` timers, the ratio, and whether the optimised LLVM IR of
``run_cycle`` is the same text both ways (the symbols' unique ids and numba's printing of the
fast-math flag set, which follows the process's string hashing, set aside).

    .venv/bin/python benchmarks/bench_compile.py [--rounds 1]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_PROGRAM = r'''
import json, sys, time
sys.path.insert(0, sys.argv[2])
from numba.core import inline_closurecall as icc
numba_own = icc.InlineWorker.inline_ir
import beltstudy.engine.dynamics  # noqa: F401  installs the one-memo copy
if sys.argv[1] == "numba":
    icc.InlineWorker.inline_ir = numba_own
from tests.conftest import WARM_UP_SCENARIO, hand_conveyor_dict
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.dynamics.kernel import run_cycle
from beltstudy.engine.run import run_one
t0 = time.perf_counter()
run_one(parse_conveyor(hand_conveyor_dict()), Scenario(**WARM_UP_SCENARIO), model="din")
wall = time.perf_counter() - t0
(sig,) = run_cycle.signatures
timers = run_cycle.get_metadata(sig)["timers"]
open(sys.argv[3], "w").write(next(iter(run_cycle.inspect_llvm().values())))
print(json.dumps({"wall_s": wall, **timers}))
'''


def _normalised(llvm: str) -> str:
    llvm = re.sub(r"_ZN[A-Za-z0-9_$.]*", "@Z", llvm)  # unique ids and ABI tags in symbols
    return re.sub(r"\[\d+ x i8\] c\"missing Environment: @Z\\00\"", "[n x i8] env", llvm)


def compile_once(mode: str) -> tuple[dict, str]:
    with tempfile.TemporaryDirectory(prefix="beltstudy-compile-") as cache:
        ir_path = os.path.join(cache, "run_cycle.ll")
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        out = subprocess.run([sys.executable, "-c", _PROGRAM, mode, str(ROOT), ir_path],
                             capture_output=True, text=True, env=env, check=True).stdout
        return json.loads(out.strip().splitlines()[-1]), _normalised(Path(ir_path).read_text())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=1)
    args = ap.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.2f}  ({time.strftime('%Y-%m-%d %H:%M')})")
    print(f"{'round':>5}  {'inliner':<9} {'wall [s]':>9} {'run_cycle [s]':>14} {'LLVM [s]':>9}")
    best: dict[str, float] = {}
    irs: dict[str, str] = {}
    for r in range(1, args.rounds + 1):
        for mode in ("numba", "one memo"):
            t, ir = compile_once("numba" if mode == "numba" else "ours")
            irs.setdefault(mode, ir)
            best[mode] = min(best.get(mode, 1e99), t["wall_s"])
            print(f"{r:>5}  {mode:<9} {t['wall_s']:>9.1f} {t['compiler_lock']:>14.1f} "
                  f"{t['llvm_lock']:>9.1f}")
    print(f"\none memo / numba, best of each: {best['one memo'] / best['numba']:.2f}")
    same = irs["numba"] == irs["one memo"]
    print(f"run_cycle's optimised LLVM IR the same text: {same} "
          f"({len(irs['numba']) / 1e6:.2f} MB)")
    print(f"load average after: {os.getloadavg()[0]:.2f}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
