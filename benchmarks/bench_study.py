"""Study service against a plain loop: a 1000-run steady study and a 100-run dynamic study.

Each study is timed twice:

* **service**: ``beltstudy serve`` in a child process (LocalCluster, one worker process per
  core, warmed before timing), the study POSTed over HTTP and polled every 0.2 s until it is
  done; the time runs from the POST to the first poll that sees ``done``, so it includes
  validation, batching, Dask, result transfer and the Parquet writes.
* **loop**: the same runs (same resolved inputs) one after another in this process:
  ``run_one(parse_conveyor(...), parse_scenario(...), ...)``, after one warm-up run.

Printed: both wall times, the speed-up (loop / service), and the service overhead per run,
``(service - loop / workers) / runs``: what the service costs beyond a perfect split of the
loop over the workers. Targets: speed-up >= 1.7 on 2 cores for the dynamic study, overhead
< 5 ms per steady run. Figures are printed, never asserted (see BENCHMARKS.md).

    .venv/bin/python benchmarks/bench_study.py [--workers N] [--only steady|dynamic]
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

STEADY = {
    "name": "bench-steady-1000",
    "conveyor": "conveyors/slope-5pct.yaml",
    "scenario": {"elements": "auto"},
    "grid": {
        "friction_model": ["din", "cema"],
        "temperature_c": {"start": -40.0, "stop": 39.68, "step": 0.32},
        "load": ["full", "empty"],
    },
    "dynamics": False,
}
DYNAMIC = {
    "name": "bench-dynamic-100",
    "conveyor": "conveyors/slope-5pct.yaml",
    "scenario": {
        "elements": 600,
        "start": {"control": "s-curve", "time_s": 60},
        "run_s": 30,
        "stop": {"mode": "controlled", "time_s": 30},
        "record_dt_s": 0.25,
    },
    "grid": {
        "friction_model": ["din", "cema"],
        "temperature_c": {"start": -30, "stop": 30, "step": 15},
        "load": ["full", "empty", 0.5, 0.75, 0.25],
        "stop_time_s": [20, 40],
    },
    "dynamics": True,
}


#: Status polling interval [s] (each poll costs a few ms of CPU on the shared cores).
POLL_S = 0.2


def plain_loop(study) -> float:
    """Wall time of the study's runs one after another in this process [s]."""
    from engine.conveyor import parse_conveyor, parse_scenario
    from engine.run import run_one

    def one(spec):
        return run_one(
            parse_conveyor(spec.conveyor),
            parse_scenario(spec.scenario),
            model=spec.model,
            params=spec.params or None,
            dynamics=spec.dynamics,
        )

    one(study.runs[0])  # warm: imports and numba compile, like the service's workers
    t0 = time.perf_counter()
    for spec in study.runs:
        one(spec)
    return time.perf_counter() - t0


def through_service(client, body: dict, server_pid: int) -> tuple[float, dict, float]:
    """Wall time from the POST to the first poll that sees the study done, the final status,
    and the CPU time the service process (API, scheduler, store writes) spent meanwhile."""
    import psutil

    server = psutil.Process(server_pid)
    cpu0 = sum(server.cpu_times()[:2])
    t0 = time.perf_counter()
    st, created = client.submit(body)
    if not created:
        raise SystemExit(f"study {st['id']} already in the store: use a fresh data directory")
    while st["state"] in ("queued", "running"):
        time.sleep(POLL_S)
        st = client.status(st["id"])
    return time.perf_counter() - t0, st, sum(server.cpu_times()[:2]) - cpu0


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.machine()


def main() -> int:
    from service.client import ServiceClient
    from service.demo import free_port, start_server, stop_server, wait_ready
    from service.study import resolve_study

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--only", choices=("steady", "dynamic"))
    args = ap.parse_args()
    cases = [("steady", STEADY), ("dynamic", DYNAMIC)]
    if args.only:
        cases = [c for c in cases if c[0] == args.only]

    print(
        f"# bench_study  {time.strftime('%Y-%m-%d %H:%M')}  {platform.node()}  "
        f"{_cpu_model()}  cores={os.cpu_count()}  python {platform.python_version()}  "
        f"workers={args.workers}  load average {os.getloadavg()[0]:.2f}"
    )
    with tempfile.TemporaryDirectory(prefix="bench-study-") as tmp:
        port = free_port()
        env = {
            "BELTSTUDY_DATA_DIR": tmp,
            "BELTSTUDY_WORKERS": str(args.workers),
            "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"),
            "BELTSTUDY_SCHEDULER": "",
            "BELTSTUDY_TOKEN": "",
        }
        proc = start_server(port, env=env)
        try:
            with ServiceClient(f"http://127.0.0.1:{port}", timeout=120) as client:
                t0 = time.perf_counter()
                wait_ready(client, proc)
                print(
                    f"service ready (workers started and warmed) in "
                    f"{time.perf_counter() - t0:.1f} s"
                )
                results = {}
                for label, body in cases:
                    study = resolve_study(body, studies_root=ROOT / "studies")
                    results[label] = (study.total, *through_service(client, body, proc.pid))
                # the plain loops run after the service studies, with the workers idle
                for label, body in cases:
                    study = resolve_study(body, studies_root=ROOT / "studies")
                    n, t_service, st, cpu = results[label]
                    t_loop = plain_loop(study)
                    speedup = t_loop / t_service
                    overhead_ms = (t_service - t_loop / args.workers) / n * 1e3
                    print(
                        f"{label:>7}: {n:5d} runs  loop {t_loop:7.2f} s ({t_loop / n * 1e3:7.2f} "
                        f"ms/run)  service {t_service:7.2f} s  speed-up {speedup:4.2f}x  "
                        f"overhead {overhead_ms:6.2f} ms/run  service-process CPU "
                        f"{cpu / n * 1e3:5.2f} ms/run  ({st['failed']} failed)"
                    )
        finally:
            stop_server(proc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
