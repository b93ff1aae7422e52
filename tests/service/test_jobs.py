"""Batch sizing of a study's Dask tasks (service/jobs.py)."""

from __future__ import annotations

from service.jobs import MAX_BATCH, MIN_TASK_S, batch_size


def test_first_wave_is_small():
    assert batch_size(None, 1000, 4, 1.0, dynamics=False) == 8
    assert batch_size(None, 1000, 4, 1.0, dynamics=True) == 1


def test_batches_hold_about_task_seconds_of_work():
    assert batch_size(0.004, 10_000, 4, 1.0, False) == 250  # 1 s of 4 ms runs
    assert batch_size(0.5, 100, 4, 1.0, False) == 2
    assert batch_size(3.0, 100, 4, 1.0, True) == 1  # long runs: one per task
    assert batch_size(1e-7, 10**9, 4, 1.0, False) == MAX_BATCH


def test_near_the_end_batches_shrink_but_not_below_the_latency_floor():
    # 40 runs of 4 ms left for 4 slots: not 250 in one task, nor 10 per task (0.04 s of work,
    # less than a round trip), but 0.2 s of work each
    assert batch_size(0.004, 40, 4, 1.0, False) == round(MIN_TASK_S / 0.004) == 50
    assert batch_size(0.004, 400, 4, 1.0, False) == 100
    assert batch_size(0.05, 3, 4, 1.0, True) == 4  # 0.2 s of work; the caller takes the 3 left
