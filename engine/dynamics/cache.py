"""numba's on-disk cache of the transient engine, keyed on every source file of this package.

numba keys a cached function on its own file's content only (numba 0.68: a SHA-256 of the
file), but the kernel (:func:`beltstudy.engine.dynamics.kernel.run_cycle`) inlines and links
functions from every module here: a change in ``passes.py`` alone would leave ``run_cycle``'s
stale machine code in use. :class:`PackageCacheLocator` keys every cached function of this
package on the contents of all its ``.py`` files together, so any change recompiles all of
them (and a fresh copy of the same sources loads the same cache). It is installed in front of
numba's own locators by :func:`install`, which the package runs before any of its functions
is compiled (``beltstudy/engine/dynamics/__init__.py``).

:func:`first_compile` makes processes that start cold at the same time (a study's Dask
workers, the test processes) compile the kernel once between them: one compiles, the others
wait and load the cache it wrote.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import os
import threading
from pathlib import Path

from numba.core import caching

try:
    import fcntl
except ImportError:  # not POSIX: each process compiles on its own, as numba does
    fcntl = None

__all__ = ["PackageCacheLocator", "PackageUserCacheLocator", "package_stamp", "install",
           "first_compile", "LOCK_NAME"]

_HERE = Path(__file__).resolve().parent


@functools.lru_cache(maxsize=1)
def package_stamp() -> bytes:
    """SHA-256 of the package's ``.py`` files, by name and content, in name order."""
    h = hashlib.sha256()
    for path in sorted(_HERE.glob("*.py")):
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.digest()


class _PackageStamp:
    """For this package's functions only, stamped with :func:`package_stamp`."""

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent != _HERE:
            return None
        return super().from_function(py_func, py_file)

    def get_source_stamp(self):
        return package_stamp()


class PackageCacheLocator(_PackageStamp, caching.InTreeCacheLocator):
    """numba's in-tree cache (``__pycache__`` beside the sources) for the functions of this
    package, stamped with :func:`package_stamp`."""


class PackageUserCacheLocator(_PackageStamp, caching.UserProvidedCacheLocator):
    """The same under ``NUMBA_CACHE_DIR`` when it is set (numba's own rule: that directory
    wins over the in-tree one)."""


def install() -> None:
    """Put the package's locators first among numba's cache locators (once):
    :class:`PackageUserCacheLocator` (``NUMBA_CACHE_DIR`` set), then
    :class:`PackageCacheLocator`."""
    classes = caching.CacheImpl._locator_classes
    for cls in (PackageCacheLocator, PackageUserCacheLocator):
        if cls not in classes:
            classes.insert(0, cls)


#: The lock file's name, in numba's cache folder of the kernel.
LOCK_NAME = "beltstudy-compile.lock"

#: Whether the kernel has run in this process (compiled or loaded): later runs take no lock.
_ready = False
_ready_lock = threading.Lock()


def lock_path(dispatcher) -> str | None:
    """The lock file in ``dispatcher``'s cache folder (numba's private cache object: None when
    its layout is not the one expected, or the function is not cached)."""
    try:
        folder = dispatcher._cache._cache_path
    except AttributeError:
        return None
    return os.path.join(folder, LOCK_NAME) if os.path.isdir(folder) else None


def index_cached(dispatcher) -> bool:
    """Whether numba's on-disk cache has an index for ``dispatcher`` (numba's private cache
    object: when its layout is not the one expected, the answer is no)."""
    try:
        return Path(dispatcher._cache._cache_file._index_path).is_file()
    except AttributeError:
        return False


def _cold(dispatcher) -> bool:
    """Neither compiled in this process nor in numba's on-disk cache (its index file); a
    function numba does not cache is not cold (nothing to wait for)."""
    if dispatcher.signatures or not hasattr(dispatcher, "_cache"):
        return False
    if type(dispatcher._cache).__name__ == "NullCache":
        return False
    return not index_cached(dispatcher)


@contextlib.contextmanager
def file_lock(path: str | None):
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
def first_compile(dispatcher):
    """Around a call of the kernel ``dispatcher``. The first call in a process, when it is
    cold (neither compiled here nor cached), holds an exclusive lock on a file in numba's
    cache folder: of several processes starting cold at once, one compiles while the others
    wait, then load the cache it wrote (about a second) instead of compiling the same code
    again on a core the first one needs (two processes on an empty cache: 130.9 s and 130.8 s
    wall, one of them compiling). Later calls, and a warm kernel, take no lock."""
    global _ready
    if _ready:
        yield
        return
    with _ready_lock:
        with file_lock(lock_path(dispatcher) if _cold(dispatcher) else None):
            yield
        _ready = True
