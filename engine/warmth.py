"""Whether the transient engine will compile on its first run in this process.

The kernel is numba code cached beside its sources (``cache=True``): a fresh clone compiles it
on the first transient run (a minute or more on a busy machine), later processes load it from
the cache in about a second. :func:`kernel_cold` tells a command line which of the two is
coming, so it can say so before the wait rather than after.
"""

from __future__ import annotations

import sys

__all__ = ["kernel_dispatchers", "kernel_cold", "COMPILE_LINE"]

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


def kernel_cold() -> bool:
    """True when a cached kernel function of the engine is neither compiled in this process nor
    in numba's on-disk cache: the first transient run will compile it. Functions inlined into
    their callers (``inline="always"``) are compiled within them and have no cache entry of
    their own: they are not counted."""
    from beltstudy.engine.dynamics.cache import index_cached

    for d in kernel_dispatchers():
        if d.signatures or d.targetoptions.get("inline", "never") != "never":
            continue
        if type(getattr(d, "_cache", None)).__name__ in ("NullCache", "NoneType"):
            continue
        if not index_cached(d):
            return True
    return False
