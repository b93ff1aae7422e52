"""Study submission benchmark: resolving a 20 000-run study (the service's largest).

Times ``resolve_study`` (validation, expansion of every grid point, design basis, run ids) of a
study with one conveyor axis of 20 000 values on the 2 km example, best of several repeats,
and, in the same run, the same with each grid point's conveyor built as a deep copy of the
whole conveyor (``copy.deepcopy`` then set, the expansion before paths were copied on write),
and prints the ratio. Both must give the same study id (checked).

Then, over HTTP against a live ``beltstudy serve`` (no Dask scheduler reachable, so studies
are accepted and stored but never run: the door alone is measured): the time to accept a
20 000-run study, the time to answer its resend, and the longest ``/health`` answer while five
different 20 000-run studies are submitted at once.

Run: ``.venv/bin/python benchmarks/bench_submit.py [--repeats N] [--no-http]``.
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
    ap.add_argument("--no-http", dest="http", action="store_false",
                    help="skip the measurements against a live service")
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
    if args.http:
        http_bench()


def _post(url: str, body: dict) -> tuple[float, int, dict]:
    import httpx

    t0 = time.perf_counter()
    r = httpx.post(f"{url}/studies", json=body, timeout=600)
    return time.perf_counter() - t0, r.status_code, r.json()


def http_bench() -> None:
    """Accept, resend and /health under five submissions at once, against a live service."""
    import tempfile
    import threading

    import httpx

    from beltstudy.service.cli.demo import free_port, start_server, stop_server
    from beltstudy.service.door.studyfile import study_body

    with tempfile.TemporaryDirectory() as tmp:
        port = free_port()
        url = f"http://127.0.0.1:{port}"
        env = {"BELTSTUDY_DATA_DIR": tmp, "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"),
               "BELTSTUDY_WARM_START": "false", "BELTSTUDY_TOKEN": "",
               "BELTSTUDY_SCHEDULER": "tcp://127.0.0.1:9",  # nothing there: nothing runs
               "BELTSTUDY_DASK_TIMEOUT_S": "1"}
        proc = start_server(port, env=env)
        try:
            t0 = time.monotonic()
            while True:
                try:
                    httpx.get(f"{url}/health", timeout=2).raise_for_status()
                    break
                except httpx.HTTPError:
                    if time.monotonic() - t0 > 120:
                        raise
                    time.sleep(0.2)
            base = {**STUDY, "conveyor": study_body_conveyor(study_body)}
            t_accept, code, st = _post(url, base)
            assert code == 202 and st["total"] == 20_000, (code, st)
            resends = [_post(url, base) for _ in range(5)]
            assert all(c == 200 for _, c, _ in resends)
            t_resend = min(t for t, _, _ in resends)
            print(f"  HTTP accept of a new 20 000-run study  {t_accept:6.2f} s")
            print(f"  HTTP resend of it (best of 5)          {t_resend * 1e3:6.1f} ms "
                  f"(worst {max(t for t, _, _ in resends) * 1e3:.1f} ms)")
            health, stop = [], threading.Event()

            def poll():
                while not stop.is_set():
                    t = time.perf_counter()
                    httpx.get(f"{url}/health", timeout=60)
                    health.append(time.perf_counter() - t)
                    time.sleep(0.05)

            poller = threading.Thread(target=poll)
            poller.start()
            times: list[tuple[float, int]] = []
            posts = [threading.Thread(target=lambda k=k: times.append(
                _post(url, {**base, "name": f"bench-submit-{k}"})[:2])) for k in range(5)]
            t0 = time.perf_counter()
            for t in posts:
                t.start()
            for t in posts:
                t.join()
            wall = time.perf_counter() - t0
            stop.set()
            poller.join()
            codes = sorted(c for _, c in times)
            print(f"  five new 20 000-run studies at once    {wall:6.2f} s wall, each "
                  f"{min(t for t, _ in times):.2f}-{max(t for t, _ in times):.2f} s, "
                  f"answers {codes}")
            print(f"  /health during them: {len(health)} answers, longest "
                  f"{max(health) * 1e3:.0f} ms, median "
                  f"{sorted(health)[len(health) // 2] * 1e3:.0f} ms")
        finally:
            stop_server(proc)


def study_body_conveyor(study_body) -> dict:
    """The benchmark study's conveyor file as a mapping (the body then needs no files)."""
    import json
    import tempfile

    with tempfile.NamedTemporaryFile("w", suffix=".json", dir=ROOT / "studies",
                                     delete=True) as f:
        json.dump({**STUDY}, f)
        f.flush()
        return study_body(f.name)["conveyor"]


if __name__ == "__main__":
    main()
