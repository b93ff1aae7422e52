"""numba's on-disk cache of the transient engine, keyed on every source file of this package.

numba keys a cached function on its own file's content only (numba 0.68: a SHA-256 of the
file), but the kernel (:func:`beltstudy.engine.dynamics.kernel.run_cycle`) inlines and links
functions from every module here: a change in ``passes.py`` alone would leave ``run_cycle``'s
stale machine code in use. :class:`PackageCacheLocator` keys every cached function of this
package on the contents of all its ``.py`` files together, so any change recompiles all of
them (and a fresh copy of the same sources loads the same cache). It is installed in front of
numba's own locators by :func:`install`, which the package runs before any of its functions
is compiled (``beltstudy/engine/dynamics/__init__.py``).
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from numba.core import caching

__all__ = ["PackageCacheLocator", "PackageUserCacheLocator", "package_stamp", "install"]

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
