"""The service under pressure, end to end: a real uvicorn server (child process) with a real
LocalCluster or an external ``dask scheduler``, results read back from Parquet with pandas.

Wall-clock bounds appear only where the acceptance sets them (an alias bomb refused in under
1 s; DELETE and SIGTERM with the scheduler gone within 10 s), with the server's own limits
well inside them.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import threading
import time

import httpx
import pandas as pd
import psutil
import pytest

from tests.service.conftest import LiveService
from tests.service.test_parse import ALIAS_BOMB

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def svc(tmp_path_factory):
    """One service (LocalCluster, two workers) for the tests that need nothing special."""
    tmp = tmp_path_factory.mktemp("hardening")
    service = LiveService(tmp / "data", tmp / "beltstudy.service.log")
    yield service
    service.stop()


def _tiny_dynamic(make_study, name: str) -> dict:
    return make_study(name=name, dynamics=True, grid={"friction_model": ["din", "cema"]})


def test_concurrent_identical_posts_make_one_study_and_one_row_per_run(svc, make_study):
    """10 identical POSTs at once, 20 times: one 202, nine 200s, one job, one row per run."""
    ids = []
    with httpx.Client(base_url=svc.url, timeout=60) as http:
        for rep in range(20):
            body = _tiny_dynamic(make_study, f"concurrent-{rep}")
            barrier = threading.Barrier(10)
            answers: list = [None] * 10

            def post(i, body=body, barrier=barrier, answers=answers):
                barrier.wait()
                answers[i] = http.post("/studies", json=body)

            threads = [threading.Thread(target=post, args=(i,)) for i in range(10)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            codes = sorted(r.status_code for r in answers)
            assert codes == [200] * 9 + [202], [r.text for r in answers]
            assert len({r.json()["id"] for r in answers}) == 1
            ids.append(answers[0].json()["id"])
    assert len(set(ids)) == 20
    for sid in ids:
        st = svc.wait(sid)
        assert st["state"] == "done" and st["done"] == st["total"] == 2, st
        root = svc.data_dir / "studies" / sid
        runs = pd.read_parquet(root / "runs")
        assert len(runs) == 2 and runs["run_id"].is_unique
        ts = pd.read_parquet(root / "timeseries")
        assert set(ts["run_id"]) == set(runs["run_id"])
        assert not ts.duplicated(["run_id", "t_s"]).any(), "a run's time series stored twice"
    listed = [s["id"] for s in svc.client.list()]
    assert len(listed) == len(set(listed))


def test_concurrent_deletes_of_a_running_study_give_one_200_the_others_409_or_404(
        svc, make_study):
    """2 to 5 DELETEs of one running study at once, 20 times: one 200, the others 409 (being
    deleted) or 404 (already gone); the study is gone after, the stored studies untouched."""
    keep = svc.client.submit(_tiny_dynamic(make_study, "kept-beside-deletes"))[0]["id"]
    assert svc.wait(keep)["state"] == "done"
    kept = pd.read_parquet(svc.data_dir / "studies" / keep / "runs")
    with httpx.Client(base_url=svc.url, timeout=60) as http:
        for rep in range(20):
            n = 2 + rep % 4
            body = make_study(name=f"deleted-{rep}", dynamics=True,
                              grid={"friction_model": ["din", "cema"],
                                    "temperature_c": list(range(-30, 31, 5))})
            sid = svc.client.submit(body)[0]["id"]
            barrier = threading.Barrier(n)
            answers: list = [None] * n

            def delete(i, sid=sid, barrier=barrier, answers=answers):
                barrier.wait()
                answers[i] = http.delete(f"/studies/{sid}")

            threads = [threading.Thread(target=delete, args=(i,)) for i in range(n)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            codes = sorted(r.status_code for r in answers)
            assert codes.count(200) == 1 and set(codes) <= {200, 404, 409}, \
                [r.text for r in answers]
            assert http.get(f"/studies/{sid}").status_code == 404
    assert [s["id"] for s in svc.client.list()].count(keep) == 1
    again = pd.read_parquet(svc.data_dir / "studies" / keep / "runs")
    pd.testing.assert_frame_equal(again, kept)


def test_reads_while_studies_are_deleted_are_never_a_500_and_the_list_never_a_404(
        svc, make_study):
    """Runs, run pages and the study list read without pause while each study is deleted, 10
    times: a study answers 200 or 404 (gone), the list always 200 (a read that had listed the
    files before they moved away was a 500; the list a 404)."""
    bad: list = []
    with httpx.Client(base_url=svc.url, timeout=60) as http:
        for rep in range(10):
            sid = svc.client.submit(make_study(name=f"read-while-deleted-{rep}"))[0]["id"]
            svc.wait(sid)
            rid = http.get(f"/studies/{sid}/runs", params={"limit": 1}).json()["runs"][0]["run_id"]
            paths = {"/studies": {200}}
            for path in (f"/studies/{sid}/runs", f"/studies/{sid}/runs?format=parquet",
                         f"/studies/{sid}/runs/{rid}", f"/studies/{sid}/runs/{rid}/profile",
                         f"/studies/{sid}/compare?baseline=din&candidate=cema"):
                paths[path] = {200, 404}
            stop = threading.Event()

            def read(path, ok, stop=stop):
                with httpx.Client(base_url=svc.url, timeout=60) as own:
                    while not stop.is_set():
                        r = own.get(path)
                        if r.status_code not in ok:
                            bad.append((path, r.status_code, r.text[:200]))

            threads = [threading.Thread(target=read, args=item) for item in paths.items()]
            for t in threads:
                t.start()
            time.sleep(0.3)
            assert http.delete(f"/studies/{sid}").status_code == 200
            time.sleep(0.2)
            stop.set()
            for t in threads:
                t.join()
    assert not bad, bad[:5]


def test_alias_bomb_is_refused_in_under_a_second_while_health_answers(svc):
    latencies: list[float] = []
    stop = threading.Event()

    def poll_health():
        with httpx.Client(base_url=svc.url, timeout=30) as http:
            while not stop.is_set():
                t0 = time.perf_counter()
                assert http.get("/health").status_code == 200
                latencies.append(time.perf_counter() - t0)

    poller = threading.Thread(target=poll_health)
    poller.start()
    try:
        with httpx.Client(base_url=svc.url, timeout=60) as http:
            for _ in range(10):
                t0 = time.perf_counter()
                r = http.post("/studies", content=ALIAS_BOMB.encode(),
                              headers={"Content-Type": "application/yaml"})
                elapsed = time.perf_counter() - t0
                assert r.status_code == 413, r.text
                assert r.json()["message"].startswith("grid.temperature_c.")
                assert elapsed < 1.0, f"the alias bomb took {elapsed:.2f} s"
                time.sleep(0.05)
    finally:
        stop.set()
        poller.join()
    assert latencies and max(latencies) < 1.0, max(latencies)


def _listening(pid: int) -> list[tuple[str, int]]:
    """Addresses the process and its children listen on."""
    out = []
    proc = psutil.Process(pid)
    for p in [proc, *proc.children(recursive=True)]:
        try:
            conns = p.net_connections(kind="inet")
        except psutil.Error:
            continue
        out += [(c.laddr.ip, c.laddr.port) for c in conns if c.status == psutil.CONN_LISTEN]
    return out


def _outside_address() -> str | None:
    """An IPv4 address of this machine that is not loopback."""
    for addrs in psutil.net_if_addrs().values():
        for a in addrs:
            if a.family == socket.AF_INET and not a.address.startswith("127."):
                return a.address
    return None


def _reachable(host: str, port: int) -> bool:
    try:
        with socket.create_connection((host, port), timeout=2):
            return True
    except OSError:
        return False


def test_nothing_listens_beyond_loopback_by_default(svc):
    listening = _listening(svc.proc.pid)
    assert listening  # uvicorn, the scheduler, the workers
    assert all(ip.startswith("127.") for ip, _ in listening), listening
    assert svc.client.health()["executor"]["dashboard"] is None


def test_the_dashboard_when_asked_for_binds_to_the_service_host(live_service):
    outside = _outside_address()
    if outside is None:
        pytest.skip("this machine has no non-loopback IPv4 address")
    svc = live_service(BELTSTUDY_DASHBOARD="true", BELTSTUDY_DASHBOARD_PORT="0")
    url = svc.client.health()["executor"]["dashboard"]
    assert url and url.startswith("http://127.0.0.1:"), url
    port = int(url.split(":")[2].split("/")[0])
    assert httpx.get(url, timeout=30).status_code == 200  # there, on loopback
    assert not _reachable(outside, port), f"dashboard reachable on {outside}:{port}"
    assert all(ip.startswith("127.") for ip, _ in _listening(svc.proc.pid))


def test_delete_and_sigterm_with_the_scheduler_unreachable_finish_within_10_s(
    make_study, tmp_path
):
    """Nothing listens at BELTSTUDY_SCHEDULER: studies stay queued, and deleting them or
    stopping the service does not wait for a connection."""
    from beltstudy.service.cli.client import ServiceClient
    from beltstudy.service.cli.demo import free_port, start_server, stop_server

    port = free_port()
    env = {"BELTSTUDY_DATA_DIR": str(tmp_path / "data"), "BELTSTUDY_TOKEN": "",
           "BELTSTUDY_SCHEDULER": f"tcp://127.0.0.1:{free_port()}",
           "BELTSTUDY_STUDIES_DIR": str(tmp_path)}
    with open(tmp_path / "beltstudy.service.log", "ab") as log:
        proc = start_server(port, env=env, log=log)
    client = ServiceClient(f"http://127.0.0.1:{port}", timeout=60)
    try:
        deadline = time.monotonic() + 120
        while True:
            try:
                client.health()
                break
            except Exception:
                assert time.monotonic() < deadline and proc.poll() is None
                time.sleep(0.3)
        ids = [client.submit(make_study(name=f"unreachable-{i}"))[0]["id"] for i in range(3)]
        time.sleep(1.0)  # the jobs are waiting for Dask
        assert all(client.status(sid)["state"] == "queued" for sid in ids)
        for sid in ids[:2]:
            t0 = time.monotonic()
            assert client.delete(sid)["deleted"]
            assert time.monotonic() - t0 < 10.0, f"DELETE took {time.monotonic() - t0:.1f} s"
        t0 = time.monotonic()
        proc.send_signal(signal.SIGTERM)
        proc.wait(60)
        assert time.monotonic() - t0 < 10.0, f"SIGTERM took {time.monotonic() - t0:.1f} s"
        assert (tmp_path / "data" / "studies" / ids[2] / "study.json").is_file()
    finally:
        client.close()
        stop_server(proc)


def test_delete_and_sigterm_with_the_scheduler_gone_finish_within_10_s(
    live_service, make_study, tmp_path
):
    from beltstudy.service.cli.demo import free_port

    port = free_port()
    dask = os.path.join(os.path.dirname(sys.executable), "dask")
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "dask.log", "ab")  # noqa: SIM115
    procs = [subprocess.Popen(
        [dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
        stdout=log, stderr=log)]
    try:
        time.sleep(1.0)
        procs.append(subprocess.Popen(
            [dask, "worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
             "--host", "127.0.0.1"], stdout=log, stderr=log))
        svc = live_service(BELTSTUDY_SCHEDULER=address)
        long = make_study(name="scheduler-gone", dynamics=True,
                          grid={"temperature_c": {"start": -40, "stop": 40, "step": 0.5}})
        long["scenario"] = {**long["scenario"], "elements": 200, "run_s": 30}
        running, _ = svc.client.submit(long)
        svc.wait(running["id"], until=lambda st: st["done"] >= 1)
        for p in reversed(procs):
            p.send_signal(signal.SIGKILL)
            p.wait(10)
        queued, created = svc.client.submit(make_study(name="after-the-scheduler"))
        assert created
        for sid in (running["id"], queued["id"]):
            t0 = time.monotonic()
            assert svc.client.delete(sid)["deleted"]
            assert time.monotonic() - t0 < 10.0, f"DELETE took {time.monotonic() - t0:.1f} s"
            assert not (svc.data_dir / "studies" / sid).exists()
        third, _ = svc.client.submit(make_study(name="left-queued"))
        t0 = time.monotonic()
        svc.proc.send_signal(signal.SIGTERM)
        svc.proc.wait(30)
        assert time.monotonic() - t0 < 10.0, f"SIGTERM took {time.monotonic() - t0:.1f} s"
        svc.stop()
        # the study left behind is kept, to resume on the next start
        assert (svc.data_dir / "studies" / third["id"] / "study.json").is_file()
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.wait(10)
        log.close()


def _runs_alive() -> int:
    """RunSpec objects alive in this process (every resolved run is one)."""
    import gc

    from beltstudy.service.grid.expand import RunSpec

    gc.collect()
    return sum(1 for o in gc.get_objects() if isinstance(o, RunSpec))


def test_a_finished_study_releases_its_job_memory(data_dir, make_settings, make_conveyor):
    """In-process service with a real LocalCluster: the resolved runs a study holds while it
    runs (counted, and their bytes measured with tracemalloc) are freed once it has finished."""
    import tracemalloc

    from beltstudy.service.door.studyfile import resolve_study

    n_runs = 300  # the grid below: 100 to 249.5 t/h in steps of 0.5 (about 1.3 MB of runs)
    from beltstudy.service.studies import StudyService

    body = {
        "name": "memory",
        "conveyor": make_conveyor(),
        "grid": {"material.capacity_t_h": {"start": 100, "stop": 249.5, "step": 0.5},
                 "friction_model": ["din"]},
        "dynamics": False,
    }
    tracemalloc.start()
    study = resolve_study(body)
    study_bytes = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    assert len(study.runs) == n_runs and study_bytes > 1_000_000
    del study
    service = StudyService(make_settings(data_dir).model_copy(update={"warm_start": True}))
    service.start()
    try:
        service.executor.client()  # the cluster started and warmed
        # runs of other studies this process resolved may still be alive (FastAPI keeps the
        # route functions of every app it built, and with them their service's cache): count
        # from here
        before = _runs_alive()
        st, created = service.submit(body, confine=False)
        assert created and st["total"] == n_runs
        assert _runs_alive() >= before + n_runs  # the job holds them while it runs
        st = service.wait(st["id"], poll_s=0.2, timeout_s=240)
        assert st["state"] == "done" and st["done"] == n_runs, st
        deadline = time.monotonic() + 30
        while service.running_count() and time.monotonic() < deadline:
            time.sleep(0.05)
        # the runs travel to Dask as themselves: the in-process scheduler holds a batch's task
        # (and its runs) until the client's release of its future reaches it, a moment after
        # the job has ended
        left = _runs_alive() - before
        while left > 0 and time.monotonic() < deadline:
            time.sleep(0.2)
            left = _runs_alive() - before
        assert left <= 0, (
            f"a finished study still holds {left} resolved runs, about "
            f"{study_bytes * left / n_runs / 1e6:.1f} MB (the study's runs take "
            f"{study_bytes / 1e6:.1f} MB)"
        )
    finally:
        service.close()


#: A study of seconds of expansion: 5 models x 5 temperatures x 40 lifts x 4 widths, 4 000
#: steady runs of 160 conveyor designs (a fifth of it took a minute on a loaded machine).
SLOW_EXPANSION = {
    "name": "slow-expansion", "conveyor": "conveyors/slope-5pct.yaml", "dynamics": False,
    "grid": {"friction_model": ["cema", "din", "nonlin", "cmod", "visco"],
             "temperature_c": [-20, 0, 10, 20, 30],
             "profile.0.lift_m": {"start": 1, "stop": 40, "step": 1},
             "belt.width_m": [1.2, 1.4, 1.6, 1.8]}}


def test_submit_sends_a_study_again_after_a_503_with_retry_after(live_service, make_study,
                                                                 capsys):
    """With one expansion at a time and a 1 s wait for it, a second study sent while the
    first expands is a 503 with Retry-After: 1. ``beltstudy submit`` stopped there with exit
    status 2, though the answer said when to send it again; it now sends it again after the
    time asked, saying so, and the study is submitted."""
    svc = live_service(BELTSTUDY_EXPANSION_WAIT_S="1")
    first = threading.Thread(target=lambda: svc.client.submit(SLOW_EXPANSION, retries=0))
    first.start()
    time.sleep(1.0)
    st, created = svc.client.submit(make_study(name="second-in-line"), retries=60)
    first.join(120)
    assert created and st["total"] == 6
    err = capsys.readouterr().err
    assert "(BELTSTUDY_MAX_EXPANSIONS)" in err and "sending it again in 1 s (1 of 60)" in err


def test_sigterm_while_a_study_expands_answers_503_with_retry_after(live_service, tmp_path):
    """A study still in expansion when the service is stopped (SIGTERM) outlived uvicorn's
    grace period and was cut off with a plain-text '500 Internal Server Error', which the CLI
    took for another server ('check --url'). It is a JSON 503 with Retry-After: the service is
    being stopped, send it again once it is back."""
    svc = live_service()
    slow = SLOW_EXPANSION
    answer: dict = {}

    def post():
        with httpx.Client(base_url=svc.url, timeout=120) as http:
            answer["r"] = http.post("/studies", json=slow)

    poster = threading.Thread(target=post)
    poster.start()
    time.sleep(1.5)  # the body is read and the expansion under way
    svc.proc.send_signal(signal.SIGTERM)
    poster.join(60)
    r = answer["r"]
    assert r.status_code == 503, (r.status_code, r.text[:300])
    assert r.headers["content-type"].startswith("application/json")
    assert r.json()["error"] == "unavailable"
    assert "the service is being stopped" in r.json()["message"]
    assert int(r.headers["Retry-After"]) >= 1
    svc.kill()
