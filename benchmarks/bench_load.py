"""The study service under load: 50 concurrent clients reading status and runs during a study.

``beltstudy serve`` runs in a child process (LocalCluster, one worker process per core, warmed
first). A dynamic study is submitted; while it runs, 50 clients, each on its own connection,
alternate ``GET /studies/{id}`` and ``GET /studies/{id}/runs`` (JSON, every stored row) for a
fixed number of rounds. Printed: the machine, the requests and errors (transport errors and
non-2xx answers), latency percentiles per route, throughput, and how far the study got
meanwhile. Figures are printed, never asserted (see BENCHMARKS.md).

    .venv/bin/python benchmarks/bench_load.py [--clients 50] [--rounds 20]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

STUDY = {
    "name": "bench-load",
    "conveyor": "conveyors/slope-5pct.yaml",
    "scenario": {"elements": 600, "start": {"control": "s-curve", "time_s": 60}, "run_s": 30,
                 "stop": {"mode": "controlled", "time_s": 30}, "record_dt_s": 0.25},
    "grid": {"friction_model": ["din", "cema"],
             "temperature_c": {"start": -30, "stop": 30, "step": 5},
             "load": ["full", "empty", 0.5, 0.75, 0.25]},
    "dynamics": True,
}


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.machine()


def _pct(values: list[float], q: float) -> float:
    values = sorted(values)
    if not values:
        return float("nan")
    k = min(len(values) - 1, max(0, int(round(q / 100 * (len(values) - 1)))))
    return values[k]


async def _client(http, sid: str, rounds: int, out: dict, errors: list) -> None:
    for i in range(rounds):
        route, path = (("status", f"/studies/{sid}") if i % 2 == 0
                       else ("runs", f"/studies/{sid}/runs"))
        t0 = time.perf_counter()
        try:
            r = await http.get(path)
            ok = r.status_code < 400
            if not ok:
                errors.append(f"{route}: HTTP {r.status_code} {r.text[:120]}")
        except Exception as exc:  # transport errors count as errors
            ok = False
            errors.append(f"{route}: {type(exc).__name__}: {exc}")
        if ok:
            out[route].append(time.perf_counter() - t0)


async def _load(url: str, sid: str, clients: int, rounds: int) -> tuple[dict, list, float]:
    import httpx

    out: dict[str, list[float]] = {"status": [], "runs": []}
    errors: list[str] = []
    limits = httpx.Limits(max_connections=clients, max_keepalive_connections=clients)
    async with httpx.AsyncClient(base_url=url, timeout=120, limits=limits) as http:
        t0 = time.perf_counter()
        await asyncio.gather(*(_client(http, sid, rounds, out, errors) for _ in range(clients)))
        wall = time.perf_counter() - t0
    return out, errors, wall


def _wait(client, sid: str, poll_s: float = 0.5) -> dict:
    while True:
        st = client.status(sid)
        if st["state"] not in ("queued", "running"):
            return st
        time.sleep(poll_s)


def main() -> int:
    from beltstudy.service.cli.client import ServiceClient
    from beltstudy.service.cli.demo import free_port, start_server, stop_server, wait_ready

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--clients", type=int, default=50)
    ap.add_argument("--rounds", type=int, default=20, help="requests per client")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args()
    print(
        f"# bench_load  {time.strftime('%Y-%m-%d %H:%M')}  {platform.node()}  {_cpu_model()}  "
        f"cores={os.cpu_count()}  python {platform.python_version()}  workers={args.workers}  "
        f"load average {os.getloadavg()[0]:.2f}"
    )
    with tempfile.TemporaryDirectory(prefix="bench-load-") as tmp:
        port = free_port()
        url = f"http://127.0.0.1:{port}"
        env = {"BELTSTUDY_DATA_DIR": tmp, "BELTSTUDY_WORKERS": str(args.workers),
               "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"), "BELTSTUDY_SCHEDULER": "",
               "BELTSTUDY_TOKEN": ""}
        proc = start_server(port, env=env)
        try:
            with ServiceClient(url, timeout=120) as client:
                wait_ready(client, proc)
                st, _ = client.submit(STUDY)
                sid = st["id"]
                while client.status(sid)["done"] < 1:  # rows to read from the start
                    time.sleep(0.1)
                before = client.status(sid)
                out, errors, wall = asyncio.run(_load(url, sid, args.clients, args.rounds))
                during = client.status(sid)
                st = _wait(client, sid)
        finally:
            stop_server(proc)
    n = sum(len(v) for v in out.values()) + len(errors)
    print(f"study: {st['total']} dynamic runs (slope-5pct, 600 elements), "
          f"{st['elapsed_s']:.1f} s compute time; {before['done']} -> {during['done']} runs "
          f"done while the clients ran (state then: {during['state']})")
    print(f"load: {args.clients} clients x {args.rounds} requests = {n} requests in "
          f"{wall:.1f} s ({n / wall:.0f} req/s), errors {len(errors)}")
    for route, lat in out.items():
        ms = [v * 1e3 for v in lat]
        print(f"  {route:>6}: n={len(ms):4d}  p50 {_pct(ms, 50):7.1f} ms  p95 {_pct(ms, 95):7.1f} "
              f"ms  p99 {_pct(ms, 99):7.1f} ms  max {max(ms, default=float('nan')):7.1f} ms  "
              f"mean {statistics.fmean(ms) if ms else float('nan'):7.1f} ms")
    for e in errors[:5]:
        print(f"  error: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
