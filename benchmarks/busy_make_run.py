"""``make run`` on a fresh clone while other CPU-bound processes keep the cores busy.

The cold start of a fresh clone (virtual environment, package install, the workers' first
compile of the transient engine) must work on a loaded machine: ``beltstudy demo`` follows the
service's stages with no fixed time limit and shows ``compiling the transient engine (first
run only)`` while the workers compile. This script clones the repository into a temporary
directory, starts ``--burners`` (default 2) processes that spin on the CPU at normal priority,
runs ``make run`` in the clone, stops the burners and prints the command's exit code, its
wall time, the load average and whether the compile line was shown; it exits 1 when ``make
run`` failed or the compile line is missing.

    python3 benchmarks/busy_make_run.py [--burners 2] [--keep]

It needs what ``make run`` needs (Python 3.11, make, the package registry); a fresh clone
takes about 10-20 minutes on a busy 2-core machine (most of it the install and the compile).
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COMPILE_LINE = "compiling the transient engine (first run only)"


def _burn() -> None:
    """Spin on the CPU until killed (a CPU-bound process at normal priority)."""
    x = 0
    while True:
        x = (x * 1103515245 + 12345) % 2147483648


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--burners", type=int, default=2,
                    help="CPU-bound processes running beside make run (default 2)")
    ap.add_argument("--keep", action="store_true", help="keep the clone and its log")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="busy-make-run-"))
    clone = tmp / "clone"
    subprocess.run(["git", "clone", "--quiet", str(ROOT), str(clone)], check=True)
    head = subprocess.run(["git", "-C", str(clone), "rev-parse", "--short", "HEAD"],
                          capture_output=True, text=True, check=True).stdout.strip()
    ctx = mp.get_context("spawn")
    burners = [ctx.Process(target=_burn, daemon=True) for _ in range(args.burners)]
    for p in burners:
        p.start()
    print(f"# busy_make_run  {time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC  "
          f"clone of {head} in {clone}  cores={os.cpu_count()}  {args.burners} CPU-bound "
          "processes beside it", flush=True)
    log = tmp / "make-run.log"
    loads = []
    t0 = time.perf_counter()
    try:
        with log.open("w", encoding="utf-8") as fh:
            proc = subprocess.Popen(["make", "run"], cwd=clone, stdout=fh,
                                    stderr=subprocess.STDOUT, env={
                                        k: v for k, v in os.environ.items()
                                        if not k.startswith(("VIRTUAL_ENV", "BELTSTUDY_"))})
            while proc.poll() is None:
                time.sleep(5.0)
                loads.append(os.getloadavg()[0])
        rc = proc.returncode
    finally:
        for p in burners:
            p.kill()
    wall = time.perf_counter() - t0
    text = log.read_text(encoding="utf-8", errors="replace")
    shown = COMPILE_LINE in text
    tail = "\n".join(text.rstrip().splitlines()[-12:])
    print(f"make run: exit code {rc} after {wall / 60:.1f} min; load average (1 min) "
          f"{min(loads, default=0):.2f}-{max(loads, default=0):.2f} while it ran")
    print(f"compile line shown: {shown}")
    print("last lines of its output:\n" + tail)
    if args.keep:
        print(f"kept: {tmp}")
    else:
        subprocess.run(["pkill", "-f", f"{clone}/.venv/bin/beltstudy"], check=False)
        shutil.rmtree(tmp, ignore_errors=True)
    return 0 if rc == 0 and shown else 1


if __name__ == "__main__":
    sys.exit(main())
