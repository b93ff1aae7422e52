"""Study service against in-process loops: throughput and where a run's worker time goes.

Three studies, all on ``studies/conveyors/slope-5pct.yaml`` (the 2 km, 5 % slope):

* **steady**: 1000 runs (din, cema x 250 temperatures x full, empty), steady tensions only;
* **dynamic**: 100 runs, 600 elements, s-curve start 60 s, 30 s running, controlled stop
  (din, cema x 5 temperatures x 5 loads x 2 stop times);
* **study288**: 288 runs, 202 elements, s-curve start 40 s, 20 s running, controlled stop
  (din, cema, nonlin x 4 temperatures x 4 stop times x full, empty, 0.5 x ST2000, ST2500).

Each is timed in one benchmark run, so the ratios compare figures of the same machine state:

* **service**: ``beltstudy serve`` in a child process (LocalCluster, one worker process per
  core, warmed before timing: the workers by the service, the API and the study path by one
  tiny dynamic study), the study POSTed over HTTP and polled every second until it is done;
  the time runs from the POST to the study's ``finished_at``, so it includes validation and
  the design basis, batching, Dask, result transfer and every Parquet write (the first poll
  that sees it done is printed beside it). The 288-run study goes through twice: as it is
  (surfaces recomputed on demand) and with ``surface: true``.
* **beltstudy run** (study288 only): the command in a child process with its own data
  directory, after the service has stopped; its rate is the study's own ``elapsed_s`` (from
  the first task to the last row; the command's wall time, with Dask start-up and warm-up,
  is printed beside it).
* **loop**: the same runs (same resolved inputs) one after another in one process:
  ``run_one(parse_conveyor(...), parse_scenario(...), ...)``, after one warm-up run per model;
  nothing is stored. Two workers can at best run two such loops: the ideal two-loop rate is
  2 x the loop's. The loops run at the CPU niceness of the LocalCluster's workers (10), so
  other load on the machine slows both alike. The study is also run as two loops at once in
  two processes (what the two cores give two copies of the engine).

study288 runs in rounds (``--rounds``, default 3) of: the loop in one process, a fresh
service with the study (and with ``surface: true``), ``beltstudy run``, the loops at once;
interleaved, so each meets the machine's other load alike, and the best round of each is
compared (every round is printed).

For study288 it then splits a run's time (statics, build and fresh state, kernel, decode, the rest
of ``run_one``, measured in this process; the Arrow tables and Parquet writes of
:func:`beltstudy.service.dask.tasks.run_batch`) and the service study's worker time (the workers' own split,
summed by the service into ``study.json`` as ``worker_s``, and the time outside tasks: Dask
round trips, waiting, start and tail), and the CPU time per run of the loop, of the service's
workers and of the service process. Figures are printed, never asserted (see BENCHMARKS.md).

``--against REV`` (study288) also runs the study through revision REV's ``beltstudy run``
(installed once into its own virtual environment, as ``bench_kernel_against.py`` does),
alternating with this version's in every round, and prints the ratio of the rates (issue 29:
``--against 187e89f``, engine 0.4.1).

    .venv/bin/python benchmarks/bench_study.py [--workers N] [--only steady|dynamic|study288]
        [--rounds N] [--against REV]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
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
#: The 288-run dynamic study of the 2 km conveyor: its own belt and one stronger one.
STUDY288 = {
    "name": "bench-dynamic-288",
    "conveyor": "conveyors/slope-5pct.yaml",
    "scenario": {
        "elements": 202,
        "start": {"control": "s-curve", "time_s": 40},
        "run_s": 20,
        "stop": {"mode": "controlled", "time_s": 20},
    },
    "grid": {
        "friction_model": ["din", "cema", "nonlin"],
        "temperature_c": [-20, 0, 20, 40],
        "stop_time_s": [10, 20, 30, 40],
        "load": ["full", "empty", 0.5],
        "belt_type": ["ST2000", "ST2500"],
    },
    "dynamics": True,
}

#: Status polling interval [s], as the study page and ``beltstudy submit --wait`` poll (each
#: poll costs a few ms of CPU on the shared cores; the times come from ``finished_at``).
POLL_S = 1.0


def _one(spec):
    from beltstudy.engine.conveyor import parse_conveyor, parse_scenario
    from beltstudy.engine.run import run_one

    return run_one(
        parse_conveyor(spec.conveyor),
        parse_scenario(spec.scenario),
        model=spec.model,
        params=spec.params or None,
        dynamics=spec.dynamics,
    )


def _warm(study) -> None:
    """One run per friction model: imports and numba compile, like the service's workers."""
    seen = set()
    for spec in study.runs:
        if spec.model not in seen:
            seen.add(spec.model)
            _one(spec)


