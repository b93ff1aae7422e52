"""One compile between processes that start cold together (``engine/dynamics/cache.py``)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from beltstudy.engine.dynamics import cache
from beltstudy.engine.dynamics.kernel import run_cycle

pytestmark = pytest.mark.skipif(cache.fcntl is None, reason="flock is POSIX")

#: Holds the lock, writes "A", waits for the go file, writes "B" and lets go.
_HOLDER = textwrap.dedent('''
    import sys, time
    from pathlib import Path
    from beltstudy.engine.dynamics import cache

    lock, log, go = sys.argv[1:4]
    with cache.file_lock(lock):
        Path(log).write_text("A")
        while not Path(go).exists():
            time.sleep(0.01)
        time.sleep(0.2)
        with open(log, "a") as f:
            f.write("B")
''')


def test_second_process_waits_for_the_first(tmp_path: Path):
    lock, log, go = tmp_path / "x.lock", tmp_path / "log", tmp_path / "go"
    holder = subprocess.Popen([sys.executable, "-c", _HOLDER, str(lock), str(log), str(go)])
    try:
        for _ in range(6000):  # the holder has the lock once it wrote "A"
            if log.exists() and log.read_text() == "A":
                break
            holder.poll()
            assert holder.returncode is None, "the lock holder ended early"
            time.sleep(0.01)
        go.touch()
        with cache.file_lock(str(lock)):  # waits for the holder to let go
            with open(log, "a") as f:
                f.write("C")
    finally:
        holder.wait(timeout=60)
    assert log.read_text() == "ABC"


def test_no_lock_where_none_can_be_taken(tmp_path: Path):
    with cache.file_lock(None):
        pass
    with cache.file_lock(str(tmp_path / "no such folder" / "x.lock")):
        pass  # cannot be created: runs unlocked rather than failing


def test_lock_beside_the_kernel_cache():
    path = cache.lock_path(run_cycle)
    assert path is not None
    assert Path(path).name == cache.LOCK_NAME
    assert Path(path).parent == Path(run_cycle._cache._cache_path)


def test_warm_kernel_takes_no_lock(monkeypatch, kernel_ran):
    """Once the kernel has run in a process (the warm-up run), no lock is looked for."""
    assert cache._ready
    monkeypatch.setattr(cache, "lock_path", lambda d: pytest.fail("lock looked for"))
    with cache.first_compile(run_cycle):
        pass


def test_a_compiled_kernel_is_not_cold(kernel_ran):
    assert run_cycle.signatures and not cache._cold(run_cycle)
