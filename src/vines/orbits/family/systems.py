"""The one contract of the systems that continuation and curve tracing run on, and the one
Newton on their square forms.

A system of any family (the 1:1 shooting systems of ``augmented``, with exact derivatives by
Taylor jets; the systems of any wall sequence in ``map_systems``, on the maps: exact in the
state, central differences in the parameters) is called on the unknowns z and returns
(G, G_z), NaN where it is undefined (a map fails, a parameter leaves its range).
``arclength.Tracer`` follows G = 0 with one more unknown than equations; ``solve`` solves
it with as many.
"""
from __future__ import annotations

from typing import Protocol

import numpy as np

#: the codimension-one points of symmetric (True) and asymmetric (False) orbits of any family
KINDS = {True: ("fold", "symmetry-breaking", "neimark-sacker", "grazing"),
         False: ("fold", "flip", "neimark-sacker", "grazing")}


def compound2(A) -> list:
    """Second compound matrix (eigenvalues lambda_i lambda_j, i < j) of a 4 x 4 matrix of
    numbers or Taylor jets (rows indexable as A[p][r]), as nested lists."""
    pairs = [(p, q) for p in range(len(A)) for q in range(p + 1, len(A))]
    return [[A[p][r] * A[q][s] - A[p][s] * A[q][r] for (r, s) in pairs] for (p, q) in pairs]


class System(Protocol):
    """G, G_z = system(z)."""

    def __call__(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]: ...


class AugmentedSystem(System, Protocol):
    """A system of codimension-one points: the family's orbit equations and one condition."""

    kind: str           # fold, flip, symmetry-breaking, neimark-sacker or grazing
    family: str         # the family's name (1:1: "symmetric" or "asymmetric")
    graze: tuple | None  # (flight, wall) of a grazing, else None


def solve(system: AugmentedSystem, z0, tol=1e-11, max_iter=30):
    """Newton on the square system (one free parameter); the solution or None."""
    z = np.asarray(z0, dtype=float).copy()
    for _ in range(max_iter):
        G, Gz = system(z)
        if not np.all(np.isfinite(G)):
            return None
        try:
            dz = np.linalg.solve(Gz, -G)
        except np.linalg.LinAlgError:
            return None
        z += dz
        if np.max(np.abs(dz)) <= tol * (1.0 + np.max(np.abs(z))):
            return z
    return None