def plain_loop(study) -> tuple[float, dict, float]:
    """Wall time of the study's runs one after another in this process [s], the times of
    the runs of each friction model [s], and the CPU time of the loop [s]."""
    _warm(study)
    per_model: dict[str, list[float]] = defaultdict(list)
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    for spec in study.runs:
        t1 = time.perf_counter()
        _one(spec)
        per_model[spec.model].append(time.perf_counter() - t1)
    wall = time.perf_counter() - t0
    return wall, dict(per_model), time.process_time() - cpu0


def _loop_child(body: dict, part: int, parts: int, nice: int, ready, go, out) -> None:
    from beltstudy.service.door.studyfile import resolve_study

    os.setpriority(os.PRIO_PROCESS, 0, max(nice, os.getpriority(os.PRIO_PROCESS, 0)))
    study = resolve_study(body, studies_dir=ROOT / "studies")
    _warm(study)
    mine = study.runs[part::parts]
    ready.put(part)
    go.wait()
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    for spec in mine:
        _one(spec)
    out.put((part, len(mine), time.perf_counter() - t0, time.process_time() - cpu0))


def loops_at_once(body: dict, parts: int, nice: int) -> tuple[float, float]:
    """The study's runs split between ``parts`` processes running at the same time (every
    ``parts``-th run each, all warmed first): runs / the slowest process's wall time, and
    the CPU time per run [s]."""
    import multiprocessing as mp

    ctx = mp.get_context("spawn")
    ready, out, go = ctx.Queue(), ctx.Queue(), ctx.Event()
    procs = [ctx.Process(target=_loop_child, args=(body, i, parts, nice, ready, go, out))
             for i in range(parts)]
    for p in procs:
        p.start()
    for _ in procs:
        ready.get(timeout=600)
    go.set()
    results = [out.get(timeout=3600) for _ in procs]
    for p in procs:
        p.join()
    n = sum(r[1] for r in results)
    return n / max(r[2] for r in results), sum(r[3] for r in results) / n


