"""vines: exact simulation and map-based analysis of the vibro-impact nonlinear energy sink.

Dimensionless model (see docs/model.md): between impacts
    z_m'' + d z_m' + z_m = F sin(omega t + phi) + d omega F cos(omega t + phi),   z_b'' = 0,
walls at w = z_m - z_b = +1 (L) and -1 (R), Newtonian impact law with restitution r.
Subpackages: core (simulation), orbits (periodic orbits), reference (independent oracles),
studies (work-precision, convergence), data (datasets), pipeline, plotting; see
docs/architecture.md.
"""
from ._numba_cache import refresh as _refresh_numba_cache

_refresh_numba_cache()   # before any jitted function is loaded from the cache

from .core.params import (D_DEFAULT, L_HALF_M, ModelParams, ParameterError,  # noqa: E402
                          SolverSettings)
from .core.result import IMPACT_DTYPE, SimulationResult  # noqa: E402
from .core.simulation import simulate, simulate_batch  # noqa: E402

__version__ = "0.1.0"

__all__ = ["simulate", "simulate_batch", "ModelParams", "SolverSettings", "ParameterError",
           "SimulationResult", "IMPACT_DTYPE", "D_DEFAULT", "L_HALF_M", "__version__"]
