"""Pseudo-arclength continuation of the solution curve of R(z) = 0, R: R^(n+1) -> R^n.

``Tracer`` follows the curve from a point: tangent predictor z + h t, Newton corrector on
the bordered system [R(z); t . (z - z_pred)] = 0 (Jacobian [R_z; t^T]), new tangent from
[R_z; t^T] tau = (0, ..., 0, 1), step control (grow by 1.5 after an easy correction,
halve after a failed one or a turn of more than ``MAX_TURN`` between tangents). Folds in
any coordinate are passed: the parameter is an unknown like the others.

``Tracer.point_at`` corrects onto the hyperplane t_k . (z - z_k) = tau of a step (the
points between two accepted ones) and ``Tracer.locate`` finds the root of a scalar test
function of those points along a step (Illinois regula falsi, bisection fallback): this is
how events are located along the arclength.

``fun(z)`` returns (R, R_z) with R_z of shape (n, n+1); ``scale`` (n+1 positive weights)
defines the norm t . t = sum (scale_k t_k)^2 used for steps and tangents.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

MAX_TURN = math.radians(30.0)
NEWTON_TOL = 1e-11
MAX_NEWTON = 10


@dataclass
class Step:
    """One accepted step: start z0 with unit tangent t0 -> end z1 with tangent t1."""

    z0: np.ndarray
    t0: np.ndarray
    z1: np.ndarray
    t1: np.ndarray
    h: float


class Tracer:
    """Pseudo-arclength continuation (module docstring)."""

    def __init__(self, fun: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                 z0: ArrayLike, direction: ArrayLike, h: float, h_min: float, h_max: float,
                 scale: ArrayLike | None = None) -> None:
        self.fun = fun
        self.scale = np.ones(len(z0)) if scale is None else np.asarray(scale, float)
        self.h, self.h_min, self.h_max = float(h), float(h_min), float(h_max)
        self.z = np.asarray(z0, dtype=float).copy()
        _, Rz = fun(self.z)
        self.t = self.tangent(Rz, np.asarray(direction, dtype=float))

    # ----------------------------------------------------------------- geometry
    def tangent(self, Rz: np.ndarray, t_ref: np.ndarray) -> np.ndarray:
        """Unit tangent (scaled norm) of the curve, oriented along t_ref."""
        w = self.scale
        A = np.vstack([Rz / w, (t_ref * w)[None, :]])
        rhs = np.zeros(A.shape[0])
        rhs[-1] = 1.0
        try:
            y = np.linalg.solve(A, rhs)
        except np.linalg.LinAlgError:
            y = np.linalg.svd(Rz / w)[2][-1]
        y = y / np.linalg.norm(y)
        t = y / w
        return t if np.dot(t * w, t_ref * w) >= 0.0 else -t

    def dot(self, a: np.ndarray, b: np.ndarray) -> float:
        """The scaled inner product a . b."""
        return float(np.dot(a * self.scale, b * self.scale))

    def correct(self, z_pred: np.ndarray, t_ref: np.ndarray, z_ref: np.ndarray,
                tau: float) -> tuple[np.ndarray, np.ndarray, int] | None:
        """Newton on R(z) = 0, t_ref . (z - z_ref) = tau from z_pred: (z, Rz, iterations)
        or None."""
        z = z_pred.copy()
        tw = t_ref * self.scale * self.scale
        n = len(z)
        A, F = np.empty((n, n)), np.empty(n)        # the bordered system
        A[-1] = tw
        for it in range(1, MAX_NEWTON + 1):
            R, Rz = self.fun(z)
            if not (np.isfinite(R).all() and np.isfinite(Rz).all()):
                return None
            A[:-1], F[:-1], F[-1] = Rz, R, np.dot(tw, z - z_ref) - tau
            try:
                dz = np.linalg.solve(A, -F)
            except np.linalg.LinAlgError:
                return None
            z = z + dz
            if np.abs(dz).max() <= NEWTON_TOL * (1.0 + np.abs(z).max()):
                R, Rz = self.fun(z)
                if np.abs(R).max() <= 1e3 * NEWTON_TOL:
                    return z, Rz, it
                return None
        return None

    def point_at(self, step: Step, tau: float) -> tuple[np.ndarray, np.ndarray] | None:
        """(z, t) on the curve where t0 . (z - z0) = tau within a step, or None."""
        got = self.correct(step.z0 + tau * step.t0, step.t0, step.z0, tau)
        if got is None:
            return None
        z, Rz, _ = got
        return z, self.tangent(Rz, step.t0)

    # ----------------------------------------------------------------- stepping
    def step(self) -> Step | None:
        """Advance one step; the Step, or None when the step fell below h_min."""
        while self.h >= self.h_min:
            h = self.h
            got = self.correct(self.z + h * self.t, self.t, self.z, h)
            if got is not None:
                z, Rz, its = got
                t = self.tangent(Rz, self.t)
                if self.dot(t, self.t) >= math.cos(MAX_TURN):
                    st = Step(self.z, self.t, z, t, h)
                    self.z, self.t = z, t
                    if its <= 3:
                        self.h = min(self.h_max, 1.5 * h)
                    return st
            self.h = 0.5 * h
        return None

    def locate(self, step: Step, test: Callable[[np.ndarray, np.ndarray], float], f0: float,
               f1: float, tol: float = 1e-10, max_iter: int = 60) -> tuple | None:
        """(tau, z, t) of a root of test(z, t) (scalar) along a step, given its values f0 at
        z0 and f1 at z1 of opposite signs; None when a point cannot be corrected."""
        a, fa, b, fb = 0.0, f0, step.h, f1
        best = None
        side = 0
        for _ in range(max_iter):
            tau = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
            if not (a < tau < b) or (b - a) < 4 * tol:
                tau = 0.5 * (a + b)
            pt = self.point_at(step, tau)
            if pt is None:
                return best
            f = test(*pt)
            best = (tau, pt[0], pt[1])
            if f == 0.0 or b - a <= tol:
                return best
            if (f > 0.0) == (fa > 0.0):
                a, fa = tau, f
                if side == -1:
                    fb *= 0.5
                side = -1
            else:
                b, fb = tau, f
                if side == 1:
                    fa *= 0.5
                side = 1
            if b - a <= tol:
                break
        return best

    def bisect(self, step: Step, flag: Callable[[np.ndarray, np.ndarray], bool], flag0: bool,
               tol: float = 1e-10) -> tuple[tuple, tuple]:
        """Where the boolean flag(z, t) changes from flag0 along a step: the (tau, z, t)
        just after the change and the one just before it (flag still flag0)."""
        a, b = 0.0, step.h
        after, before = (b, step.z1, step.t1), (a, step.z0, step.t0)
        while b - a > tol:
            tau = 0.5 * (a + b)
            pt = self.point_at(step, tau)
            if pt is None:
                break
            if flag(*pt) == flag0:
                a = tau
                before = (tau, pt[0], pt[1])
            else:
                b = tau
                after = (tau, pt[0], pt[1])
        return after, before