class _Timers:
    """Wraps module functions for one pass and sums their wall time by label."""

    def __init__(self):
        self.seconds: dict[str, float] = defaultdict(float)
        self._undo: list = []

    def wrap(self, module, name: str, label: str) -> None:
        original = getattr(module, name)
        seconds = self.seconds

        def timed(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return original(*args, **kwargs)
            finally:
                seconds[label] += time.perf_counter() - t0

        setattr(module, name, timed)
        self._undo.append((module, name, original))

    def restore(self) -> None:
        for module, name, original in reversed(self._undo):
            setattr(module, name, original)
        self._undo.clear()


def engine_split(study) -> dict[str, float]:
    """Mean seconds per run of the stages of ``run_one`` over the study, in this process:
    parse, statics (steady solve and the design sizes), build and fresh state, kernel, decode,
    and the rest of run_one."""
    import importlib

    import beltstudy.engine.conveyor as conveyor_mod
    import beltstudy.engine.run as er

    sim = importlib.import_module("beltstudy.engine.dynamics.simulate")  # the package exports a function

    timers = _Timers()
    timers.wrap(er, "solve_steady", "statics")
    timers.wrap(er, "auto_sizes", "statics")
    timers.wrap(er, "build_system", "build")
    timers.wrap(sim, "fresh_run", "build")
    timers.wrap(sim, "decode", "decode")
    timers.wrap(conveyor_mod, "parse_conveyor", "parse")
    timers.wrap(conveyor_mod, "parse_scenario", "parse")
    kernel = 0.0
    t0 = time.perf_counter()
    try:
        from beltstudy.engine.conveyor import parse_conveyor, parse_scenario

        for spec in study.runs:
            result = er.run_one(
                parse_conveyor(spec.conveyor),
                parse_scenario(spec.scenario),
                model=spec.model,
                params=spec.params or None,
                dynamics=spec.dynamics,
            )
            if result.transient is not None:
                kernel += float(result.transient.raw["wall_s"])
    finally:
        timers.restore()
    total = time.perf_counter() - t0
    n = len(study.runs)
    out = {k: v / n for k, v in timers.seconds.items()}
    out["kernel"] = kernel / n
    out["decode"] = out.get("decode", 0.0)
    out["run_one other"] = total / n - sum(out.values())
    out["run_one"] = total / n
    return out


def worker_split(study, surface: bool) -> dict[str, float]:
    """Mean seconds per run of :func:`beltstudy.service.dask.tasks.run_batch` writing into a scratch study
    (batches of about the service's size), and what it reports of its own split."""
    from beltstudy.service.dask.tasks import run_batch
    from beltstudy.service.store.parquet import Store

    specs = study.runs
    total = 0.0
    split: dict[str, float] = defaultdict(float)
    with tempfile.TemporaryDirectory(prefix="bench-split-") as tmp:
        store = Store(tmp)
        store.create(study.id, {"id": study.id, "store_token": "bench"})
        sink = {"dir": str(store.study_dir(study.id)), "token": "bench"}
        size = 32
        for i in range(0, len(specs), size):
            batch = specs[i : i + size]
            t0 = time.perf_counter()
            out = run_batch(study.id, batch, surface, {**sink, "key": f"{i:06d}"})
            total += time.perf_counter() - t0
            for k, v in (out.get("split") or {}).items():
                split[k] += v
    n = len(specs)
    res = {"run_batch": total / n}
    res.update({k: v / n for k, v in split.items()})
    return res


def around_kernel(study, repeats: int = 20) -> dict[str, dict[str, float]]:
    """What surrounds the kernel in a run and its storing, per friction model (the study's
    first run of each), as the least CPU time over ``repeats`` [s]: the least is what the
    code costs, whatever else the machine does. ``kernel``: one call; ``decode``: kernel
    outputs to the summary and arrays; ``timeseries`` and ``surface``: the worker's Arrow
    tables; ``write timeseries`` and ``write surface``: a part of 32 runs of the model, per
    run."""
    import importlib

    import pyarrow as pa

    from beltstudy.engine.conveyor import parse_conveyor, parse_scenario
    from beltstudy.engine.dynamics import DynamicsOptions, build_system
    from beltstudy.engine.run import run_one, transient_safety_min
    from beltstudy.engine.statics import solve_steady
    from beltstudy.service.dask.tasks import surface_table, timeseries_table
    from beltstudy.service.store.parquet import _write_parquet

    sim = importlib.import_module("beltstudy.engine.dynamics.simulate")

    def least(fn, n=repeats) -> float:
        best = float("inf")
        for _ in range(n):
            c0 = time.process_time()
            fn()
            best = min(best, time.process_time() - c0)
        return best

    # parts of 32 different runs of the model, as a task writes them
    parts: dict[str, list] = defaultdict(list)
    for spec in study.runs:
        if len(parts[spec.model]) < 32:
            result = _one(spec)
            parts[spec.model].append((timeseries_table(spec.run_id, result),
                                      surface_table(spec.run_id, result)))
    out: dict[str, dict[str, float]] = {}
    with tempfile.TemporaryDirectory(prefix="bench-around-") as tmp:
        for spec in study.runs:
            if spec.model in out:
                continue
            conv, scn = parse_conveyor(spec.conveyor), parse_scenario(spec.scenario)
            n = None if scn.elements == "auto" else int(scn.elements)
            steady = solve_steady(conv, model=spec.model, params=spec.params or None,
                                  temperature_c=scn.temperature_c, load=scn.load, n_elements=n)
            system = build_system(conv, scn, steady, DynamicsOptions())
            ki = sim.fresh_run(system)
            ki.call()
            kw = {"steady_summary": steady.summary, "conveyor": conv,
                  "safety_factor_min": transient_safety_min(conv, steady.loop.belt.kind)}
            result = run_one(conv, scn, model=spec.model, params=spec.params or None)
            path = Path(tmp) / "part.parquet"
            ts = pa.concat_tables([t for t, _ in parts[spec.model]])
            sf = pa.concat_tables([t for _, t in parts[spec.model]])
            k = len(parts[spec.model])
            out[spec.model] = {
                "kernel": least(ki.call, 5),
                "decode": least(lambda: sim.decode(system, ki, 0.0, **kw)),  # noqa: B023
                "timeseries": least(lambda: timeseries_table(spec.run_id, result)),  # noqa: B023
                "surface": least(lambda: surface_table(spec.run_id, result)),  # noqa: B023
                "write timeseries": least(lambda: _write_parquet(path, ts), 5) / k,  # noqa: B023
                "write surface": least(lambda: _write_parquet(path, sf), 5) / k,  # noqa: B023
            }
    return out


class Service:
    """``beltstudy serve`` in a child process (LocalCluster), warmed: its workers by the
    service itself, its API and study path by one tiny dynamic study before any timing."""

    def __init__(self, workers: int, data_dir: str):
        from beltstudy.service.cli.client import ServiceClient
        from beltstudy.service.cli.demo import free_port, start_server, wait_ready

        port = free_port()
        env = {
            "BELTSTUDY_DATA_DIR": data_dir,
            "BELTSTUDY_WORKERS": str(workers),
            "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"),
            "BELTSTUDY_SCHEDULER": "",
            "BELTSTUDY_TOKEN": "",
        }
        self.data_dir = Path(data_dir)
        self.proc = start_server(port, env=env)
        self.client = ServiceClient(f"http://127.0.0.1:{port}", timeout=120)
        t0 = time.perf_counter()
        wait_ready(self.client, self.proc)
        self.ready_s = time.perf_counter() - t0
        from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO

        self.run({"name": "bench-warm-up", "conveyor": TINY_CONVEYOR, "scenario": TINY_SCENARIO,
                  "grid": {"friction_model": ["din", "cema"]}, "dynamics": True})

    def _cpu(self) -> tuple[float, float]:
        """CPU time [s] of the service process and of its worker processes."""
        import psutil

        server = psutil.Process(self.proc.pid)
        workers = 0.0
        for child in server.children(recursive=True):
            try:
                workers += sum(child.cpu_times()[:2])
            except psutil.Error:
                pass
        return sum(server.cpu_times()[:2]), workers

    def run(self, body: dict) -> dict:
        """POST ``body`` and poll every ``POLL_S`` until the study ends. ``wall``: from the POST to
        the study's ``finished_at`` (the service's clock, this machine's); ``poll_wall``: to
        the first poll that saw it; the CPU time of the service process and of the workers
        meanwhile; the study's ``study.json``."""
        svc0, wrk0 = self._cpu()
        t_post = time.time()
        t0 = time.perf_counter()
        st, created = self.client.submit(body)
        if not created:
            raise SystemExit(f"study {st['id']} already in the store: use a fresh data directory")
        while st["state"] in ("queued", "running"):
            time.sleep(POLL_S)
            st = self.client.status(st["id"])
        poll_wall = time.perf_counter() - t0
        svc1, wrk1 = self._cpu()
        doc = json.loads((self.data_dir / "studies" / st["id"] / "study.json").read_text())
        return {"wall": doc["finished_at"] - t_post, "poll_wall": poll_wall, "status": st,
                "service_cpu": svc1 - svc0, "worker_cpu": wrk1 - wrk0, "doc": doc}

    def stop(self) -> None:
        from beltstudy.service.cli.demo import stop_server

        self.client.close()
        stop_server(self.proc)


