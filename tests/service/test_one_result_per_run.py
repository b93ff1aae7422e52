"""One result per run id: the same run computed in two processes (one fresh, one that ran
another run first, with different thread settings of the numeric libraries) stores the same
bytes: its runs row (but the wall-clock ``elapsed_s``) and its time series, as Parquet.

Both processes load the same compiled kernel (numba's cache of this checkout). Measured for
issue 31 (the 5 % slope, din, paper-comparison's first run): with the kernel's fast-math flags
as they are (``engine/dynamics/fastmath.py``: ``reassoc`` and ``contract`` among them) a
process that compiles the kernel stores other last bits than every process that loads it
from the cache (``t_max_dyn_kn`` 470.3735892113305 against 470.37358921133074, reproduced
with two fresh caches); without ``reassoc`` and ``contract`` the two agree. The service
restarts workers that compiled (``Executor._warm_up``), so its runs come from the cached
kernel.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from .conftest import ROOT

SCRIPT = r'''
import hashlib, io, json, sys
import pyarrow.parquet as pq
from beltstudy.service.dask.jobs import study_schema
from beltstudy.service.dask.tasks import run_batch
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.store.columns import rows_to_table

study = resolve_study(json.loads(sys.argv[1]), studies_dir=sys.argv[2])
runs = study.runs
if sys.argv[3] == "after-another":
    run_batch(study.id, [runs[1]], True)
out = run_batch(study.id, [runs[0]], True)
table = rows_to_table(out["rows"], study_schema(study)).drop_columns(["elapsed_s"])
digests = {}
for name, data in (("runs", table), ("timeseries", out["timeseries"]),
                   ("surface", out["surface"])):
    buf = io.BytesIO()
    pq.write_table(data, buf)
    digests[name] = hashlib.sha256(buf.getvalue()).hexdigest()
print(json.dumps({"run_id": runs[0].run_id, **digests}))
'''


def _run_in_a_process(study: dict, how: str, **env: str) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT, json.dumps(study), str(ROOT / "studies"), how],
        capture_output=True, text=True, timeout=600, env={**os.environ, **env})
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_one_run_in_two_processes_stores_the_same_bytes(make_study):
    study = make_study("bytes", dynamics=True, surface=True,
                       grid={"friction_model": ["nonlin", "din"]})
    first = _run_in_a_process(study, "alone")
    second = _run_in_a_process(study, "after-another", OPENBLAS_NUM_THREADS="1",
                               OMP_NUM_THREADS="1", NUMBA_NUM_THREADS="1")
    assert first == second
