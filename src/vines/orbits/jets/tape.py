"""Recording of a closed-form formula as a tape of elementary operations (``Node``).

The formulas of ``shooting`` are written once, over numbers (floats, ``jets.Jet``).
Evaluated on ``Node`` inputs they record every + - * / and negation, and the ``jets``
functions sin/cos/exp/sqrt, into a ``Tape``. Registers: 0 .. n_in - 1 are the inputs,
register n_in + i holds the result of operation i (a constant is an operation too).
``kernels`` evaluates a tape on Taylor jets in compiled code: one interpreter,
whatever the formula.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

OPS = ("add", "sub", "mul", "div", "neg", "sin", "cos", "exp", "sqrt", "const")


class Tape:
    """Operations (code, a, b) in order (codes: index in ``OPS``; ``const``: a indexes
    ``consts``) and the constants."""

    def __init__(self, n_in: int):
        self.n_in = n_in
        self.ops: list = []
        self.consts: list = []

    def emit(self, code: str, a: int, b: int = 0) -> int:
        self.ops.append((OPS.index(code), a, b))
        return self.n_in + len(self.ops) - 1

    def const(self, c: float) -> int:
        self.consts.append(float(c))
        return self.emit("const", len(self.consts) - 1)


class Node:
    """A recorded number: its register on the tape."""

    __slots__ = ("tape", "reg")
    __array_priority__ = 1000           # numpy scalars defer to Node's operators

    def __init__(self, tape: Tape, reg: int):
        self.tape, self.reg = tape, reg

    def _r(self, o) -> int:
        return o.reg if isinstance(o, Node) else self.tape.const(o)

    def _op(self, code, a, b=0):
        return Node(self.tape, self.tape.emit(code, a, b))

    def __add__(self, o):
        return self._op("add", self.reg, self._r(o))

    def __radd__(self, o):
        return self._op("add", self._r(o), self.reg)

    def __sub__(self, o):
        return self._op("sub", self.reg, self._r(o))

    def __rsub__(self, o):
        return self._op("sub", self._r(o), self.reg)

    def __mul__(self, o):
        return self._op("mul", self.reg, self._r(o))

    def __rmul__(self, o):
        return self._op("mul", self._r(o), self.reg)

    def __truediv__(self, o):
        return self._op("div", self.reg, self._r(o))

    def __rtruediv__(self, o):
        return self._op("div", self._r(o), self.reg)

    def __neg__(self):
        return self._op("neg", self.reg)

    def unary(self, name: str):
        """sin, cos, exp or sqrt of this number (called by ``jets.sin`` ...)."""
        return self._op(name, self.reg)


def record(fn: Callable[..., list], n_in: int) -> tuple:
    """Tape of outputs = fn(*inputs) as arrays: (ops (n, 3) int64, consts, output registers
    int64); fn returns a sequence of recorded numbers."""
    tape = Tape(n_in)
    outs = fn(*[Node(tape, k) for k in range(n_in)])
    regs = [o.reg if isinstance(o, Node) else tape.const(o) for o in outs]
    return (np.array(tape.ops, dtype=np.int64).reshape(-1, 3),
            np.array(tape.consts, dtype=float), np.array(regs, dtype=np.int64))