def through_run_command(body: dict, workers: int, python: str | None = None) -> dict:
    """``beltstudy run`` on the study in a child process with its own data directory: the
    command's wall time, the study's ``elapsed_s`` and its ``study.json``. ``python``: the
    interpreter of another installed version (``--against``; this one's by default)."""
    with tempfile.TemporaryDirectory(prefix="bench-run-") as tmp:
        study = dict(body, conveyor=str(ROOT / "studies" / body["conveyor"]))
        path = Path(tmp) / "study.json"
        path.write_text(json.dumps(study), encoding="utf-8")
        env = {
            **os.environ,
            "BELTSTUDY_DATA_DIR": str(Path(tmp) / "data"),
            "BELTSTUDY_WORKERS": str(workers),
            "BELTSTUDY_SCHEDULER": "",
        }
        t0 = time.perf_counter()
        proc = subprocess.run(
            [python or sys.executable, "-m", "beltstudy.service.cli", "run", str(path)],
            env=env, capture_output=True, text=True, check=False, cwd=tmp,
        )
        wall = time.perf_counter() - t0
        if proc.returncode != 0:
            raise SystemExit(f"beltstudy run failed ({proc.returncode}): {proc.stderr[-2000:]}")
        docs = list((Path(tmp) / "data" / "studies").glob("*/study.json"))
        doc = json.loads(docs[0].read_text(encoding="utf-8"))
        return {"command_wall": wall, "wall": float(doc["elapsed_s"]), "doc": doc}


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.machine()


