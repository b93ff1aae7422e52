"""A resumed study's progress: after a restart, GET /studies/{id} reads what the store last
said (runs done, failed, elapsed) until the job has counted its stored runs, never 0 runs done.

In-process, no Dask: the job's work is held at its start.
"""

from __future__ import annotations

import threading

from beltstudy.service.dask import jobs
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.store.parquet import Store
from beltstudy.service.studies import StudyService

from .conftest import ROOT


class IdleExecutor:
    """No Dask: the resumed job never gets as far as asking for a client."""

    def start_background(self):
        pass

    def close(self):
        pass

    def n_workers(self):
        return 0


def test_a_resumed_study_keeps_its_stored_progress_until_it_has_counted_its_runs(
    data_dir, make_settings, make_study, monkeypatch
):
    # a study killed mid-way: 7 083 of its runs stored, 2 failed, 41.5 s spent (the numbers of
    # a 19 764-run study SIGKILLed mid-run, which read 'queued 0/19764' for seconds after the
    # restart while it read its stored rows)
    study = resolve_study(make_study("resumed"), studies_dir=ROOT / "studies")
    store = Store(data_dir)
    store.create(study.id, {**StudyService._new_doc(study), "state": "running",
                            "done": 7083, "failed": 2, "elapsed_s": 41.5})
    release = threading.Event()
    monkeypatch.setattr(jobs.StudyJob, "_execute", lambda self: release.wait(10))
    service = StudyService(make_settings(data_dir), executor=IdleExecutor())
    try:
        service.start()  # resumes the study: its job is alive, its runs not yet counted
        st = service.status(study.id)
        assert (st["done"], st["failed"]) == (7083, 2), st
        assert st["elapsed_s"] == 41.5
    finally:
        release.set()
        for job in list(service._jobs.values()):
            job.join(5)
