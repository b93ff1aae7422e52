"""The transient kernel against an earlier revision of the engine, in the same run.

For a change that must not slow the kernel (a reshaping): the 16.8 km example with 1 000
elements (120 s s-curve start, 30 s run, 60 s controlled stop), DIN and Non-Lin, timed with
this checkout and with revision REV in alternating rounds (each round runs both, each in its
own interpreter, best of ``--repeat`` kernel calls after one that loads the compile cache), so a
slower spell of a shared machine falls on both. Prints each round and, per model, the best
kernel wall time of each version and their ratio (this checkout over REV; below 1.05 is
within 5 %).

REV is installed once into its own virtual environment under the system's temporary
directory (``git archive`` of the revision, ``pip install``; a few minutes the first time).

``--study288``: the 2 km slope at 202 elements in the 288-run study's scenario instead (its
steps are short, so the scalar work per step counts: pulley blocks, drives, records).

Run: ``.venv/bin/python benchmarks/bench_kernel_against.py 187e89f [--rounds 5] [--study288]``.
"""

from __future__ import annotations

import argparse
import datetime
import json
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONVEYOR = ROOT / "studies" / "conveyors" / "overland-16km.yaml"
SCENARIO = dict(start={"control": "s-curve", "time_s": 120}, run_s=30,
                stop={"mode": "controlled", "time_s": 60})
#: ``--study288``: the 2 km slope at 202 elements in the 288-run study's scenario
#: (benchmarks/bench_study.py, its 20 s controlled stop), where a step's scalar work (pulley
#: blocks, drives, observation, records) is a large part of the step.
CONVEYOR_288 = ROOT / "studies" / "conveyors" / "slope-5pct.yaml"
SCENARIO_288 = dict(start={"control": "s-curve", "time_s": 40}, run_s=20,
                    stop={"mode": "controlled", "time_s": 20})

#: Run in each version's interpreter: the best kernel wall time per model [s].
SNIPPET = """
import json, sys
from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.dynamics import build_system
from beltstudy.engine.dynamics.simulate import run_kernel
from beltstudy.engine.statics import solve_steady
conv = load_conveyor(sys.argv[1])
out = {}
for model in sys.argv[2].split(","):
    st = solve_steady(conv, model=model, n_elements=int(sys.argv[3]))
    system = build_system(conv, Scenario(**json.loads(sys.argv[4])), st)
    run_kernel(system)
    out[model] = min(run_kernel(system)[1] for _ in range(int(sys.argv[5])))
print(json.dumps(out))
"""


def interpreter(rev: str) -> Path:
    """The python of a virtual environment with revision ``rev`` installed (made once)."""
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", rev],
                         capture_output=True, text=True, check=True).stdout.strip()
    home = Path(tempfile.gettempdir()) / f"beltstudy-rev-{sha}"
    python = home / "venv" / "bin" / "python"
    if python.exists():
        return python
    src = home / "src"
    src.mkdir(parents=True, exist_ok=True)
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", "--format=tar", sha],
                             capture_output=True, check=True).stdout
    tar_path = home / "src.tar"
    tar_path.write_bytes(archive)
    with tarfile.open(tar_path) as tar:
        tar.extractall(src, filter="data")
    print(f"installing {sha} into {home / 'venv'} ...", flush=True)
    subprocess.run([sys.executable, "-m", "venv", str(home / "venv")], check=True)
    subprocess.run([str(python), "-m", "pip", "install", "--quiet", str(src)], check=True)
    return python


def timed(python: Path, models: str, n: int, repeat: int, study288: bool = False
          ) -> dict[str, float]:
    conveyor, scenario = (CONVEYOR_288, SCENARIO_288) if study288 else (CONVEYOR, SCENARIO)
    proc = subprocess.run([str(python), "-c", SNIPPET, str(conveyor), models, str(n),
                           json.dumps(scenario), str(repeat)], capture_output=True, text=True,
                          cwd=tempfile.gettempdir())
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr.strip().splitlines()[-1])
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rev", help="the revision to compare against (a commit or tag)")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--elements", type=int, default=None,
                    help="default 1000 (202 with --study288)")
    ap.add_argument("--models", default="din,nonlin")
    ap.add_argument("--study288", action="store_true",
                    help="the 2 km slope at 202 elements in the 288-run study's scenario")
    args = ap.parse_args()
    if args.elements is None:
        args.elements = 202 if args.study288 else 1000
    old = interpreter(args.rev)
    new = Path(sys.executable)
    print("# bench_kernel_against")
    print(f"date: {datetime.datetime.now().isoformat(timespec='seconds')}")
    what = "2 km slope (study288 scenario)" if args.study288 else "16.8 km"
    print(f"this checkout ({new}) against {args.rev} ({old}); {what}, {args.elements} "
          f"elements, best of {args.repeat} kernel calls per version and round")
    best: dict[str, dict[str, float]] = {"this": {}, "rev": {}}
    for k in range(args.rounds):
        row = []
        for tag, python in (("rev", old), ("this", new)) if k % 2 == 0 else \
                (("this", new), ("rev", old)):
            walls = timed(python, args.models, args.elements, args.repeat, args.study288)
            for model, wall in walls.items():
                best[tag][model] = min(best[tag].get(model, float("inf")), wall)
                row.append(f"{tag} {model} {wall:.4f} s")
        print(f"  round {k + 1}: " + ", ".join(row), flush=True)
    for model in args.models.split(","):
        a, b = best["this"][model], best["rev"][model]
        print(f"  {model:7s} this {a:.4f} s, {args.rev} {b:.4f} s: this / {args.rev} = "
              f"{a / b:.3f}")


if __name__ == "__main__":
    main()
