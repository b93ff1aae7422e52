"""Fast scalar maths for the kernel: LLVM operations numba does not expose, and ``exp`` /
``log`` on the IEEE bits.

numba without SVML calls scalar libm for ``exp`` and ``log``, and long Horner chains leave the
resistance passes latency-bound: these are written on the IEEE-754 bits with
Chebyshev-interpolated polynomials evaluated by Estrin's scheme. ``_fmin`` / ``_fmax`` are
LLVM's ``minnum`` / ``maxnum`` (numba's ``min`` / ``max`` become compare-and-select, which LLVM
neither vectorises as a reduction nor stores unconditionally).
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir as llir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

__all__ = ["FASTMATH", "FASTMATH_RED", "OPTS", "OPTS_RED"]

#: LLVM fast-math flags: everything but 'nnan'/'ninf' (divergence checks still see NaN),
#: 'reassoc' (sums keep the order written: a reassociated sum in a loop that stores is
#: vectorised behind runtime checks and could come out differently from one memory layout to
#: the next; element-wise loops vectorise without it) and 'contract' (a multiply and an add
#: fused or not by the code generator: the kernel compiled in a process and the same kernel
#: loaded from numba's cache gave other last bits with it). The same inputs give the same bits
#: in any process, compiled or cached.
FASTMATH = {"nsz", "arcp", "afn"}
#: For pure reductions (min/max, exact in any order) that LLVM only vectorises without NaN
#: semantics.
FASTMATH_RED = FASTMATH | {"nnan", "ninf", "reassoc"}
#: numba options of every kernel function: error_model="numpy" drops the zero-division
#: checks that would stop LLVM from vectorising the passes.
OPTS = dict(cache=True, nogil=True, fastmath=FASTMATH, error_model="numpy", _nrt=False)
#: Options of the reductions.
OPTS_RED = dict(cache=True, nogil=True, fastmath=FASTMATH_RED, error_model="numpy", _nrt=False)


# --------------------------------------------------------------------------------------
# bit-level helpers: LLVM operations numba does not expose


_I64 = llir.IntType(64)
_F64 = llir.DoubleType()


@intrinsic
def _bits(typingctx, x):
    """The IEEE-754 bits of a float64 as an int64 (a free bitcast)."""
    sig = types.int64(types.float64)

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], _I64)

    return sig, codegen


@intrinsic
def _from_bits(typingctx, i):
    """The float64 with the IEEE-754 bits of an int64 (a free bitcast)."""
    sig = types.float64(types.int64)

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], _F64)

    return sig, codegen


def _binary(name):
    @intrinsic
    def impl(typingctx, a, b):
        sig = types.float64(types.float64, types.float64)

        def codegen(context, builder, signature, args):
            fnty = llir.FunctionType(_F64, [_F64, _F64])
            fn = cgutils.get_or_insert_function(builder.module, fnty, name)
            return builder.call(fn, args, fastmath=("nnan", "nsz"))

        return sig, codegen

    return impl


#: min / max for the envelopes and reductions: LLVM's minnum/maxnum (NaN semantics dropped
#: on these calls only: numba's min/max become compare-and-select, which LLVM neither
#: vectorises as a reduction nor stores unconditionally). Divergence is checked on the
#: velocity sum, which keeps NaN.
_fmin = _binary("llvm.minnum.f64")
_fmax = _binary("llvm.maxnum.f64")


def _flagged(builder, op, a, b, flags):
    inst = getattr(builder, op)(a, b)
    inst.flags.extend(flags)  # non-empty flags: numba's fast-math pass leaves them alone
    return inst


@intrinsic
def _cttz(typingctx, x):
    """The number of trailing zero bits of a uint64 (LLVM's cttz; 64 for zero)."""
    sig = types.uint64(types.uint64)

    def codegen(context, builder, signature, args):
        fnty = llir.FunctionType(_I64, [_I64, llir.IntType(1)])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.cttz.i64")
        return builder.call(fn, [args[0], llir.Constant(llir.IntType(1), 0)])

    return sig, codegen


@intrinsic
def _round(typingctx, x):
    """x rounded to the nearest integer (|x| < 2^51) as ``(x + 1.5 2^52) - 1.5 2^52``,
    emitted without 'reassoc' so fast-math cannot fold it away."""
    sig = types.float64(types.float64)

    def codegen(context, builder, signature, args):
        c = llir.Constant(_F64, MAGIC)
        return _flagged(builder, "fsub", _flagged(builder, "fadd", args[0], c, ["nsz"]), c,
                        ["nsz"])

    return sig, codegen


@intrinsic
def _reduce_ln2(typingctx, y, k):
    """``(y - k LN2_HI) - k LN2_LO`` (Cody and Waite), without 'reassoc'."""
    sig = types.float64(types.float64, types.float64)

    def codegen(context, builder, signature, args):
        y_, k_ = args
        fl = ["nsz", "contract"]
        hi = _flagged(builder, "fmul", k_, llir.Constant(_F64, LN2_HI), fl)
        lo = _flagged(builder, "fmul", k_, llir.Constant(_F64, LN2_LO), fl)
        return _flagged(builder, "fsub", _flagged(builder, "fsub", y_, hi, fl), lo, fl)

    return sig, codegen


@intrinsic
def _mul_strict(typingctx, a, b):
    """a * b emitted without 'reassoc': fast-math cannot turn ``x * (y / z)`` back into
    ``(x * y) / z`` (which would put a division on the critical path)."""
    sig = types.float64(types.float64, types.float64)

    def codegen(context, builder, signature, args):
        return _flagged(builder, "fmul", args[0], args[1], ["nsz", "contract"])

    return sig, codegen


# --------------------------------------------------------------------------------------
# exp and log on the IEEE bits


LN2 = math.log(2.0)
#: ln 2 in two parts (Cody and Waite): k * LN2_HI is exact for |k| < 2^21.
LN2_HI = 0.6931471803691238
LN2_LO = 1.9082149292705877e-10
SQRT2 = math.sqrt(2.0)
#: 1.5 * 2**52: adding it rounds a double to an integer held in the low mantissa bits.
MAGIC = 6755399441055744.0
MAGIC_BITS = int(np.array([MAGIC]).view(np.int64)[0])
#: 2**52 as bits: OR-ing an integer below 2**52 into them gives 2**52 + that integer.
TWO52_BITS = 0x4330000000000000
MANT_MASK = 0x000FFFFFFFFFFFFF
ONE_BITS = 0x3FF0000000000000
#: ln of |v| or of the sag ratio when it is zero: any positive power of it is exp(-700).
LN_ZERO = -1e300
#: below this a speed or sag ratio counts as zero (its powers vanish, as np.power(0, p)).
TINY = 1e-300


#: ln m = 2 f P(f^2), f = (m - 1) / (m + 1), |f| <= 0.1716: P interpolated at Chebyshev
#: points (relative error of ln m below 3e-16).
LN_P = (1.0, 0.3333333333333383, 0.19999999999646884, 0.14285714381291126,
        0.11111098424786409, 0.09091821468161111, 0.07656113501554195, 0.07406428274258672)
#: exp r on |r| <= ln2 / 2, interpolated at Chebyshev points (relative error 2.2e-16).
EXP_P = (1.0, 1.0, 0.5000000000000019, 0.1666666666666668, 0.04166666666648666,
         0.00833333333331949, 0.0013888888952696516, 0.00019841269890340666,
         2.4801485074105115e-05, 2.7557240604663896e-06, 2.763279054211718e-07,
         2.511015364692893e-08)


@njit(inline="always", **OPTS)
def _ln(x):
    """ln x for x > 0 (no libm call): exponent and mantissa split on the IEEE bits,
    ``ln m = 2 atanh((m - 1) / (m + 1))`` on [sqrt(1/2), sqrt(2)] by a polynomial in
    ((m - 1) / (m + 1))^2, evaluated by Estrin's scheme (short dependency chains: the loops
    are latency-bound otherwise). Relative error below 1e-15; x = 0 gives about -709."""
    xb = _bits(x)
    m = _from_bits((xb & MANT_MASK) | ONE_BITS)
    e = _from_bits((xb >> 52) | TWO52_BITS) - (4503599627370496.0 + 1023.0)
    big = m > SQRT2
    m = m * 0.5 if big else m
    e = e + 1.0 if big else e
    f = (m - 1.0) / (m + 1.0)
    q = f * f
    q2 = q * q
    q4 = q2 * q2
    c = LN_P
    p = ((c[0] + c[1] * q) + (c[2] + c[3] * q) * q2) + \
        ((c[4] + c[5] * q) + (c[6] + c[7] * q) * q2) * q4
    return e * LN2 + 2.0 * f * p


@njit(inline="always", **OPTS)
def _exp(y):
    """exp(y), y clipped to [-700, 700] (no libm call): ``y = k ln 2 + r`` (ln 2 in two
    parts), ``exp(r)`` by a polynomial of degree 11 evaluated by Estrin's scheme (relative
    error below 1e-15), ``2^k`` added to the exponent bits."""
    y = min(max(y, -700.0), 700.0)
    k = _round(y * (1.0 / LN2))
    r = _reduce_ln2(y, k)
    r2 = r * r
    r4 = r2 * r2
    r8 = r4 * r4
    c = EXP_P
    p = (((c[0] + c[1] * r) + (c[2] + c[3] * r) * r2)
         + ((c[4] + c[5] * r) + (c[6] + c[7] * r) * r2) * r4) \
        + ((c[8] + c[9] * r) + (c[10] + c[11] * r) * r2) * r8
    return _from_bits(_bits(p) + ((_bits(k + MAGIC) - MAGIC_BITS) << 52))


@njit(inline="always", **OPTS)
def _ln0(x):
    """ln x, or LN_ZERO for x <= TINY (so that x^p = exp(p ln x) vanishes for p > 0)."""
    return _ln(x) if x > TINY else LN_ZERO


@njit(inline="always", **OPTS)
def _power(x, code, p):
    """x^p for one element (scalar), specialised like the passes."""
    if code == 0:
        return 1.0
    if code == 1:
        return math.sqrt(x)
    if code == 2:
        return x
    if code == 3:
        return x * math.sqrt(x)
    if code == 4:
        return x * x
    return math.exp(p * math.log(x)) if x > 0.0 else 0.0


@njit(inline="always", **OPTS)
def _speed(v, lnv, code, p):
    """|v|^p inside a term pass: code 0 (p = 0), 2 (p = 1), else exp(p ln|v|)."""
    if code == 0:
        return 1.0
    if code == 2:
        return abs(v)
    return _exp(p * lnv)
