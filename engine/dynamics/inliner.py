"""numba's inliner copying an inlined function's IR once per call site, not once per block.

The kernel inlines its phases at numba's IR level (``inline="always"``: 76 functions, nested).
numba 0.68's ``InlineWorker.inline_ir`` copies the callee's IR block by block, each block by
its own ``copy.deepcopy``, and a block refers to its function's scope, which holds every
variable of the function: the whole scope is copied again for every block. For a callee that
has inlined its own callees (thousands of variables, hundreds of blocks) that is quadratic:
on a cold cache it was about 40 % of the kernel's compile (``run_cycle`` 217.7 s against
134.5 s with the change below, the same machine; cProfile: 369 of 573 s in ``deepcopy``, 21
million variable copies for 440 inlined calls).

:func:`install` gives the block copies of one call site one memo, so the scope and each
variable are copied once. The copy is the same IR: the inliner reads the callee's one scope
(it asserts there is one: the per-block copies were equal ones), renames its variables by
name and then points every inlined block at the caller's scope. numba's code generation, and
so the machine code and every result, are unchanged: the kernel's optimised LLVM IR was the
same text either way (2.39 MB, compiled in two processes; the symbols' ABI tags differ only
in the order numba prints the set of fast-math flags), and
``tests/engine/dynamics/test_inliner.py`` compares the same on nested inlined functions.

The change is made only where numba's source of ``inline_ir`` holds the expected lines (numba
0.68); on another numba it is left alone and the kernel compiles as numba does it, slower.
"""

from __future__ import annotations

import inspect
import textwrap

__all__ = ["install", "installed", "rewritten"]

#: The copy in numba 0.68's ``InlineWorker.inline_ir`` (``copy_ir``), dedented once.
_PER_BLOCK = (
    "        kernel_copy.blocks = {}\n"
    "        for block_label, block in the_ir.blocks.items():\n"
    "            new_block = copy.deepcopy(the_ir.blocks[block_label])\n"
)
#: The same with one memo for the blocks of a call site.
_ONE_MEMO = (
    "        kernel_copy.blocks = {}\n"
    "        memo = {}  # one copy of the scope and each variable (beltstudy inliner.py)\n"
    "        for block_label, block in the_ir.blocks.items():\n"
    "            new_block = copy.deepcopy(the_ir.blocks[block_label], memo)\n"
)

_MARK = "_beltstudy_one_memo"


def installed() -> bool:
    """Whether numba's inliner copies with one memo per call site in this process."""
    from numba.core import inline_closurecall

    return bool(getattr(inline_closurecall.InlineWorker.inline_ir, _MARK, False))


def rewritten(source: str) -> str | None:
    """``inline_ir``'s dedented source with the blocks copied under one memo; None where it
    does not hold numba 0.68's per-block copy exactly once."""
    if source.count(_PER_BLOCK) != 1:
        return None
    return source.replace(_PER_BLOCK, _ONE_MEMO)


def install() -> bool:
    """Make numba's ``InlineWorker.inline_ir`` copy a callee's blocks with one memo (once per
    process). Returns whether it is in place; False, and numba untouched, where numba's source
    is not the one expected."""
    from numba.core import inline_closurecall

    worker = inline_closurecall.InlineWorker
    if installed():
        return True
    try:
        source = rewritten(textwrap.dedent(inspect.getsource(worker.inline_ir)))
        filename = inspect.getsourcefile(worker.inline_ir) or "<numba inline_ir>"
    except (OSError, TypeError):
        return False
    if source is None:
        return False
    first_line = worker.inline_ir.__code__.co_firstlineno
    code = compile("\n" * (first_line - 1) + source, filename, "exec")
    namespace: dict = {}
    exec(code, vars(inline_closurecall), namespace)  # numba's module globals, as the original
    inline_ir = namespace["inline_ir"]
    inline_ir.__qualname__ = worker.inline_ir.__qualname__
    inline_ir.__doc__ = worker.inline_ir.__doc__
    setattr(inline_ir, _MARK, True)
    worker.inline_ir = inline_ir
    return True