def _ms(x: float) -> str:
    return f"{x * 1e3:6.2f} ms"


def _best(items: list[dict]) -> dict:
    """The round with the shortest wall time (the least disturbed by other load)."""
    return min(items, key=lambda r: r["wall"])


def report_around(around: dict[str, dict[str, float]]) -> None:
    keys = list(next(iter(around.values())))
    print("  around the kernel, least CPU per run [ms] (first run of each model):")
    print("    " + f"{'':<8}" + "".join(f"{k:>18}" for k in keys))
    for model, row in around.items():
        print("    " + f"{model:<8}" + "".join(f"{row[k] * 1e3:18.3f}" for k in keys))


#: Issue 16's throughput target for study288 on this machine [runs/s].
TARGET_RUNS_S = 80.0


def report_study288(n, workers, rounds: dict, per_model, split, wsplit) -> None:
    """``rounds``: per round the loop in one process and at once in ``workers`` processes
    ((rate, CPU per run)), the service study, the ``surface: true`` study and ``beltstudy
    run``; the best round of each is compared (every round is listed)."""
    loop_rate, loop_cpu = max(rounds["loop"])
    ideal = workers * loop_rate
    print(f"study288: {n} runs, {workers} workers, best of {len(rounds['loop'])} rounds "
          f"(every round in brackets)")
    print("  in-process run_one per model, median (mean): " + "  ".join(
        f"{m} {_ms(statistics.median(t))} ({_ms(statistics.fmean(t)).strip()})"
        for m, t in per_model.items()))
    if "nonlin" in per_model and "din" in per_model:
        print(f"  median Non-Lin run over DIN's: "
              f"{statistics.median(per_model['nonlin']) / statistics.median(per_model['din']):.2f}")
    print(f"  loop (one process)                {loop_rate:6.1f} runs/s  (CPU {_ms(loop_cpu)}/run)"
          f"  [{', '.join(f'{r:.1f}' for r, _ in rounds['loop'])}]")
    print(f"  ideal: {workers} x loop                  {ideal:6.1f} runs/s")
    at_once = at_once_cpu = None
    if rounds.get("at_once"):
        at_once, at_once_cpu = max(rounds["at_once"])
        print(f"  {workers} loops at once ({workers} processes) {at_once:6.1f} runs/s  "
              f"= {at_once / ideal:.2f} x ideal  (CPU {_ms(at_once_cpu)}/run)  "
              f"[{', '.join(f'{r:.1f}' for r, _ in rounds['at_once'])}]")

    def line(label: str, items: list[dict], extra: str = "") -> None:
        best = _best(items)
        rate = n / best["wall"]
        text = (f"  {label:<24}{best['wall']:6.2f} s  {rate:6.1f} runs/s  "
                f"/ ideal = {rate / ideal:.2f}")
        if at_once is not None:
            text += f"  / {workers} loops at once = {rate / at_once:.2f}"
        every = ", ".join(f"{n / r['wall']:.1f}" for r in items)
        print(text + extra + f"  [{every}]")

    svc = _best(rounds["service"])
    line("service", rounds["service"])
    if rounds.get("surface"):
        line("service, surface: true", rounds["surface"])
    if rounds.get("run"):
        line("beltstudy run", rounds["run"], f"  (command wall "
             f"{_best(rounds['run'])['command_wall']:.1f} s with Dask start-up)")
    if rounds.get("against"):
        label = f"beltstudy run, {rounds['against_rev']}"
        line(label, rounds["against"], f"  (command wall "
             f"{_best(rounds['against'])['command_wall']:.1f} s with Dask start-up)")
        this, other = _best(rounds["run"])["wall"], _best(rounds["against"])["wall"]
        print(f"  this version / {rounds['against_rev']}: {other / this:.2f} x the runs/s "
              f"(best round of each; per round: " + ", ".join(
                  f"{b['wall'] / a['wall']:.2f}" for a, b in zip(rounds["run"],
                                                                  rounds["against"], strict=False)) + ")")
    if any(r["status"]["failed"] for r in rounds["service"]):
        print(f"  failed runs: {[r['status']['failed'] for r in rounds['service']]}")

    print("  a run in one process (mean over the study):")
    for key in ("parse", "statics", "build", "kernel", "decode", "run_one other"):
        value = split.get(key, 0.0)
        print(f"    {key:<24}{_ms(value)}  {value / split['run_one'] * 100:5.1f} %")
    print(f"    {'run_one (with parse)':<24}{_ms(split['run_one'])}")
    kernel = split.get("kernel", 0.0)
    if kernel > 0:
        print(f"  the kernel alone bounds the study: {workers} workers / {_ms(kernel).strip()} "
              f"= {workers / kernel:.1f} runs/s at most with nothing around the runs "
              f"({TARGET_RUNS_S:g} runs/s needs a mean kernel of {_ms(workers / TARGET_RUNS_S).strip()}"
              " at most)")
    print(f"  the worker in one process (run_batch, batches of 32, parts written): "
          f"{_ms(wsplit['run_batch'])}/run: runs {_ms(wsplit.get('run_s', 0))}, tables "
          f"{_ms(wsplit.get('tables_s', 0))}, writes {_ms(wsplit.get('write_s', 0))}")

    acc = svc["doc"].get("worker_s") or {}
    if not acc:
        return
    core = workers * svc["wall"] / n
    task = acc.get("task_s", 0.0) / n
    runs_ms = acc.get("run_s", 0.0) / n
    print(f"  the best service study per run: {workers} workers x wall = {_ms(core)} "
          f"({acc.get('tasks', 0)} tasks)")
    rows = [("runs (run_one)", runs_ms)]
    rows += [(f"  {key}", runs_ms * split.get(key, 0.0) / split["run_one"])
             for key in ("statics", "build", "kernel", "decode")]
    rows += [("tables (Arrow)", acc.get("tables_s", 0.0) / n),
             ("writes (Parquet parts)", acc.get("write_s", 0.0) / n),
             ("Dask and waiting (outside tasks)", core - task)]
    for label, value in rows:
        print(f"    {label:<34}{_ms(value)}  {value / core * 100:5.1f} %")
    task_cpu = acc.get("cpu_s", 0.0) / n
    cpu = (svc["service_cpu"] + svc["worker_cpu"]) / n
    print(f"  CPU per run: the loop {_ms(loop_cpu)}; the service's workers "
          f"{_ms(svc['worker_cpu'] / n)} (tasks {_ms(task_cpu)}, Dask "
          f"{_ms(svc['worker_cpu'] / n - task_cpu)}), the service process "
          f"{_ms(svc['service_cpu'] / n)}: together {cpu / loop_cpu:.2f} x the loop's"
          + ("" if at_once_cpu is None else
             f", {cpu / at_once_cpu:.2f} x {workers} loops at once"))


