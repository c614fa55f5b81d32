"""LAPACK ``dgeev`` (eigenvalues of a real square matrix) callable from nogil numba code.

``np.linalg.eigvals`` inside numba refuses real matrices with complex eigenvalues (no
"domain change"), and a complex copy would go through ``zgeev`` (other round-off than
numpy). ``dgeev`` here is scipy's (``scipy.linalg.cython_lapack``), the routine numpy's
``eigvals`` calls on real input, so the eigenvalues are those of numpy where numpy and
scipy ship the same LAPACK build, and within their condition numbers times the round-off
otherwise (tests/test_stability_map.py). The symbol is registered with llvmlite under a
fixed name at import and the compiled code refers to that name (no embedded address), so
the callers can be cached (``cache=True``).
"""
from __future__ import annotations

import math

import numpy as np
from llvmlite import binding as _ll
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import get_cython_function_address, intrinsic

from ..._jit import njit

_SYMBOL = "vines_scipy_dgeev"
_ll.add_symbol(_SYMBOL, get_cython_function_address("scipy.linalg.cython_lapack", "dgeev"))


@intrinsic
def _dgeev_nn(typingctx, a, wr, wi, work):
    """dgeev('N', 'N', n, a, n, wr, wi, _, 1, _, 1, work, len(work)) -> info (int32).

    a: n*n float64 array in column-major order (overwritten); wr, wi: n; work: >= 3 n;
    all contiguous 1-D float64 arrays (others do not compile).
    """
    for t in (a, wr, wi, work):
        if not (isinstance(t, types.Array) and t.dtype == types.float64 and t.ndim == 1
                and t.layout == "C"):
            return None
    sig = types.int32(a, wr, wi, work)

    def codegen(context, builder, signature, args):
        i8, i32 = ir.IntType(8), ir.IntType(32)
        dptr = ir.DoubleType().as_pointer()
        ip = i32.as_pointer()
        fnty = ir.FunctionType(ir.VoidType(), [i8.as_pointer(), i8.as_pointer(), ip, dptr, ip,
                                               dptr, dptr, dptr, ip, dptr, ip, dptr, ip, ip])
        fn = cgutils.get_or_insert_function(builder.module, fnty, _SYMBOL)
        arr = [context.make_array(t)(context, builder, v)
               for t, v in zip(signature.args, args, strict=False)]
        nn = builder.trunc(arr[1].nitems, i32)          # n = len(wr)
        job = cgutils.alloca_once_value(builder, ir.Constant(i8, ord("N")))
        n = cgutils.alloca_once_value(builder, nn)
        one = cgutils.alloca_once_value(builder, ir.Constant(i32, 1))
        lwork = cgutils.alloca_once_value(builder, builder.trunc(arr[3].nitems, i32))
        info = cgutils.alloca_once_value(builder, ir.Constant(i32, 0))
        dummy = cgutils.alloca_once(builder, ir.DoubleType(), size=2)
        builder.call(fn, [job, job, n, arr[0].data, n, arr[1].data, arr[2].data, dummy, one,
                          dummy, one, arr[3].data, lwork, info])
        return builder.load(info)

    return sig, codegen


@njit(cache=True, nogil=True)
def lambda_max_4(M, a, wr, wi, work):
    """max |eigenvalue| (hypot of real and imaginary parts) of the 4x4 matrix M; nan when
    M is not finite or dgeev fails. a (16), wr, wi (4), work (>= 12) are workspace."""
    for k in range(4):
        for i in range(4):
            v = M[i, k]
            if not math.isfinite(v):
                return math.nan
            a[4 * k + i] = v                 # column-major
    if _dgeev_nn(a, wr, wi, work) != 0:
        return math.nan
    lam = 0.0
    for k in range(4):
        lam = max(lam, math.hypot(wr[k], wi[k]))
    return lam


def eigvals(M: np.ndarray) -> np.ndarray:
    """Eigenvalues of a real square matrix by the compiled dgeev, as ``np.linalg.eigvals``
    returns them (real when all are real; LinAlgError for a matrix with inf or nan): tests
    run numpy's callers with this one."""
    M = np.asarray(M, dtype=float)
    if not np.all(np.isfinite(M)):
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
    n = M.shape[0]
    a = M.ravel(order="F").copy()
    wr, wi, work = np.empty(n), np.empty(n), np.empty(max(64, 4 * n))
    info = _dgeev_py(a, wr, wi, work)
    if info != 0:
        raise np.linalg.LinAlgError(f"dgeev info {info}")
    return wr.copy() if not wi.any() else wr + 1j * wi


@njit(cache=True, nogil=True)
def _dgeev_py(a, wr, wi, work):
    return _dgeev_nn(a, wr, wi, work)


def monodromy_eigvals(J1: np.ndarray, J2: np.ndarray) -> np.ndarray:
    """``periodic.monodromy_eigenvalues`` as the compiled ``orbit_classify`` computes it:
    J2 J1 by numba's np.dot, eigenvalues by the compiled dgeev (tests)."""
    M = np.empty((4, 4))
    _dot(np.ascontiguousarray(J2, dtype=float), np.ascontiguousarray(J1, dtype=float), M)
    return eigvals(M)


@njit(cache=True, nogil=True)
def _dot(A, B, out):
    np.dot(A, B, out)
