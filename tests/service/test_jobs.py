"""Batch sizing of a study's Dask tasks (service/dask/jobs.py) and a failed run's message."""

from __future__ import annotations

import pytest

from beltstudy.service.dask.jobs import MAX_BATCH, MIN_TASK_S, batch_size


class FakeStore:
    """A study store that holds no runs and keeps what a job saves (``saved``)."""

    def __init__(self):
        self.saved: list[dict] = []

    def read(self, sid):
        return {}

    def done_runs(self, sid):
        import pandas as pd

        return pd.DataFrame()

    def update(self, sid, **fields):
        self.saved.append(fields)
        return fields


def test_first_wave_is_small():
    assert batch_size(None, 1000, 4, 1.0, dynamics=False) == 8
    assert batch_size(None, 1000, 4, 1.0, dynamics=True) == 1


def test_batches_hold_about_task_seconds_of_work():
    assert batch_size(0.004, 10_000, 4, 1.0, False) == 250  # 1 s of 4 ms runs
    assert batch_size(0.5, 100, 4, 1.0, False) == 2
    assert batch_size(3.0, 100, 4, 1.0, True) == 1  # long runs: one per task
    assert batch_size(1e-7, 10**9, 4, 1.0, False) == MAX_BATCH


def test_near_the_end_batches_shrink_but_not_below_the_floor():
    # 40 runs of 1 ms left for 4 slots: not 250 in one task, nor 10 per task (0.01 s of work,
    # less than a task costs), but 0.05 s of work each
    assert batch_size(0.001, 40, 4, 1.0, False) == round(MIN_TASK_S / 0.001) == 50
    assert batch_size(0.004, 400, 4, 1.0, False) == 100
    # 40 dynamic runs of 30 ms left: a fair share each (0.3 s), not 1 s of work in one task
    assert batch_size(0.03, 40, 4, 1.0, True) == 10
    # the last runs: 0.05 s of work at least; the caller takes the 3 left
    assert batch_size(0.01, 3, 4, 1.0, True) == 5


class Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


def test_eta_comes_from_the_measured_run_rate_not_the_start_up():
    """A study of 100 runs of 0.1 s on 2 workers (about 5 s of work) whose first task lands
    after 20 s of cluster start and numba compiling: the time left is about 5 s, not the
    20 s of start-up stretched over the runs."""
    from beltstudy.service.dask.jobs import RunRate

    clock = Clock()
    rate = RunRate(clock)
    assert rate.eta_s(100, 2) is None  # nothing finished yet: no guess
    clock.t = 20.0
    rate.finished(1, 0.1)  # the first task: compute per run spread over the workers
    assert rate.eta_s(99, 2) == pytest.approx(99 * 0.1 / 2, rel=1e-9)
    clock.t = 20.05
    rate.finished(1, 0.1)  # a second task a moment later: the window is too short to trust
    assert rate.eta_s(98, 2) == pytest.approx(98 * 0.1 / 2, rel=1e-9)
    for k in range(1, 21):  # then 2 runs every 0.1 s: 20 runs/s
        clock.t = 20.05 + 0.1 * k
        rate.finished(2, 0.2)
    remaining = 100 - 42
    assert rate.eta_s(remaining, 2) == pytest.approx(remaining / (41 / 2.05), rel=1e-9)
    assert abs(rate.eta_s(remaining, 2) - remaining / 20.0) < 0.2
    assert rate.eta_s(0, 2) == 0.0


def test_a_failed_runs_message_is_the_input_problem_in_its_own_words():
    """An InputError names the field and the fix: no Python class name before it; any other
    exception keeps its name (a fault of the program, not of the inputs)."""
    from beltstudy.engine import InputError
    from beltstudy.service.dask.tasks import _message

    exc = InputError("5 s is above the stability limit 0.01 s", field="scenario.dt_s")
    assert _message(exc) == "scenario.dt_s: 5 s is above the stability limit 0.01 s"
    assert _message(ZeroDivisionError("division by zero")) == (
        "ZeroDivisionError: division by zero")
    assert _message(RuntimeError()) == "RuntimeError"


def test_a_study_back_from_a_lost_scheduler_drops_its_waiting_message(monkeypatch):
    """A study that lost its scheduler mid-run says it waits for Dask; once Dask is back and
    its runs go on, the message goes (it said 'waiting for Dask' to the end of the study)."""
    from types import SimpleNamespace

    from beltstudy.service.dask import jobs
    from beltstudy.service.errors import Unavailable

    monkeypatch.setattr(jobs, "WAIT_FOR_DASK_S", 0.0)
    monkeypatch.setattr(jobs, "adjacent_starts", list)
    store = FakeStore()
    saved = store.saved

    answers = iter(["client", Unavailable("Dask on tcp://127.0.0.1:1 is not ready: lost the "
                                          "Dask scheduler; reconnecting"), "client"])

    class FakeExecutor:
        failing_since = None

        def client(self, timeout, halt, connected=False):
            answer = next(answers)
            if isinstance(answer, Exception):
                raise answer
            return answer

        def n_workers(self):
            return 1

    runs = [SimpleNamespace(run_id="r1"), SimpleNamespace(run_id="r2")]
    study = SimpleNamespace(id="s1", runs=runs, total=2, axes=[], dynamics=False, surface=False)
    job = jobs.StudyJob(study, store, FakeExecutor(), SimpleNamespace(task_seconds=1.0))
    monkeypatch.setattr(job, "_new_session", lambda: {})
    streams: list[str] = []

    def stream(client, todo):
        streams.append(client)
        if len(streams) == 1:  # the scheduler goes: the client is lost, the runs wait
            return True
        progress = [f for f in saved if "message" in f]
        assert progress[-1]["message"] == "", progress  # back on Dask: no longer waiting
        todo.clear()
        job.done = 2
        return False

    monkeypatch.setattr(job, "_stream", stream)
    job._execute()
    messages = [f["message"] for f in saved if "message" in f]
    assert any(m.startswith("waiting for Dask: ") for m in messages), messages
    assert job.state == "done" and messages[-1] == "" and len(streams) == 2