def study288_rounds(args, nice: int) -> dict:
    """``args.rounds`` rounds of: the loop in one process, the study through a fresh service
    (and with ``surface: true``), ``beltstudy run``, the loops at once; interleaved, so each
    meets the machine's other load alike."""
    rounds: dict[str, list] = defaultdict(list)
    rounds["against_rev"] = args.against
    for r in range(args.rounds):
        rounds["loop"].append(loops_at_once(STUDY288, 1, nice))
        with tempfile.TemporaryDirectory(prefix="bench-study288-") as tmp:
            service = Service(args.workers, tmp)
            try:
                rounds["service"].append(service.run(STUDY288))
                if not args.no_surface:
                    body = dict(STUDY288, name="bench-dynamic-288-surface", surface=True)
                    rounds["surface"].append(service.run(body))
            finally:
                service.stop()
        if args.against:
            # this version and the other one's ``beltstudy run``, the order swapped each round
            pair = [("run", None), ("against", args.against_python)]
            for key, python in pair if r % 2 == 0 else pair[::-1]:
                rounds[key].append(through_run_command(STUDY288, args.workers, python))
        elif not args.no_run_command:
            rounds["run"].append(through_run_command(STUDY288, args.workers))
        if not args.no_at_once:
            rounds["at_once"].append(loops_at_once(STUDY288, args.workers, nice))
        print(f"  study288 round {r + 1}: loop {rounds['loop'][-1][0]:.1f} runs/s, service "
              f"{288 / rounds['service'][-1]['wall']:.1f} runs/s", flush=True)
    return rounds


