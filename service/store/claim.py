"""One process runs a data folder's studies at a time.

A service (``beltstudy serve``) and ``beltstudy run`` both write a study's rows, time series
and ``study.json``, and a service resumes every unfinished study of its folder when it
starts. Two of them on one folder ran the same study twice: a second ``serve`` left 496 rows
for 279 runs (217 duplicates), and a ``beltstudy run`` beside a service cleaned away the time
series of 62 runs the service was writing and rewrote the study's state. So the process that
runs studies holds an exclusive lock on ``<data dir>/.beltstudy.lock`` (``flock``: the system
lets go of it when the process ends, killed or not) and writes who it is into the file; a
second one is refused with that name. Commands that only read the store take no lock.
"""

from __future__ import annotations

import fcntl
import json
import os
import sys
import threading
import time
from pathlib import Path

from beltstudy.service.errors import Conflict

__all__ = ["LOCK_NAME", "DataDirClaim"]

#: The lock file in the data folder.
LOCK_NAME = ".beltstudy.lock"


#: Folders this process holds: resolved path -> (file descriptor, claims). Two services in
#: one process (tests, an embedding program) share the process's hold; two processes cannot.
_HELD: dict[Path, list[int]] = {}
_GUARD = threading.Lock()


class DataDirClaim:
    """The exclusive claim of one data folder by this process (:meth:`take`, :meth:`drop`)."""

    def __init__(self, data_dir: str | os.PathLike, who: str = ""):
        self.path = (Path(data_dir) / LOCK_NAME).resolve()
        self.who = who or "beltstudy " + " ".join(sys.argv[1:4])
        self._taken = False

    @property
    def held(self) -> bool:
        return self._taken

    def take(self) -> None:
        """Hold the folder, or a :class:`Conflict` naming the process that holds it and the
        way out (its address to submit to, or another folder). Taking it twice is a no-op."""
        if self._taken:
            return
        with _GUARD:
            if self.path in _HELD:
                _HELD[self.path][1] += 1
                self._taken = True
                return
            # the store creates its folder when it first writes; the lock comes first
            self.path.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                holder = _read(fd)
                os.close(fd)
                # a service takes studies; a `beltstudy run` ends with its study
                way = ("wait for it to finish (it ends with its study)"
                       if holder.startswith("beltstudy run") else
                       "submit to it (beltstudy submit, or POST /studies at its address)")
                raise Conflict(
                    f"the data folder {self.path.parent} is in use by {holder}: one process "
                    f"runs a folder's studies at a time (two would run them twice); {way}, or "
                    "give this one another folder (BELTSTUDY_DATA_DIR)") from None
            os.ftruncate(fd, 0)
            os.write(fd, json.dumps({"pid": os.getpid(), "command": self.who,
                                     "since": time.strftime("%Y-%m-%d %H:%M:%S")}).encode())
            _HELD[self.path] = [fd, 1]
            self._taken = True

    def drop(self) -> None:
        """Let go of the folder (the file stays; its lock is what counts)."""
        if not self._taken:
            return
        self._taken = False
        with _GUARD:
            held = _HELD.get(self.path)
            if held is None:
                return
            held[1] -= 1
            if held[1] > 0:
                return
            del _HELD[self.path]
            try:
                fcntl.flock(held[0], fcntl.LOCK_UN)
            finally:
                os.close(held[0])


def _read(fd: int) -> str:
    """Who holds the lock, in words, from what it wrote ('another process' if unreadable)."""
    try:
        os.lseek(fd, 0, os.SEEK_SET)
        doc = json.loads(os.read(fd, 4096).decode() or "{}")
        return (f"{doc.get('command', 'a beltstudy process')} (pid {doc.get('pid', '?')}, since "
                f"{doc.get('since', '?')})")
    except (OSError, ValueError):
        return "another beltstudy process"
