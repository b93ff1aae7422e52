"""Whether the transient engine will compile on its first run in this process.

The kernel is numba code cached beside its sources (``cache=True``): a fresh clone compiles it
on the first transient run (a minute or more on a busy machine), later processes load it from
the cache in about a second. :func:`kernel_cold` tells a command line which of the two is
coming, so it can say so before the wait rather than after. :func:`first_compile` makes
processes that start cold at the same time (a study's Dask workers, the test processes) compile
it once between them: one compiles, the others wait and load its cache.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from pathlib import Path

try:
    import fcntl
except ImportError:  # not POSIX: each process compiles on its own, as numba does
    fcntl = None

__all__ = ["kernel_dispatchers", "kernel_cold", "first_compile", "COMPILE_LINE"]

#: What a command prints while the transient engine compiles.
COMPILE_LINE = "compiling the transient engine (first run only)"


def kernel_dispatchers() -> list:
    """The numba functions of the loaded engine modules, each once."""
    from numba.core.dispatcher import Dispatcher

    import beltstudy.engine.run  # noqa: F401 - loads the transient engine's modules

    found = {}
    for name, module in list(sys.modules.items()):
        if name.startswith("beltstudy.engine.") and module is not None:
            for value in vars(module).values():
                if isinstance(value, Dispatcher):
                    found[id(value)] = value
    return list(found.values())


def _cached(dispatcher) -> bool:
    """Whether numba's on-disk cache has an index for ``dispatcher`` (numba's private cache
    object: when its layout is not the one expected, the answer is no)."""
    try:
        return Path(dispatcher._cache._cache_file._index_path).is_file()
    except AttributeError:
        return False


def kernel_cold() -> bool:
    """True when a cached kernel function of the engine is neither compiled in this process nor
    in numba's on-disk cache: the first transient run will compile it. Functions inlined into
    their callers (``inline="always"``) are compiled within them and have no cache entry of
    their own: they are not counted."""
    for d in kernel_dispatchers():
        if d.signatures or d.targetoptions.get("inline", "never") != "never":
            continue
        if type(getattr(d, "_cache", None)).__name__ in ("NullCache", "NoneType"):
            continue
        if not _cached(d):
            return True
    return False


#: The lock file's name, beside numba's cache of the kernel.
LOCK_NAME = "beltstudy-compile.lock"

#: Whether the kernel has run in this process (compiled or loaded): later runs take no lock.
_ready = False
_ready_lock = threading.Lock()


def _lock_path() -> str | None:
    """The lock file beside the kernel's cache (numba's private cache object: None when its
    layout is not the one expected, or the kernel is not cached)."""
    from beltstudy.engine.dynamics.kernel import run_cycle

    try:
        folder = run_cycle._cache._cache_path
    except AttributeError:
        return None
    return os.path.join(folder, LOCK_NAME) if os.path.isdir(folder) else None


@contextlib.contextmanager
def _file_lock(path: str | None):
    """An exclusive ``flock`` on ``path`` while inside (nothing where it cannot be taken). The
    system drops it when the process ends, however it ends."""
    if path is None or fcntl is None:
        yield
        return
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    except OSError:
        yield
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


@contextlib.contextmanager
def first_compile():
    """Around a call of the transient kernel. The first call in a process, when the kernel is
    cold (:func:`kernel_cold`), holds an exclusive lock on a file beside numba's cache: of
    several processes starting cold at once, one compiles while the others wait, then load
    the cache it wrote (about a second) instead of compiling the same code again on a core the
    first one needs. Later calls, and a warm kernel, take no lock."""
    global _ready
    if _ready:
        yield
        return
    with _ready_lock:
        path = _lock_path() if kernel_cold() else None
        with _file_lock(path):
            yield
        _ready = True