def main() -> int:
    from beltstudy.service.dask.executor import LOCAL_WORKER_NICE
    from beltstudy.service.door.studyfile import resolve_study

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--only", choices=("steady", "dynamic", "study288"))
    ap.add_argument("--no-run-command", action="store_true",
                    help="skip beltstudy run (study288)")
    ap.add_argument("--no-surface", action="store_true",
                    help="skip the surface: true pass of study288")
    ap.add_argument("--no-at-once", action="store_true",
                    help="skip the loops run at once in several processes (study288)")
    ap.add_argument("--against", metavar="REV",
                    help="study288 also through REV's beltstudy run (installed side by side, "
                    "as bench_kernel_against.py does), alternating with this version's")
    ap.add_argument("--rounds", type=int, default=3,
                    help="rounds of study288 (loop, service, beltstudy run, loops at once)")
    ap.add_argument("--loop-nice", type=int, default=LOCAL_WORKER_NICE,
                    help="CPU niceness of the in-process loops (default: the LocalCluster "
                    "workers', so both meet other load on the machine alike)")
    args = ap.parse_args()
    if args.against:
        from bench_kernel_against import interpreter

        args.against_python = str(interpreter(args.against))
    cases = [("steady", STEADY), ("dynamic", DYNAMIC), ("study288", STUDY288)]
    if args.only:
        cases = [c for c in cases if c[0] == args.only]

    print(
        f"# bench_study  {time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC  "
        f"{platform.node()}  {_cpu_model()}  cores={os.cpu_count()}  "
        f"python {platform.python_version()}  workers={args.workers}  "
        f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}"
    )
    studies = {label: resolve_study(body, studies_dir=ROOT / "studies") for label, body in cases}
    nice = max(args.loop_nice, os.getpriority(os.PRIO_PROCESS, 0))
    print(f"loops at nice {nice} (the LocalCluster workers run at nice {LOCAL_WORKER_NICE})")
    others = [(label, body) for label, body in cases if label != "study288"]
    results: dict[str, dict] = {}
    if others:
        with tempfile.TemporaryDirectory(prefix="bench-study-") as tmp:
            service = Service(args.workers, tmp)
            try:
                print(f"service ready (workers started and warmed) in {service.ready_s:.1f} s")
                for label, body in others:
                    results[label] = service.run(body)
            finally:
                service.stop()
    rounds = study288_rounds(args, nice) if "study288" in studies else None
    # the loops of the other studies, and the splits, run last with no service running, at
    # the workers' CPU priority
    os.setpriority(os.PRIO_PROCESS, 0, nice)
    for label, _ in others:
        study = studies[label]
        n = study.total
        svc = results[label]
        t_loop, t_service = plain_loop(study)[0], svc["wall"]
        speedup = t_loop / t_service
        overhead_ms = (t_service - t_loop / args.workers) / n * 1e3
        print(
            f"{label:>7}: {n:5d} runs  loop {t_loop:7.2f} s ({t_loop / n * 1e3:7.2f} "
            f"ms/run)  service {t_service:7.2f} s  speed-up {speedup:4.2f}x  "
            f"overhead {overhead_ms:6.2f} ms/run  service-process CPU "
            f"{svc['service_cpu'] / n * 1e3:5.2f} ms/run  ({svc['status']['failed']} failed)"
        )
    if rounds is not None:
        study = studies["study288"]
        _, per_model, _ = plain_loop(study)
        split = engine_split(study)
        wsplit = worker_split(study, surface=False)
        report_study288(study.total, args.workers, rounds, per_model, split, wsplit)
        report_around(around_kernel(study))
    print(f"# load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
