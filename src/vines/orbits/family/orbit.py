"""What every periodic orbit holds, ``OrbitBase``: its flights, symmetry, admissibility and
stability, whatever its family; the 1:1 orbit (``periodic.PeriodicOrbit``) and the orbit of
any wall sequence (``sequence.SequenceOrbit``) are its two forms."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...core.params import ModelParams


@dataclass(kw_only=True)
class OrbitBase:
    """One periodic orbit and its stability (keyword fields).

    flight_times  one per flight, in the order of the impacts
    symmetric     invariant under the mirror z -> -z with a half-period shift
    admissible    every flight is a genuine impact-to-impact flight
    eigenvalues   of the monodromy matrix (the product of the map Jacobians), sorted by
                  decreasing modulus; lambda_max = max |eigenvalue|
    stable        admissible and lambda_max < 1
    residual      the Newton residual at the solution
    params        the model point of the orbit
    """

    flight_times: list | np.ndarray
    symmetric: bool
    admissible: bool
    eigenvalues: np.ndarray
    lambda_max: float
    stable: bool
    residual: float = 0.0
    params: ModelParams | None = field(default=None, repr=False)