def test_a_study_waiting_for_a_lost_scheduler_has_no_time_left(monkeypatch):
    """While a study waits for its lost scheduler nothing runs: its time left is unknown (it
    grew by 2 s each second of the outage, 3.5 s to 134 s over a minute, on a live service
    whose scheduler was killed), and once Dask is back it comes from the runs since then, not
    from a rate averaged over the outage (63 s left for 28 runs that took 1.5 s)."""
    from types import SimpleNamespace

    from beltstudy.service.dask import jobs
    from beltstudy.service.errors import Unavailable

    clock = Clock()
    monkeypatch.setattr(jobs, "WAIT_FOR_DASK_S", 0.0)
    monkeypatch.setattr(jobs, "adjacent_starts", list)
    run_rate = jobs.RunRate
    monkeypatch.setattr(jobs, "RunRate", lambda: run_rate(clock))

    store = FakeStore()

    etas_waiting: list = []

    class FakeExecutor:
        failing_since = None
        answers = iter(["client", "down", "client"])

        def client(self, timeout, halt, connected=False):
            if next(self.answers) == "down":
                clock.t += 60.0  # a minute without a scheduler
                etas_waiting.append(job.eta_s())
                raise Unavailable("Dask on tcp://127.0.0.1:1 is not ready: lost the Dask "
                                  "scheduler; reconnecting")
            return "client"

        def n_workers(self):
            return 1

    runs = [SimpleNamespace(run_id=f"r{i}") for i in range(60)]
    study = SimpleNamespace(id="s1", runs=runs, total=60, axes=[], dynamics=False, surface=False)
    job = jobs.StudyJob(study, store, FakeExecutor(), SimpleNamespace(task_seconds=1.0))
    monkeypatch.setattr(job, "_new_session", lambda: {})
    etas: list = []

    def stream(client, todo):
        for _ in range(10):  # 2 runs of 0.1 s every 0.2 s: 10 runs/s
            clock.t += 0.2
            job.rate.finished(2, 0.2)
            job.done += 2
            todo.popleft(), todo.popleft()
        etas.append(job.eta_s())
        if len(etas) == 1:
            return True  # the first session loses its scheduler
        todo.clear()
        job.done = 60
        return False

    monkeypatch.setattr(job, "_stream", stream)
    job._execute()
    assert job.state == "done" and len(etas) == 2
    assert etas[0] == pytest.approx(40 / (18 / 1.8), rel=1e-9)  # 4 s left at 10 runs/s
    assert etas_waiting == [None]  # nothing runs: no time left to give
    # back on Dask: the new session's 20 runs over 2 s, not 20 runs over 62 s
    assert etas[1] == pytest.approx(20 / (18 / 1.8), rel=1e-9)


def test_a_running_studys_time_left_never_reads_zero(data_dir, make_settings, make_study,
                                                     finished_study):
    """0 s left is the done study's answer: a running study with 40 ms of runs left (40 steady
    runs at 1000 runs/s) said 0.0, rounded to the 0.1 s the status gives; it says 0.1."""
    from beltstudy.service.studies import StudyService

    sid = finished_study(data_dir, make_study("eta"))
    service = StudyService(make_settings(data_dir))

    class Job:
        state, done, failed = "running", 5, 0

        def __init__(self, eta):
            self.eta = eta

        def is_alive(self):
            return True

        def elapsed_s(self):
            return 1.0

        def eta_s(self):
            return self.eta

    for eta, said in ((0.04, 0.1), (0.0, 0.0), (None, None), (2.34, 2.3)):
        service._jobs[sid] = Job(eta)
        assert service.status(sid)["eta_s"] == said, eta
    del service._jobs[sid]
    assert service.status(sid)["eta_s"] == 0.0  # done


def test_a_stopped_study_stores_the_runs_it_kept(monkeypatch):
    """A service stopped mid-study (SIGTERM) writes the runs it has finished; its study.json
    said the count of its last periodic save (29 of 60 with 48 rows stored), which
    'beltstudy status' and 'results' then read with no service up. It now says 48."""
    from types import SimpleNamespace

    from beltstudy.service.dask import jobs

    monkeypatch.setattr(jobs, "adjacent_starts", list)
    store = FakeStore()
    saved = store.saved

    class FakeExecutor:
        def client(self, timeout, halt, connected=False):
            return "client"

        def n_workers(self):
            return 2

    runs = [SimpleNamespace(run_id=f"r{i}") for i in range(60)]
    study = SimpleNamespace(id="s1", runs=runs, total=60, axes=[], dynamics=False, surface=False)
    job = jobs.StudyJob(study, store, FakeExecutor(), SimpleNamespace(task_seconds=1.0))
    monkeypatch.setattr(job, "_new_session", lambda: {})

    def stream(client, todo):
        job.done = 29
        job._save()  # the last periodic save
        job.stop()  # SIGTERM: the tasks in flight finish into the buffer, which is written
        job.done = 48
        return False

    monkeypatch.setattr(job, "_stream", stream)
    job._execute()
    assert saved[-1]["done"] == 48 and saved[-1]["state"] == "running"
