"""A process's start with and without the package's own bytecode, in alternating rounds.

``make run``, ``make serve`` and ``make test`` write the package's bytecode first
(``python -m compileall -q engine service``): an editable install does not, and where
``PYTHONDONTWRITEBYTECODE`` is set no process writes it either, so each one (a test worker,
a service, a Dask worker, a command the tests start) compiled the package's sources again.
This times a fresh interpreter importing the engine and the service (what every such process
does first) with ``PYTHONDONTWRITEBYTECODE=1``, alternately with the package's ``.pyc`` files in
place and moved aside (they are put back at the end, whatever happens), and prints the best
of each and their difference per process.

    .venv/bin/python benchmarks/bench_bytecode.py [--rounds 5]
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMPORTS = "import beltstudy.engine.run, beltstudy.service.api.app"


def start_s() -> float:
    """Wall time of a fresh interpreter importing the engine and the service [s]."""
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", IMPORTS], cwd=ROOT, env=env, check=True)
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    subprocess.run([sys.executable, "-m", "compileall", "-q", "engine", "service"], cwd=ROOT,
                   check=True, stdout=subprocess.DEVNULL)
    pycs = [p for d in ("engine", "service") for p in (ROOT / d).rglob("__pycache__/*.pyc")]
    aside = Path(tempfile.mkdtemp(prefix="beltstudy-pyc-"))
    print(f"# bench_bytecode  {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}  "
          f"python {sys.version.split()[0]}  {len(pycs)} .pyc files of the package  "
          f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    start_s()  # the libraries' own files into the page cache
    with_pyc, without = [], []
    try:
        for r in range(args.rounds):
            with_pyc.append(start_s())
            for i, p in enumerate(pycs):
                shutil.move(p, aside / f"{i}.pyc")
            try:
                without.append(start_s())
            finally:
                for i, p in enumerate(pycs):
                    shutil.move(aside / f"{i}.pyc", p)
            print(f"  round {r + 1}: with {with_pyc[-1]:.2f} s, without {without[-1]:.2f} s")
    finally:
        shutil.rmtree(aside, ignore_errors=True)
    a, b = min(with_pyc), min(without)
    print(f"  best: with the package's bytecode {a:.2f} s, without {b:.2f} s: "
          f"{b - a:.2f} s more a process without it ({b / a:.2f} x)")


if __name__ == "__main__":
    main()
