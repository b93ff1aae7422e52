"""A task whose Dask workers died under it (``KilledWorker``) gives its runs failed rows: their
message said only Dask's own text ('Attempted to run task 'beltstudy-...' on 4 different
workers ... Inspecting worker logs is often a good next step'), nothing of what to do. It now
says it in the study's terms: the worker died, the run was not judged, what lightens a run
that runs out of memory, and how to run it again."""
from __future__ import annotations

from distributed import KilledWorker

from beltstudy.service.dask.jobs import task_failed_words


def test_a_killed_worker_is_said_with_its_causes_and_the_way_to_rerun():
    said = task_failed_words(KilledWorker("beltstudy-abc-000000", "tcp://127.0.0.1:1", 3))
    assert said.startswith("task failed: the Dask worker running it died each time it was "
                           "tried (KilledWorker: killed from outside, or out of memory)")
    assert "scenario.elements" in said and "DELETE the study and submit it again" in said
    assert len(said) <= 1000


def test_any_other_task_error_keeps_its_type_and_text():
    assert task_failed_words(ValueError("bad dt")) == "task failed: ValueError: bad dt"
