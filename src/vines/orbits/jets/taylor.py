"""Second-order forward-mode differentiation (Taylor jets) for the small shooting systems.

A ``Jet`` carries a value, its gradient and (order 2) its Hessian with respect to n
independent variables. The closed-form residuals of ``vines.orbits.jets.shooting`` are written
once, over numbers that support + - * / and ``sin``/``cos``/``exp``/``sqrt`` from this
module, and evaluated on floats (values) or on jets (exact first and second derivatives,
to rounding: no step size, no truncation error). Mixed float/jet arithmetic works. A
third kind of number, ``tape.Node``, records the operations (``sin`` ... call its
``unary``) for the compiled evaluation of ``kernels``.

``lift(J)`` turns the gradients of order-2 jets into order-1 jets of the first
derivatives (value = d f_i / d v_k, gradient = the Hessian row), which is how derivatives
of Jacobian-based test functions (determinants of J - I, ...) are obtained.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


class Jet:
    """f with gradient g (shape (n,)) and Hessian H ((n, n), or None for order 1)."""

    __slots__ = ("v", "g", "H")
    __array_priority__ = 1000           # numpy scalars defer to Jet's operators

    def __init__(self, v: float, g: np.ndarray, H: np.ndarray | None = None) -> None:
        self.v = float(v)
        self.g = g
        self.H = H

    # --------------------------------------------------------------- arithmetic
    def __add__(self, o):
        if isinstance(o, Jet):
            return Jet(self.v + o.v, self.g + o.g, _add(self.H, o.H))
        return Jet(self.v + o, self.g, self.H)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, -self.g, None if self.H is None else -self.H)

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if not isinstance(o, Jet):
            return Jet(self.v * o, self.g * o, None if self.H is None else self.H * o)
        H = None
        if self.H is not None and o.H is not None:
            cross = np.outer(self.g, o.g)
            H = self.v * o.H + o.v * self.H + cross + cross.T
        return Jet(self.v * o.v, self.v * o.g + o.v * self.g, H)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, Jet):
            return self * (1.0 / o)
        return self * _unary(o, 1.0 / o.v, -1.0 / o.v ** 2, 2.0 / o.v ** 3)

    def __rtruediv__(self, o):
        return o * _unary(self, 1.0 / self.v, -1.0 / self.v ** 2, 2.0 / self.v ** 3)

    def __repr__(self):
        return f"Jet({self.v!r}, g={self.g!r})"


def _add(a, b):
    return None if a is None or b is None else a + b


def _unary(x: Jet, f, f1, f2) -> Jet:
    """Chain rule for a scalar function with value f, derivatives f1, f2 at x.v."""
    H = None if x.H is None else f1 * x.H + f2 * np.outer(x.g, x.g)
    return Jet(f, f1 * x.g, H)


def sin(x: float | Jet) -> float | Jet:
    if not isinstance(x, Jet):
        return x.unary("sin") if hasattr(x, "unary") else math.sin(x)
    s, c = math.sin(x.v), math.cos(x.v)
    return _unary(x, s, c, -s)


def cos(x: float | Jet) -> float | Jet:
    if not isinstance(x, Jet):
        return x.unary("cos") if hasattr(x, "unary") else math.cos(x)
    s, c = math.sin(x.v), math.cos(x.v)
    return _unary(x, c, -s, -c)


def exp(x: float | Jet) -> float | Jet:
    if not isinstance(x, Jet):
        return x.unary("exp") if hasattr(x, "unary") else math.exp(x)
    e = math.exp(x.v)
    return _unary(x, e, e, e)


def sqrt(x: float | Jet) -> float | Jet:
    if not isinstance(x, Jet):
        return x.unary("sqrt") if hasattr(x, "unary") else math.sqrt(x)
    q = math.sqrt(x.v)
    return _unary(x, q, 0.5 / q, -0.25 / (q * x.v))


# --------------------------------------------------------------- variables and results

def variables(values: Sequence[float], order: int = 1) -> list:
    """Independent jets for the given values (unit gradients)."""
    n = len(values)
    eye = np.eye(n)
    zero = np.zeros((n, n)) if order >= 2 else None
    return [Jet(v, eye[k].copy(), None if zero is None else zero.copy())
            for k, v in enumerate(values)]


def value(x: float | Jet) -> float:
    return x.v if isinstance(x, Jet) else float(x)


def gradient(x: float | Jet, n: int) -> np.ndarray:
    return x.g if isinstance(x, Jet) else np.zeros(n)


def values(fs: Sequence) -> np.ndarray:
    return np.array([value(f) for f in fs])


def jacobian(fs: Sequence, n: int) -> np.ndarray:
    """Rows = gradients of the jets fs (constants give zero rows)."""
    return np.array([gradient(f, n) for f in fs]).reshape(len(fs), n)


def lift(f: float | Jet, n: int) -> list:
    """Order-1 jets of the n first derivatives of the order-2 jet f (d f / d v_k)."""
    if not isinstance(f, Jet):
        return [0.0] * n
    H = f.H if f.H is not None else np.zeros((n, n))
    return [Jet(f.g[k], H[k].copy()) for k in range(n)]


def compose(f: float | Jet, inner_grad: np.ndarray) -> float | Jet:
    """Order-1 jet f over local variables, re-expressed over global ones.

    inner_grad[k] is the gradient (over the global variables) of local variable k.
    """
    if not isinstance(f, Jet):
        return f
    return Jet(f.v, f.g @ inner_grad)


def det(M: list) -> float | Jet:
    """Determinant of a square matrix (list of lists) of floats/jets: Gaussian elimination
    with partial pivoting on the values (the last pivot is never divided by, so the
    result and its derivatives stay finite at a singular matrix)."""
    A = [list(row) for row in M]
    n = len(A)
    out = 1.0
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(value(A[i][k])))
        if p != k:
            A[k], A[p] = A[p], A[k]
            out = -out
        out = out * A[k][k]
        if k == n - 1:
            break
        if value(A[k][k]) == 0.0:
            return 0.0 * out
        for i in range(k + 1, n):
            f = A[i][k] / A[k][k]
            for j in range(k + 1, n):
                A[i][j] = A[i][j] - f * A[k][j]
    return out
