"""The Euler-X kernel: the whole rest -> start -> run -> stop -> rest cycle in one call.

Semi-implicit (symplectic) Euler on plain float64 arrays (PHYSICS section 5; the seed
paper's Eq. 4 with the order of 4d changed: velocities first, then tensions from the new
velocities; the literal forward Euler of Eq. 4d is unstable on an undamped chain).

Elements (masses) and springs (element boundaries, spring j between elements j and j+1)
fall in two groups:

* **free** belt elements and the springs between them are integrated explicitly in
  vectorised passes: ``v' = v + dt (T[j] - T[j-1] - G_j) / M_j`` then the resistance
  ``R0_j clip(v / v_eps, -1, 1)`` applied implicitly in closed form (stable for any v_eps);
* **blocks**: each pulley element with the springs on both its sides and the belt elements
  at their far ends (and the gravity take-up carriage when its pulley is in the block). The
  block's springs are taken implicitly (their tension at the new step, linearised with the
  same tangent stiffness the spring update uses) and its velocities come from one small
  solve (tridiagonal plus the carriage's row and column, eliminated without fill-in),
  together with the PI controller's proportional part, imposed velocities
  (moving support, holding at rest), the torque limit and the carriage end stops. Short,
  stiff springs round light pulleys would otherwise set the step (a 1.9 m spring between a
  head drive and a head take-up pulley needs a step ten times below the belt's ``dx / c``).
  Brakes and holdbacks (stick friction that holds at v = 0) and the resistances act on the
  solved velocities.

Then every spring: strain increment from the new velocities, the elastic tension advanced
with the Ernst tangent modulus (below the floor tension the modulus is constant, and the
elastic tension continues below zero with it: a negative value is the slack strain times
that modulus, so a slack span must be taken up before it pulls again), the damper force by
its exact exponential, total tension ``max(elastic + damper, 0)``, and the envelopes.

Speed (the same equations; each pass checked to vectorise, 4 x double on AVX2): min/max
reductions and envelopes use LLVM's ``minnum``/``maxnum`` (numba's ``min``/``max`` become
compare-and-select, which LLVM neither vectorises as a reduction nor stores
unconditionally); the velocity pass takes the friction solve's division from old values
only, off the path from the old state to the new velocity; ``exp``/``log`` are written on
the IEEE bits with Chebyshev-interpolated polynomials evaluated by Estrin's scheme (numba
without SVML calls scalar libm, and long Horner chains leave these loops latency-bound),
and each resistance term is one loop compiled for its exponents.

The numpy implementation of the same equations is :mod:`engine.dynamics.reference`.
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir as llir
from numba import njit, types, uintp
from numba.core import cgutils
from numba.extending import intrinsic

from engine.dynamics.profiles import FORCE, TORQUE, start_reference, stop_reference

__all__ = ["run_cycle", "FP", "IP", "RES", "REC", "FASTMATH"]

#: LLVM fast-math flags: everything but 'nnan'/'ninf', so divergence checks still see NaN.
FASTMATH = {"nsz", "arcp", "contract", "afn", "reassoc"}
#: For pure reductions (min/max) that LLVM only vectorises without NaN semantics.
FASTMATH_RED = FASTMATH | {"nnan", "ninf"}
#: numba options of every kernel function: error_model="numpy" drops the zero-division
#: checks that would stop LLVM from vectorising the passes.
OPTS = dict(cache=True, nogil=True, fastmath=FASTMATH, error_model="numpy")

(FP_DT, FP_T_PRE, FP_T_START, FP_T_RUN, FP_T_STOP, FP_V_D, FP_V_EPS, FP_EB, FP_E_DAMP,
 FP_G_DAMP, FP_HS_REF, FP_HS_MAX, FP_KP, FP_KI, FP_M_TOT, FP_TU_W, FP_TU_M, FP_TU_LO,
 FP_TU_HI, FP_REC_DT, FP_SURF_DT, FP_STOP_MAX, FP_POST_REST, FP_F_CONST, FP_V_FAIL,
 FP_F_RES, FP_V_FF, FP_T_END, FP_SIZE) = range(29)
(IP_N, IP_START_CTRL, IP_STOP_MODE, IP_FORMULATION, IP_TU_GRAVITY, IP_I_TU, IP_I_TAIL,
 IP_ANY_PS, IP_M_NODE, IP_HOLD_NODE, IP_SIZE) = range(11)
(RES_STATUS, RES_T_END, RES_STEPS, RES_START_ACH, RES_STOP_ACH, RES_VMAX, RES_VMAX_T, RES_VMIN,
 RES_VMIN_T, RES_XMIN, RES_XMAX, RES_FMAX, RES_FMAX_T, RES_PMAX, RES_SLIP_MIN, RES_SLIP_MIN_T,
 RES_ENDSTOP, RES_NREC, RES_NSURF, RES_W_DRIVE, RES_T_STOPCMD, RES_STOPPED, RES_ENDSTOP_T,
 RES_V_MEAN_END, RES_I_END, RES_TMAX, RES_TMAX_T, RES_TMIN, RES_TMIN_T, RES_SLACK,
 RES_SLACK_AT, RES_SIZE) = range(32)
(REC_T, REC_V_DRIVE, REC_V_TAIL, REC_F_DRIVE, REC_T_HEAD_IN, REC_T_HEAD_OUT, REC_T_TAIL,
 REC_T_TAKEUP, REC_X_TU, REC_T_MIN, REC_T_MAX, REC_V_MEAN, REC_F_BRAKE, REC_V_REF, REC_P_DRIVE,
 REC_SIZE) = range(16)

#: Largest block (elements + carriage) the solver takes.
BLOCK_MAX = 12


def _namespace(prefix: str) -> type:
    """A read-only view of the module constants with ``prefix`` for Python callers."""
    names = {k[len(prefix):]: v for k, v in globals().items()
             if k.startswith(prefix) and isinstance(v, int)}
    return type(prefix.rstrip("_"), (), names)


FP = _namespace("FP_")
IP = _namespace("IP_")
RES = _namespace("RES_")
REC = _namespace("REC_")

# status codes
OK, DIVERGED, SLACK = 0, 1, 2
#: Fastest rate [x design speed] at which the belt's own motion can store slack in one span:
#: both its ends moving apart at up to twice the design speed. Slack that grew faster between
#: two looks is a numerical blow-up (a step above the stability limit), not the belt.
SLACK_RATE_MAX = 4.0
#: Slack strain (belt length stored as slack over a span's length) beyond which the 1-D model
#: no longer holds: the belt would pile up or leave the idlers. The run ends as failed.
SLACK_LIMIT = 0.05
# drive modes of one step
FREE, HOLD, IMPOSED, PI, OPEN = 0, 1, 2, 3, 4
# stop modes and formulation codes (model.py)
_BRAKE, _CONTROLLED = 1, 2
_SUPPORT = 1


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
# resistance


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


@njit(**OPTS)
def vlog(x, out):
    """``out = ln(x)`` for x >= 0, vectorised (see :func:`_ln`)."""
    for jj in range(x.shape[0]):
        j = uintp(jj)
        out[j] = _ln(x[j])


@njit(**OPTS)
def vexp(y, out):
    """``out = exp(y)`` for y in [-700, 700], vectorised (see :func:`_exp`). ``out`` may be
    ``y``."""
    for jj in range(y.shape[0]):
        j = uintp(jj)
        out[j] = _exp(y[j])


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


@njit(inline="always", **OPTS)
def _term(r0, c, v, lnv, phi, lnphi, sc, p, qc, q):
    """``r0 += c |v|^p phi^q`` over all elements; ``sc``/``qc`` are literal codes at every
    call, so each call compiles to its own branch-free loop."""
    for jj in range(r0.shape[0]):
        j = uintp(jj)
        r0[j] += c[j] * _speed(v[j], lnv[j], sc, p) * (
            1.0 if qc == 0 else
            (_power(phi[j], qc, q) if qc != 5 else _exp(q * lnphi[j])))


@njit(inline="always", **OPTS)
def _term_sag(r0, c, v, lnv, phi, lnphi, sc, p, qc, q):
    """:func:`_term` with the sag code ``qc`` turned into a literal (``sc`` is one already)."""
    if qc == 0:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 0, q)
    elif qc == 1:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 1, q)
    elif qc == 2:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 2, q)
    elif qc == 3:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 3, q)
    elif qc == 4:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 4, q)
    else:
        _term(r0, c, v, lnv, phi, lnphi, sc, p, 5, q)


@njit(**OPTS)
def resistance(r0, v, tt, coef, pvc, pvv, psc, psv, sw, hs_ref, hs_max, any_ps, phi,
               lnv, lnphi, t_sparse, t_ptr, t_idx):
    """Resistance magnitude ``R0_j = sum_k coef[k, j] |v_j|^pv[k] phi_j^ps[k]`` into r0 [N].

    One vectorised pass per term, compiled for its exponents: speed exponents 0 and 1 need
    no power, others ``exp(p ln|v|)``; sag exponents 0, 0.5, 1, 1.5 and 2 use sqrt and
    products, others ``exp(q ln phi)``. The logarithms are computed once per step; the
    constant term initialises r0. ``phi`` is the sag ratio over the reference from the
    element's mean tension; ``phi``, ``lnv`` and ``lnphi`` are scratch arrays.
    """
    n = r0.shape[0]
    if any_ps:
        phi[0] = min(sw[0] / max(0.5 * (tt[n - 1] + tt[0]), 1.0), hs_max) / hs_ref
        for jj in range(1, n):
            j = uintp(jj)
            phi[j] = min(sw[j] / max(0.5 * (tt[uintp(jj - 1)] + tt[j]), 1.0), hs_max) / hs_ref
    need_lnv = False
    need_lnphi = False
    first = -1
    for k in range(coef.shape[0]):
        if t_sparse[k] == 0:
            need_lnv = need_lnv or (pvc[k] != 0 and pvc[k] != 2)
            need_lnphi = need_lnphi or psc[k] == 5
            if first < 0 and pvc[k] == 0 and psc[k] == 0:
                first = k
    if need_lnv:
        for jj in range(n):
            j = uintp(jj)
            lnv[j] = _ln0(abs(v[j]))
    if need_lnphi:
        for jj in range(n):
            j = uintp(jj)
            lnphi[j] = _ln0(phi[j])
    if first >= 0:
        c = coef[first]
        for jj in range(n):
            j = uintp(jj)
            r0[j] = c[j]
    else:
        for jj in range(n):
            r0[uintp(jj)] = 0.0
    for k in range(coef.shape[0]):
        if k == first:
            continue
        pc = pvc[k]
        sc = 0 if pc == 0 else (2 if pc == 2 else 5)
        qc = psc[k]
        p = pvv[k]
        q = psv[k]
        if t_sparse[k] == 1:
            # a sparse term (a few elements: feed, pulleys, accessories): its elements only
            for i in range(t_ptr[k], t_ptr[k + 1]):
                j = t_idx[i]
                r0[j] += coef[k, j] * _power(abs(v[j]), pc, p) * (
                    _power(phi[j], qc, q) if any_ps else 1.0)
            continue
        c = coef[k]
        # literal speed codes here and literal sag codes in _term_sag: one specialised loop
        # per (speed, sag) pair
        if sc == 0:
            _term_sag(r0, c, v, lnv, phi, lnphi, 0, p, qc, q)
        elif sc == 2:
            _term_sag(r0, c, v, lnv, phi, lnphi, 2, p, qc, q)
        else:
            _term_sag(r0, c, v, lnv, phi, lnphi, 5, p, qc, q)


@njit(inline="always", **OPTS)
def _friction(vs, e, v_eps):
    """Solve ``v = vs - e clip(v / v_eps, -1, 1)`` for v exactly (e >= 0: e = dt R0 / M)."""
    a1 = vs * v_eps / (v_eps + e)
    a2 = vs - math.copysign(e, vs)
    return a1 if abs(vs) <= v_eps + e else a2


# --------------------------------------------------------------------------------------
# vectorised passes


@njit(**OPTS)
def node_pass(a, b, v, tt, hm, grav, r0, v_eps, w):
    """Explicit velocity update of free elements a..b-1 (b <= n - 1, a >= 1); returns
    ``sum w_j v_j`` over them. ``hm = dt / M``."""
    s = 0.0
    for jj in range(a, b):
        # unsigned indices: numba then drops the negative-index wraparound and LLVM vectorises
        j = uintp(jj)
        jm = uintp(jj - 1)
        h = hm[j]
        r = r0[j]
        rp = max(r, 0.0)
        rn = min(r, 0.0)
        vj = v[j]
        vs = vj + h * (tt[j] - tt[jm] - grav[j] - rn * min(max(vj / v_eps, -1.0), 1.0))
        # _friction, with its division computed from old values only (off the path from
        # the old state to the new velocity)
        e = h * rp
        den = v_eps + e
        a1 = _mul_strict(vs, v_eps / den)
        a2 = vs - math.copysign(e, vs)
        vn = a1 if abs(vs) <= den else a2
        v[j] = vn
        s += w[j] * vn
    return s


@njit(inline="always", **OPTS)
def _spring(e0, d0, dv, dlj, cdt, tfl, kfl_eb, aeb, eb, e_damp, g_damp):
    """One spring: elastic and damper tension after the strain increment
    ``dv * dl + cdt`` (dl = dt / len, cdt = carriage term). Returns (elastic, damper, total).

    An increment that carries the elastic tension from above the floor ``tfl`` to below it
    continues there with the floor modulus ``kfl = kfl_eb EB``: the tangent law followed along the path,
    so a sudden unloading (a take-up carriage hitting its end stop) stores the slack strain
    the motion made, not that strain times the stiff modulus it started from."""
    de = dv * dlj + cdt
    tc = max(e0, tfl)
    t3 = tc * tc * tc
    sm = t3 + aeb
    q = 1.0 / (t3 * sm)  # the one division: kt = EB t3 / sm and kfl / kt = kfl sm / (EB t3)
    kt = eb * (t3 * t3 * q)
    e1 = e0 + kt * de
    # below the floor the rest of the increment at kfl; kfl <= kt, so the larger of the two
    # is right on both sides of the floor (and kfl / kt = 1 when e0 is at or below it)
    e1 = max(e1, tfl + (e1 - tfl) * (kfl_eb * (sm * sm * q)))
    d1 = e_damp * d0 + g_damp * kt * de
    d1 = d1 if e1 >= 0.0 else 0.0
    return e1, d1, max(e1 + d1, 0.0)


@njit(**OPTS)
def spring_pass(a, b, v, te, td, tt, dl, t_floor, kfl_eb, a_eb, eb, e_damp, g_damp):
    """Update springs a..b-1 (b <= n - 1) from the new velocities."""
    for jj in range(a, b):
        j = uintp(jj)
        e1, d1, t1 = _spring(te[j], td[j], v[uintp(jj + 1)] - v[j], dl[j], 0.0, t_floor[j],
                             kfl_eb[j], a_eb[j], eb, e_damp, g_damp)
        te[j] = e1
        td[j] = d1
        tt[j] = t1


@njit(cache=True, nogil=True, fastmath=FASTMATH_RED, error_model="numpy")
def observe(tt, v, t_max, t_min):
    """Envelopes of every spring and the extremes of tension and speed, in one pass.

    Returns (min tension, max tension, min speed, max speed). A separate function: the
    reductions may drop NaN semantics here (divergence is checked on the speed sum).
    """
    lo = tt[0]
    hi = tt[0]
    vlo = v[0]
    vhi = v[0]
    for jj in range(tt.shape[0]):
        j = uintp(jj)
        t1 = tt[j]
        vj = v[j]
        t_max[j] = _fmax(t_max[j], t1)
        t_min[j] = _fmin(t_min[j], t1)
        lo = _fmin(lo, t1)
        hi = _fmax(hi, t1)
        vlo = _fmin(vlo, vj)
        vhi = _fmax(vhi, vj)
    return lo, hi, vlo, vhi


@njit(cache=True, nogil=True, fastmath=FASTMATH_RED, error_model="numpy")
def extremes(x):
    """(min, max) of an array."""
    lo = x[0]
    hi = x[0]
    for jj in range(1, x.shape[0]):
        j = uintp(jj)
        lo = _fmin(lo, x[j])
        hi = _fmax(hi, x[j])
    return lo, hi


@njit(**OPTS)
def slack_min(te, kfl_eb, eb):
    """min(0, min_j te_j / k_floor_j) with k_floor = kfl_eb EB: the largest slack strain
    (negative). Called at the records only, so the division costs little."""
    worst = 0.0
    for jj in range(te.shape[0]):
        j = uintp(jj)
        worst = _fmin(worst, te[j] / (kfl_eb[j] * eb))
    return worst


# --------------------------------------------------------------------------------------
# blocks


@njit(**OPTS)
def solve_dense(A, b, m):
    """Solve A[:m, :m] x = b[:m] in place (Gaussian elimination, partial pivoting); x in b."""
    for k in range(m):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, m):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                p = i
        if p != k:
            for c in range(m):
                tmp = A[k, c]
                A[k, c] = A[p, c]
                A[p, c] = tmp
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
        piv = A[k, k]
        for i in range(k + 1, m):
            f = A[i, k] / piv
            if f != 0.0:
                for c in range(k, m):
                    A[i, c] -= f * A[k, c]
                b[i] -= f * b[k]
    for k in range(m - 1, -1, -1):
        s = b[k]
        for c in range(k + 1, m):
            s -= A[k, c] * b[c]
        b[k] = s / A[k, k]


@njit(inline="always", **OPTS)
def solve_arrow(d, lo, up, cl, rw, x, m, car, car_free):
    """Solve a block's system in place (x holds the right-hand side, then the solution).

    The block matrix is tridiagonal over the ``m`` element rows (``lo[k] = A[k, k-1]``,
    ``d[k] = A[k, k]``, ``up[k] = A[k, k+1]``) with, when ``car``, the carriage column
    ``cl[k] = A[k, m]`` and row ``rw[k] = A[m, k]``, ``d[m] = A[m, m]``; ``car_free`` False
    means the carriage row is the identity (``x[m]`` already holds its imposed speed).
    Eliminating the element unknowns from both ends of the chain inwards, then the
    carriage, makes no fill-in. No pivoting: the free rows are symmetric
    positive definite (mass, controller gain and resistance slope on the diagonal plus each
    implicit spring's ``B g g^T`` with ``g = e_{k+1} - e_k (+ e_m)``, B >= 0), and an
    identity row of an imposed or stuck unknown only moves its value to the right-hand
    side, leaving a principal submatrix: every pivot is positive. Returns False if one is
    not (nothing then is reliable in x, use :func:`solve_dense`).
    """
    # eliminate from both ends towards the middle row (halves the chain of dependent
    # divisions); the carriage row collects from each side separately
    mid = m // 2
    dml = 0.0
    xml = 0.0
    for k in range(mid):  # unknown k out of row k + 1 (and the carriage row)
        piv = d[k]
        if not piv > 0.0:
            return False
        ip = 1.0 / piv
        d[k] = ip  # the back substitution multiplies by the pivot's reciprocal
        f = lo[k + 1] * ip
        d[k + 1] -= f * up[k]
        x[k + 1] -= f * x[k]
        if car:
            cl[k + 1] -= f * cl[k]
        if car_free:
            g = rw[k] * ip
            rw[k + 1] -= g * up[k]
            dml -= g * cl[k]
            xml -= g * x[k]
    dmr = 0.0
    xmr = 0.0
    for k in range(m - 1, mid, -1):  # unknown k out of row k - 1 (and the carriage row)
        piv = d[k]
        if not piv > 0.0:
            return False
        ip = 1.0 / piv
        d[k] = ip
        f = up[k - 1] * ip
        d[k - 1] -= f * lo[k]
        x[k - 1] -= f * x[k]
        if car:
            cl[k - 1] -= f * cl[k]
        if car_free:
            g = rw[k] * ip
            rw[k - 1] -= g * lo[k]
            dmr -= g * cl[k]
            xmr -= g * x[k]
    piv = d[mid]
    if not piv > 0.0:
        return False
    ip = 1.0 / piv
    d[mid] = ip
    if car_free:
        g = rw[mid] * ip
        dm = (d[m] + (dml + dmr)) - g * cl[mid]
        if not dm > 0.0:
            return False
        x[m] = ((x[m] + (xml + xmr)) - g * x[mid]) / dm
    s = x[mid]
    if car:
        s -= cl[mid] * x[m]
    x[mid] = s * ip
    for k in range(mid - 1, -1, -1):
        s = x[k] - up[k] * x[k + 1]
        if car:
            s -= cl[k] * x[m]
        x[k] = s * d[k]
    for k in range(mid + 1, m):
        s = x[k] - lo[k] * x[k - 1]
        if car:
            s -= cl[k] * x[m]
        x[k] = s * d[k]
    return True


@njit(inline="always", **OPTS)
def _constrain(dg, lo, up, cl, rw, rhs, fixed, fixv, stuck, car, car_fixed, car_v, m,
               wd, wl, wu, wc, wr, sol):
    """Working copy of a block's band for the solve: imposed velocities, stuck elements and
    a carriage at its end stop get identity rows."""
    for k in range(m):
        if fixed[k] == 1.0 or stuck[k] == 1.0:
            wd[k] = 1.0
            wl[k] = 0.0
            wu[k] = 0.0
            wc[k] = 0.0
            sol[k] = fixv[k] if fixed[k] == 1.0 else 0.0
        else:
            wd[k] = dg[k]
            wl[k] = lo[k]
            wu[k] = up[k]
            wc[k] = cl[k]
            sol[k] = rhs[k]
        wr[k] = rw[k]
    if car:
        if car_fixed:
            wd[m] = 1.0
            sol[m] = car_v
        else:
            wd[m] = dg[m]
            sol[m] = rhs[m]


@njit(inline="always", **OPTS)
def _offdiag(lo, up, cl, x, k, m, car):
    """Sum of A[k, c] x[c] over c != k for an element row of a block's band."""
    s = 0.0
    if k > 0:
        s += lo[k] * x[k - 1]
    if k + 1 < m:
        s += up[k] * x[k + 1]
    if car:
        s += cl[k] * x[m]
    return s


@njit(**OPTS)
def _solve_band_dense(wd, wl, wu, wc, wr, sol, m, car, car_fixed, Ac):
    """Fallback of :func:`solve_arrow`: the same band system, dense with partial pivoting."""
    mu = m + 1 if car else m
    for r in range(mu):
        for c in range(mu):
            Ac[r, c] = 0.0
    for k in range(m):
        Ac[k, k] = wd[k]
        if k > 0:
            Ac[k, k - 1] = wl[k]
        if k + 1 < m:
            Ac[k, k + 1] = wu[k]
        if car:
            Ac[k, m] = wc[k]
            if not car_fixed:
                Ac[m, k] = wr[k]
    if car:
        Ac[m, m] = wd[m]
    solve_dense(Ac, sol, mu)


# --------------------------------------------------------------------------------------


@njit(**OPTS)
def run_cycle(fp, ip, mass, hm, gravity, sw, coef, pvc, pvv, psc, psv, w_mean,
              t_sparse, t_ptr, t_idx, dl, a_eb, t_floor, kfl_eb, car_ind, seg_node,
              seg_spring, blk_ptr, blk_nodes, blk_car,
              node_drive, node_hb, d_node, d_share, d_lim, d_euler, b_node, b_force, b_delay,
              v, te, td, tt, state, probes, surf_idx,
              rec, rec_t, rec_v, surf_t, surf_v, t_max, t_min, t_max_t, t_min_t, d_force, res):
    """Integrate the whole cycle (see the module docstring for one step).

    Arrays are prepared by :func:`engine.dynamics.simulate.prepare`. State arrays ``v, te,
    td, tt`` (velocity, elastic, damper and total tension) and ``state = [x_takeup,
    u_takeup, integrator, hold_force]`` are updated in place and hold the final state on
    return. ``res`` receives the scalars of :data:`RES`, ``rec``/``rec_t``/``rec_v`` the key
    points every ``record_dt`` and ``surf_t``/``surf_v`` the surface every ``surface_dt``;
    ``t_max``/``t_min`` are the per-spring envelopes, ``t_max_t``/``t_min_t`` their times at
    the resolution of ``record_dt``.
    """
    n = ip[IP_N]
    dt = fp[FP_DT]
    t_pre = fp[FP_T_PRE]
    t_start = fp[FP_T_START]
    t_stopcmd = t_pre + t_start + fp[FP_T_RUN]
    t_stopdur = fp[FP_T_STOP]
    v_d = fp[FP_V_D]
    v_eps = fp[FP_V_EPS]
    eb = fp[FP_EB]
    e_damp = fp[FP_E_DAMP]
    g_damp = fp[FP_G_DAMP]
    kp = fp[FP_KP]
    ki = fp[FP_KI]
    m_tot = fp[FP_M_TOT]
    tu_w = fp[FP_TU_W]
    tu_m = fp[FP_TU_M]
    tu_lo = fp[FP_TU_LO]
    tu_hi = fp[FP_TU_HI]
    rec_dt = fp[FP_REC_DT]
    surf_dt = fp[FP_SURF_DT]
    post_rest = fp[FP_POST_REST]
    f_const = fp[FP_F_CONST]
    f_res = fp[FP_F_RES]
    v_ff = fp[FP_V_FF]
    v_fail = fp[FP_V_FAIL]
    start_ctrl = ip[IP_START_CTRL]
    stop_mode = ip[IP_STOP_MODE]
    support = ip[IP_FORMULATION] == _SUPPORT
    i_tu = ip[IP_I_TU]
    i_tail = ip[IP_I_TAIL]
    any_ps = ip[IP_ANY_PS] == 1
    m_node = ip[IP_M_NODE]
    hold_node = ip[IP_HOLD_NODE]
    nd = d_share.shape[0]
    nb = b_node.shape[0]
    nblk = blk_ptr.shape[0] - 1
    nrec_max = rec.shape[0]
    nsurf_max = surf_t.shape[0]
    law_const = pvc.shape[0] == 1 and pvc[0] == 0 and psc[0] == 0

    x_tu = state[0]
    u_tu = state[1]
    integ = state[2]
    hold_f = state[3]
    w_sum = 0.0
    for j in range(n):
        w_sum += w_mean[j]
    inv_w_sum = 1.0 / w_sum

    r0 = np.empty(n)
    phi = np.empty(n)
    lnv = np.empty(n)
    lnphi = np.empty(n)
    if law_const:
        for j in range(n):
            r0[j] = coef[0, j]
    t_max_snap = np.empty(n)
    t_min_snap = np.empty(n)
    for j in range(n):
        t_max[j] = tt[j]
        t_min[j] = tt[j]
        t_max_t[j] = 0.0
        t_min_t[j] = 0.0
        t_max_snap[j] = tt[j]
        t_min_snap[j] = tt[j]
    Ac = np.zeros((BLOCK_MAX, BLOCK_MAX))  # dense fallback of the band solve
    # block matrix as a band: tridiagonal element rows plus the carriage column and row
    dg = np.zeros(BLOCK_MAX)  # A[k, k] (A[m, m] for the carriage)
    lo = np.zeros(BLOCK_MAX)  # A[k, k-1]
    up = np.zeros(BLOCK_MAX)  # A[k, k+1]
    cl = np.zeros(BLOCK_MAX)  # A[k, m]
    rw = np.zeros(BLOCK_MAX)  # A[m, k]
    dg0 = np.zeros(BLOCK_MAX)  # the parts of A[k, k] and rhs[k] the active set leaves alone
    rhs0 = np.zeros(BLOCK_MAX)
    wd = np.zeros(BLOCK_MAX)  # working copy of the band for the solve
    wl = np.zeros(BLOCK_MAX)
    wu = np.zeros(BLOCK_MAX)
    wc = np.zeros(BLOCK_MAX)
    wr = np.zeros(BLOCK_MAX)
    rpos = np.zeros(BLOCK_MAX)  # resistance magnitude per block element
    fexp = np.zeros(BLOCK_MAX)  # explicit forces (gravity, negative resistance)
    fz = np.zeros(BLOCK_MAX)  # resistance zone: -1, 0 (linear), +1
    stuck = np.zeros(BLOCK_MAX)  # brake / holdback holding the element at rest
    bdir = np.zeros(BLOCK_MAX)  # direction of motion of a slipping brake
    bforce = np.zeros(BLOCK_MAX)  # active brake force
    c_lo = np.zeros(BLOCK_MAX)  # reaction range of the stick
    c_hi = np.zeros(BLOCK_MAX)
    rhs = np.zeros(BLOCK_MAX)
    sol = np.zeros(BLOCK_MAX)
    bA = np.zeros(BLOCK_MAX)
    bB = np.zeros(BLOCK_MAX)
    v_old = np.zeros(BLOCK_MAX)
    fixed = np.zeros(BLOCK_MAX)  # imposed velocity flag per block unknown
    fixv = np.zeros(BLOCK_MAX)
    fdrv = np.zeros(BLOCK_MAX)  # explicit drive force per block element
    p_diag = np.zeros(BLOCK_MAX)  # implicit controller gain per block element
    # per block-element constants
    nbe = blk_nodes.shape[0]
    be_mdt = np.empty(nbe)  # M / dt
    be_left = np.empty(nbe, np.int64)  # spring on the element's left
    for p in range(nbe):
        j = blk_nodes[p]
        be_mdt[p] = mass[j] / dt
        be_left[p] = j - 1 if j > 0 else n - 1
    inv_veps = 1.0 / v_eps
    tu_mdt = tu_m / dt

    status = OK
    vmax = 0.0
    vmax_t = 0.0
    vmin = 0.0
    vmin_t = 0.0
    gmax, gmin = tt[0], tt[0]
    for j in range(n):
        gmax = max(gmax, tt[j])
        gmin = min(gmin, tt[j])
    gmax_t = 0.0
    gmin_t = 0.0
    xmin = x_tu
    xmax = x_tu
    fmax = 0.0
    fmax_t = 0.0
    pmax = 0.0
    slip_min = 1e300
    slip_min_t = 0.0
    endstop = 0
    endstop_t = -1.0
    w_drive = 0.0
    start_ach = -1.0
    stop_ach = -1.0
    stopped = False
    t_end_limit = t_stopcmd + fp[FP_STOP_MAX] + post_rest
    if fp[FP_T_END] > 0.0:
        t_end_limit = min(t_end_limit, fp[FP_T_END])
    pi_started = False
    f_tot = 0.0
    p_tot = 0.0
    f_brake = 0.0
    v_ref = 0.0
    max_steps = int(t_end_limit / dt) + 2
    step = 0
    t_new = 0.0

    v_mean = 0.0
    for j in range(n):
        v_mean += w_mean[j] * v[j]
    v_mean *= inv_w_sum
    nrec = _record(0, nrec_max, 0.0, v, tt, n, m_node, i_tail, i_tu, x_tu, 0.0, v_mean, 0.0,
                   0.0, 0.0, gmin, gmax, probes, rec, rec_t, rec_v)
    nsurf = _record_surface(0, nsurf_max, 0.0, v, tt, surf_idx, surf_t, surf_v)

    while step < max_steps:
        step += 1
        t_new = step * dt
        # ---------------------------------------------------------------- phase
        started = t_new > t_pre
        stopping = t_new > t_stopcmd
        a_ref = 0.0
        if not stopping:
            v_ref, a_ref = start_reference(start_ctrl, t_new - t_pre, t_start, v_d)
        elif stop_mode == _CONTROLLED:
            v_ref, a_ref = stop_reference(t_new - t_stopcmd, t_stopdur, v_d)
        else:
            v_ref = 0.0
        if not started:
            mode = HOLD
        elif support:
            mode = IMPOSED if (not stopping or stop_mode == _CONTROLLED) else FREE
        elif start_ctrl == FORCE and not stopping:
            mode = OPEN
        elif not stopping or stop_mode == _CONTROLLED:
            mode = PI
        else:
            mode = FREE
        if mode == PI and not pi_started:
            integ = hold_f
            pi_started = True
        ramp = 1.0
        if start_ctrl == TORQUE and not stopping:
            ramp = min(max((t_new - t_pre) / t_start, 0.0), 1.0)
        # rigid-body feedforward: inertia plus the running resistance (Te less the net
        # gravity, which the integrator already holds from rest), regularised like the belt
        f_ff = m_tot * a_ref + f_res * min(max(v_ref / v_ff, 0.0), 1.0)
        braking = stopping and stop_mode == _BRAKE

        # ---------------------------------------------------------------- resistances
        if not law_const:
            resistance(r0, v, tt, coef, pvc, pvv, psc, psv, sw, fp[FP_HS_REF], fp[FP_HS_MAX],
                       any_ps, phi, lnv, lnphi, t_sparse, t_ptr, t_idx)

        # ---------------------------------------------------------------- free elements
        vsum = 0.0
        for k in range(seg_node.shape[0]):
            vsum += node_pass(seg_node[k, 0], seg_node[k, 1], v, tt, hm, gravity, r0, v_eps,
                              w_mean)

        # ---------------------------------------------------------------- blocks
        # Unknowns: the block's element velocities (and the carriage speed). Each element's
        # row is its momentum balance in force units,
        #   M/dt v' - (T'_right - T'_left) + R0 clip(v'/v_eps) + P v' = M/dt v - G + F + C,
        # with the implicit springs T' = A + B (v'_{k+1} - v'_k + u'), the controller's
        # proportional gain P, explicit drive forces F and the stick reaction C of a brake or
        # holdback. Piecewise-linear parts are resolved by an active set: the resistance zone
        # (linear below v_eps, constant above), brake slip direction or stick, holdback
        # stick, torque limit, carriage end stop; the solve is repeated until consistent.
        f_tot = 0.0
        p_tot = 0.0
        f_brake = 0.0
        u_new = u_tu
        for bk in range(nblk):
            p0 = blk_ptr[bk]
            m = blk_ptr[bk + 1] - p0
            car = blk_car[bk] == 1
            # element setup
            master_k = -1
            for k in range(m):
                j = blk_nodes[p0 + k]
                if k < m - 1:
                    # implicit spring k between block elements k and k+1 (spring index j)
                    e0 = te[j]
                    if e0 < 0.0:
                        bA[k] = 0.0
                        bB[k] = 0.0
                    else:
                        tc = max(e0, t_floor[j])
                        t3 = tc * tc * tc
                        f = eb * t3 / (t3 + a_eb[j]) * (1.0 + g_damp)
                        bA[k] = e0 + e_damp * td[j]
                        bB[k] = f * dl[j]
                vo = v[j]
                v_old[k] = vo
                fixed[k] = 0.0
                fdrv[k] = 0.0
                p_diag[k] = 0.0
                r = r0[j]
                rpos[k] = max(r, 0.0)
                # a negative resistance (a force that drives) is applied explicitly
                fexp[k] = -min(r, 0.0) * min(max(vo / v_eps, -1.0), 1.0) - gravity[j]
                fz[k] = 1.0 if vo > v_eps else (-1.0 if vo < -v_eps else 0.0)
                fb = 0.0
                if braking:
                    for bi in range(nb):
                        if b_node[bi] == j and t_new > t_stopcmd + b_delay[bi]:
                            fb += b_force[bi]
                hb = node_hb[j] == 1
                c_lo[k] = -fb
                c_hi[k] = 1e300 if hb else fb
                can_stick = fb > 0.0 or hb
                stuck[k] = 1.0 if (can_stick and (abs(vo) <= 1e-12 or (hb and vo < 0.0))) \
                    else 0.0
                bdir[k] = 1.0 if vo >= 0.0 else -1.0
                bforce[k] = fb
                # the parts of the row the active set does not change
                mdt = be_mdt[p0 + k]
                d = mdt
                r = mdt * vo + fexp[k]
                c_k = 0.0
                if k == 0:
                    r -= tt[be_left[p0]]
                    lo[k] = 0.0
                else:
                    d += bB[k - 1]
                    lo[k] = -bB[k - 1]
                    r -= bA[k - 1]
                    if car:
                        c_k += bB[k - 1] * car_ind[blk_nodes[p0 + k - 1]]
                if k == m - 1:
                    r += tt[j]
                    up[k] = 0.0
                else:
                    d += bB[k]
                    up[k] = -bB[k]
                    r += bA[k]
                    if car:
                        c_k -= bB[k] * car_ind[j]
                cl[k] = c_k
                dg0[k] = d
                rhs0[k] = r
                rw[k] = 0.0
                if mode == HOLD and j == hold_node:
                    fixed[k] = 1.0
                    fixv[k] = 0.0
                dk = node_drive[j]
                if dk < 0 or mode == HOLD:
                    continue
                if mode == IMPOSED:
                    fixed[k] = 1.0
                    fixv[k] = v_ref
                elif mode == PI:
                    # load sharing: every drive takes its share of the feedforward and the
                    # integral part; the master alone adds the proportional correction
                    if dk == 0:
                        master_k = k
                        p_diag[k] = kp
                        fdrv[k] = d_share[0] * (f_ff + integ) + kp * v_ref
                    else:
                        lim = d_lim[dk] * ramp + d_share[dk] * abs(hold_f) * (1.0 - ramp)
                        fdrv[k] = min(max(d_share[dk] * (f_ff + integ), -lim), lim)
                elif mode == OPEN:
                    fdrv[k] = d_share[dk] * f_const
            if car:
                d = tu_mdt
                r = tu_mdt * u_tu + tu_w
                for k in range(m - 1):
                    if car_ind[blk_nodes[p0 + k]] != 0.0:
                        # T' = A + B (v'_{k+1} - v'_k + u'): the carriage stretches
                        # both take-up springs
                        rw[k + 1] += bB[k]
                        rw[k] -= bB[k]
                        d += bB[k]
                        r -= bA[k]
                dg[m] = d
                rhs[m] = r
            car_fixed = False
            car_v = 0.0
            sat = False
            for _it in range(16):
                # the diagonal and right-hand side the active set changes
                for k in range(m):
                    d = dg0[k] + p_diag[k]
                    r = rhs0[k] + fdrv[k]
                    if fz[k] == 0.0:
                        d += rpos[k] * inv_veps
                    else:
                        r -= fz[k] * rpos[k]
                    if bforce[k] > 0.0 and stuck[k] == 0.0:
                        r -= bdir[k] * bforce[k]
                    dg[k] = d
                    rhs[k] = r
                    # constrained copy: imposed velocities and stuck elements
                    if fixed[k] == 1.0 or stuck[k] == 1.0:
                        wd[k] = 1.0
                        wl[k] = 0.0
                        wu[k] = 0.0
                        wc[k] = 0.0
                        sol[k] = fixv[k] if fixed[k] == 1.0 else 0.0
                    else:
                        wd[k] = d
                        wl[k] = lo[k]
                        wu[k] = up[k]
                        wc[k] = cl[k]
                        sol[k] = r
                    wr[k] = rw[k]
                if car:  # the carriage at an end stop
                    if car_fixed:
                        wd[m] = 1.0
                        sol[m] = car_v
                    else:
                        wd[m] = dg[m]
                        sol[m] = rhs[m]
                if not solve_arrow(wd, wl, wu, wc, wr, sol, m, car, car and not car_fixed):
                    _constrain(dg, lo, up, cl, rw, rhs, fixed, fixv, stuck, car, car_fixed,
                               car_v, m, wd, wl, wu, wc, wr, sol)
                    _solve_band_dense(wd, wl, wu, wc, wr, sol, m, car, car_fixed, Ac)
                # consistency checks
                again = False
                if master_k >= 0 and not sat:
                    lim = d_lim[0] * ramp + d_share[0] * abs(hold_f) * (1.0 - ramp)
                    fm = d_share[0] * (f_ff + integ) + kp * (v_ref - sol[master_k])
                    if abs(fm) > lim:
                        sat = True
                        p_diag[master_k] = 0.0
                        fdrv[master_k] = math.copysign(lim, fm)
                        again = True
                if car and not car_fixed:
                    x_try = x_tu + dt * sol[m]
                    if x_try > tu_hi or x_try < tu_lo:
                        car_fixed = True
                        car_v = ((tu_hi if x_try > tu_hi else tu_lo) - x_tu) / dt
                        endstop += 1
                        if endstop_t < 0.0:
                            endstop_t = t_new
                        again = True
                for k in range(m):
                    if fixed[k] == 1.0:
                        fz[k] = 1.0 if fixv[k] > v_eps else (-1.0 if fixv[k] < -v_eps else 0.0)
                        continue
                    vk = sol[k]
                    if stuck[k] == 1.0:
                        # reaction the stick must give: row residual at v' = 0
                        c_r = _offdiag(lo, up, cl, sol, k, m, car) - rhs[k]
                        if c_r > c_hi[k] or c_r < c_lo[k]:
                            stuck[k] = 0.0
                            bdir[k] = -1.0 if c_r > c_hi[k] else 1.0
                            again = True
                    else:
                        if c_hi[k] > 1e299 and vk < 0.0:
                            stuck[k] = 1.0  # holdback engages
                            again = True
                        elif bforce[k] > 0.0 and vk * bdir[k] < 0.0:
                            stuck[k] = 1.0  # the brake stops the element
                            again = True
                    z = 1.0 if sol[k] > v_eps else (-1.0 if sol[k] < -v_eps else 0.0)
                    if stuck[k] == 1.0:
                        z = 0.0
                    if z != fz[k]:
                        fz[k] = z
                        again = True
                if not again:
                    break
            if car:
                u_new = sol[m]
            # velocities, drive forces and the controller
            for k in range(m):
                j = blk_nodes[p0 + k]
                vn = sol[k]
                v[j] = vn
                vsum += w_mean[j] * vn
                if bforce[k] > 0.0:
                    if stuck[k] == 1.0:
                        c_r = _offdiag(lo, up, cl, sol, k, m, car) - rhs[k]
                        f_brake += abs(c_r)
                    else:
                        f_brake += bforce[k]
                dk = node_drive[j]
                if mode == HOLD and j == hold_node:
                    # the force that holds the belt at rest: residual of the element's free row
                    f = dg[k] * vn - rhs[k] + _offdiag(lo, up, cl, sol, k, m, car)
                    hold_f = f
                if dk < 0:
                    continue
                if fixed[k] == 1.0 and mode != HOLD:
                    # the force the drive gives: residual of the element's free row
                    f = dg[k] * vn - rhs[k] + _offdiag(lo, up, cl, sol, k, m, car)
                    f += fdrv[k] - p_diag[k] * vn
                elif k == master_k and not sat:
                    f = d_share[0] * (f_ff + integ) + kp * (v_ref - vn)
                else:
                    f = fdrv[k]
                d_force[dk] = f
                f_tot += f
                p_tot += f * vn
                w_drive += f * 0.5 * (v_old[k] + vn) * dt
                if dk == 0:
                    if mode == PI:
                        # conditional integration: not further into the torque limit
                        e_v = v_ref - vn
                        if not sat or e_v * fdrv[k] < 0.0:
                            integ += dt * ki * e_v
            # implicit springs of the block
            for k in range(m - 1):
                s = blk_nodes[p0 + k]
                s1 = blk_nodes[p0 + k + 1]
                e1, d1, t1 = _spring(te[s], td[s], v[s1] - v[s], dl[s],
                                     car_ind[s] * u_new * dl[s] if car else 0.0, t_floor[s],
                                     kfl_eb[s], a_eb[s], eb, e_damp, g_damp)
                te[s] = e1
                td[s] = d1
                tt[s] = t1
        if ip[IP_TU_GRAVITY] == 1:
            u_tu = u_new
            x_tu += dt * u_tu
            x_tu = min(max(x_tu, tu_lo), tu_hi)
            xmin = min(xmin, x_tu)
            xmax = max(xmax, x_tu)

        # ---------------------------------------------------------------- free springs
        for k in range(seg_spring.shape[0]):
            spring_pass(seg_spring[k, 0], seg_spring[k, 1], v, te, td, tt, dl, t_floor,
                        kfl_eb, a_eb, eb, e_damp, g_damp)

        # ---------------------------------------------------------------- checks
        v_mean = vsum * inv_w_sum
        tlo, thi, vlo, vhi = observe(tt, v, t_max, t_min)
        if not math.isfinite(vsum) or vhi > v_fail or vlo < -v_fail:
            status = DIVERGED
            break
        if vhi > vmax:
            vmax = vhi
            vmax_t = t_new
        if vlo < vmin:
            vmin = vlo
            vmin_t = t_new
        if thi > gmax:
            gmax = thi
            gmax_t = t_new
        if tlo < gmin:
            gmin = tlo
            gmin_t = t_new
        if started:
            af = abs(f_tot)
            if af > fmax:
                fmax = af
                fmax_t = t_new
            if abs(p_tot) > pmax:
                pmax = abs(p_tot)
            for k in range(nd):
                j = d_node[k]
                jm = j - 1 if j > 0 else n - 1
                hi_ = max(tt[j], tt[jm])
                lo_ = max(min(tt[j], tt[jm]), 1.0)
                mg = d_euler[k] * lo_ / hi_ if hi_ > 0.0 else 1e300
                if mg < slip_min:
                    slip_min = mg
                    slip_min_t = t_new
            if start_ach < 0.0 and v_mean >= 0.99 * v_d:
                start_ach = t_new - t_pre
        if stopping and not stopped and v_mean < 0.01 * v_d:
            stopped = True
            stop_ach = t_new - t_stopcmd
            t_end_limit = min(t_end_limit, t_new + post_rest)
            if fp[FP_T_END] > 0.0:
                t_end_limit = min(t_end_limit, fp[FP_T_END])

        # ---------------------------------------------------------------- records
        if t_new + 0.5 * dt >= nrec * rec_dt:
            worst = slack_min(te, kfl_eb, eb)
            if worst < -SLACK_LIMIT:
                worst_j = 0
                for j in range(n):
                    if te[j] / (kfl_eb[j] * eb) == worst:
                        worst_j = j
                        break
                # slack of a span's length plus what the belt's motion could add since the
                # last look is beyond any physical motion: a numerical blow-up
                span = dt / dl[worst_j]
                reach = span + SLACK_RATE_MAX * v_d * (rec_dt + dt)
                status = SLACK if -worst * span <= reach else DIVERGED
                res[RES_SLACK] = -worst
                res[RES_SLACK_AT] = worst_j
                break
            nrec = _record(nrec, nrec_max, t_new, v, tt, n, m_node, i_tail, i_tu, x_tu, f_tot,
                           v_mean, f_brake, v_ref, p_tot, tlo, thi, probes, rec, rec_t, rec_v)
            _envelope_times(t_new, t_max, t_min, t_max_snap, t_min_snap, t_max_t, t_min_t)
        if t_new + 0.5 * dt >= nsurf * surf_dt:
            nsurf = _record_surface(nsurf, nsurf_max, t_new, v, tt, surf_idx, surf_t, surf_v)
        if t_new >= t_end_limit:
            break

    if status != DIVERGED and nrec > 0 and rec[nrec - 1, REC_T] < t_new - 0.5 * dt:
        tlo, thi = extremes(tt)
        nrec = _record(nrec, nrec_max, t_new, v, tt, n, m_node, i_tail, i_tu, x_tu, f_tot,
                       v_mean, f_brake, v_ref, p_tot, tlo, thi, probes, rec, rec_t, rec_v)
    _envelope_times(t_new, t_max, t_min, t_max_snap, t_min_snap, t_max_t, t_min_t)
    state[0] = x_tu
    state[1] = u_tu
    state[2] = integ
    state[3] = hold_f
    res[RES_STATUS] = status
    res[RES_T_END] = t_new
    res[RES_STEPS] = step
    res[RES_START_ACH] = start_ach
    res[RES_STOP_ACH] = stop_ach
    res[RES_VMAX] = vmax
    res[RES_VMAX_T] = vmax_t
    res[RES_VMIN] = vmin
    res[RES_VMIN_T] = vmin_t
    res[RES_XMIN] = xmin
    res[RES_XMAX] = xmax
    res[RES_FMAX] = fmax
    res[RES_FMAX_T] = fmax_t
    res[RES_PMAX] = pmax
    res[RES_SLIP_MIN] = slip_min
    res[RES_SLIP_MIN_T] = slip_min_t
    res[RES_ENDSTOP] = endstop
    res[RES_NREC] = nrec
    res[RES_NSURF] = nsurf
    res[RES_W_DRIVE] = w_drive
    res[RES_T_STOPCMD] = t_stopcmd
    res[RES_STOPPED] = 1.0 if stopped else 0.0
    res[RES_ENDSTOP_T] = endstop_t
    res[RES_V_MEAN_END] = v_mean
    res[RES_I_END] = integ
    res[RES_TMAX] = gmax
    res[RES_TMAX_T] = gmax_t
    res[RES_TMIN] = gmin
    res[RES_TMIN_T] = gmin_t
    return status


@njit(**OPTS)
def _envelope_times(t, t_max, t_min, snap_max, snap_min, t_max_t, t_min_t):
    """Stamp the springs whose envelope grew since the last record with time t."""
    for jj in range(t_max.shape[0]):
        # the envelopes only grow, so the snapshots can be copied unconditionally (selects
        # and plain stores: LLVM vectorises them)
        j = uintp(jj)
        hi = t_max[j]
        lo = t_min[j]
        t_max_t[j] = t if hi > snap_max[j] else t_max_t[j]
        t_min_t[j] = t if lo < snap_min[j] else t_min_t[j]
        snap_max[j] = hi
        snap_min[j] = lo


@njit(**OPTS)
def _record(nrec, nrec_max, t, v, tt, n, m_node, i_tail, i_tu, x_tu, f_tot, v_mean, f_brake,
            v_ref, p_tot, tlo, thi, probes, rec, rec_t, rec_v):
    if nrec >= nrec_max:
        return nrec
    rec[nrec, REC_T] = t
    rec[nrec, REC_V_DRIVE] = v[m_node]
    rec[nrec, REC_V_TAIL] = v[i_tail]
    rec[nrec, REC_F_DRIVE] = f_tot
    rec[nrec, REC_T_HEAD_IN] = tt[m_node - 1 if m_node > 0 else n - 1]
    rec[nrec, REC_T_HEAD_OUT] = tt[m_node]
    rec[nrec, REC_T_TAIL] = tt[i_tail]
    rec[nrec, REC_T_TAKEUP] = 0.5 * (tt[i_tu - 1] + tt[i_tu])
    rec[nrec, REC_X_TU] = x_tu
    rec[nrec, REC_T_MIN] = tlo
    rec[nrec, REC_T_MAX] = thi
    rec[nrec, REC_V_MEAN] = v_mean
    rec[nrec, REC_F_BRAKE] = f_brake
    rec[nrec, REC_V_REF] = v_ref
    rec[nrec, REC_P_DRIVE] = p_tot
    for k in range(probes.shape[0]):
        rec_t[nrec, k] = tt[probes[k]]
        rec_v[nrec, k] = v[probes[k]]
    return nrec + 1


@njit(**OPTS)
def _record_surface(nsurf, nsurf_max, t, v, tt, surf_idx, surf_t, surf_v):
    if nsurf >= nsurf_max:
        return nsurf
    surf_t[nsurf, 0] = t
    for k in range(surf_idx.shape[0]):
        surf_t[nsurf, k + 1] = tt[surf_idx[k]]
        surf_v[nsurf, k] = v[surf_idx[k]]
    return nsurf + 1
