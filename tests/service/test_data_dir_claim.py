"""One process runs a data folder's studies at a time (service/store/claim.py).

Nothing stopped a second process on a folder a service was running: a second ``beltstudy
serve`` resumed the service's running study and ran it again (496 rows for 279 runs, 217
duplicates), and a ``beltstudy run`` beside a service cleaned away the time series of 62
runs the service was writing and rewrote its study's state. The process that runs studies
now holds a lock in the folder; a second one is refused naming the first and the way out,
and the lock goes with its process, however it ends."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from beltstudy.service.errors import Conflict
from beltstudy.service.store.claim import LOCK_NAME, DataDirClaim
from beltstudy.service.studies import StudyService

ROOT = Path(__file__).resolve().parents[2]
HOLD = ("import sys, time\n"
        "from beltstudy.service.store.claim import DataDirClaim\n"
        "DataDirClaim(sys.argv[1], 'beltstudy serve --port 18999').take()\n"
        "print('held', flush=True)\n"
        "time.sleep(120)\n")


@pytest.fixture
def held(data_dir):
    """Another process holding ``data_dir`` (killed with SIGKILL at the end)."""
    data_dir.mkdir(parents=True)
    proc = subprocess.Popen([sys.executable, "-c", HOLD, str(data_dir)],
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "held"
    yield proc
    if proc.poll() is None:
        proc.kill()
        proc.wait()


def test_a_second_process_is_refused_naming_the_first(held, data_dir, make_settings,
                                                      make_study):
    service = StudyService(make_settings(data_dir))
    with pytest.raises(Conflict, match=(
            rf"the data folder {data_dir} is in use by beltstudy serve --port 18999 \(pid "
            rf"{held.pid}, since .*\): one process runs a folder's studies at a time .*"
            r"another folder \(BELTSTUDY_DATA_DIR\)")):
        service.submit(make_study())
    # nothing was stored by the refused submission
    assert not (data_dir / "studies").exists() or not any((data_dir / "studies").iterdir())
    with pytest.raises(Conflict):
        service.start()
    service.close()


def test_beltstudy_run_on_a_held_folder_stops_with_one_line(held, data_dir, tmp_path):
    study = tmp_path / "s.yaml"
    study.write_text((ROOT / "studies" / "power-vs-temperature.yaml").read_text())
    conveyors = tmp_path / "conveyors"
    conveyors.symlink_to(ROOT / "studies" / "conveyors")
    env = {**os.environ, "BELTSTUDY_DATA_DIR": str(data_dir), "BELTSTUDY_WORKERS": "1"}
    out = subprocess.run([sys.executable, "-m", "beltstudy.service.cli", "run", str(study)],
                         capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 2, out.stderr
    assert f"error: the data folder {data_dir} is in use by beltstudy serve" in out.stderr
    assert "Traceback" not in out.stderr


def test_the_lock_goes_with_its_process_and_is_shared_within_one(held, data_dir):
    held.send_signal(signal.SIGKILL)
    held.wait()
    deadline = time.monotonic() + 10
    first = DataDirClaim(data_dir, "first")
    while True:  # the system lets go of a killed process's lock at once; allow a moment
        try:
            first.take()
            break
        except Conflict:
            assert time.monotonic() < deadline
            time.sleep(0.1)
    second = DataDirClaim(data_dir, "second")
    second.take()  # one process's services share its hold
    first.drop()
    assert (data_dir / LOCK_NAME).exists() and second.held
    second.drop()


def test_a_folder_held_by_beltstudy_run_is_told_to_wait_for_it(data_dir):
    """A `beltstudy run` has no address to submit to: the refusal says to wait for it."""
    data_dir.mkdir(parents=True)
    hold = HOLD.replace("beltstudy serve --port 18999", "beltstudy run studies/s.yaml")
    proc = subprocess.Popen([sys.executable, "-c", hold, str(data_dir)],
                            stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "held"
        with pytest.raises(Conflict, match=r"in use by beltstudy run studies/s\.yaml \(pid "
                           r"\d+, since .*\); wait for it to finish \(it ends with its "
                           r"study\), or give this one another folder"):
            DataDirClaim(data_dir, "beltstudy serve").take()
    finally:
        proc.kill()
        proc.wait()
