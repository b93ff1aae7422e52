"""numba's inliner copying a callee's IR once per call site (``engine/dynamics/inliner.py``):
the same IR, and so the same machine code, as numba's own per-block copy."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap

import numba
import pytest

from beltstudy.engine.dynamics import inliner

ON_NUMBA_068 = numba.__version__.startswith("0.68.")

#: Nested ``inline="always"`` functions with loops and branches (several blocks, a callee
#: inlined twice into another that is inlined three times), compiled with the inliner named
#: in argv[1]; prints the result and the optimised LLVM IR.
_PROGRAM = textwrap.dedent('''
    import sys

    import numpy as np
    from numba import njit
    from numba.core import inline_closurecall as icc

    numba_own = icc.InlineWorker.inline_ir
    import beltstudy.engine.dynamics  # noqa: F401  installs the one-memo copy
    if sys.argv[1] == "numba":
        icc.InlineWorker.inline_ir = numba_own
    assert (icc.InlineWorker.inline_ir is numba_own) == (sys.argv[1] == "numba")


    @njit(inline="always")
    def leaf(x, k):
        s = 0.0
        for i in range(k):
            if x[i] > 0.5:
                s += x[i] * 2.0
            elif x[i] < -0.5:
                s -= x[i] / 3.0
            else:
                s += 1.0
        return s


    @njit(inline="always")
    def middle(x, k):
        a = leaf(x, k)
        b = leaf(x, k // 2)
        if a > b:
            return a - b
        return a + b


    @njit
    def top(x):
        t = 0.0
        for j in range(3):
            t += middle(x, x.size - j)
        return t


    print(repr(top(np.linspace(-1.0, 1.0, 11))))
    print(next(iter(top.inspect_llvm().values())))
''')


def _compiled(which: str) -> tuple[str, str]:
    env = {**os.environ, "PYTHONHASHSEED": "0", "NUMBA_DISABLE_JIT": "0"}
    out = subprocess.run([sys.executable, "-c", _PROGRAM, which], capture_output=True,
                         text=True, env=env, timeout=600, check=True).stdout
    value, llvm = out.split("\n", 1)
    # the functions' unique ids in their symbols count numba's dispatchers in the process
    return value, re.sub(r"B\d+v\d+B", "BvB", llvm)


@pytest.mark.skipif(not ON_NUMBA_068, reason="the copy is changed on numba 0.68 only")
def test_installed_on_numba_068():
    assert inliner.installed()
    assert inliner.install() is True  # once: a second call changes nothing


@pytest.mark.skipif(not ON_NUMBA_068, reason="the copy is changed on numba 0.68 only")
def test_same_llvm_ir_as_numbas_own_copy():
    value_numba, llvm_numba = _compiled("numba")
    value_ours, llvm_ours = _compiled("ours")
    assert value_ours == value_numba
    assert "top" in llvm_ours and len(llvm_ours) > 5_000
    assert llvm_ours == llvm_numba


def test_other_source_left_alone():
    """A numba whose ``inline_ir`` does not copy block by block as 0.68 does is not changed."""
    assert inliner.rewritten("def inline_ir(self):\n    return None\n") is None
    twice = inliner._PER_BLOCK * 2
    assert inliner.rewritten(twice) is None
    once = "def inline_ir(self):\n    def copy_ir(the_ir):\n" + inliner._PER_BLOCK
    assert "copy.deepcopy(the_ir.blocks[block_label], memo)" in inliner.rewritten(once)
