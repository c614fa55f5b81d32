"""vines: exact simulation and map-based analysis of the vibro-impact nonlinear energy sink.

Dimensionless model (see docs/model.md): between impacts
    z_m'' + d z_m' + z_m = F sin(omega t + phi) + d omega F cos(omega t + phi),   z_b'' = 0,
walls at w = z_m - z_b = +1 (L) and -1 (R), Newtonian impact law with restitution r.
Subpackages: core (simulation), orbits (periodic orbits), reference (independent oracles),
studies (work-precision, convergence), data (datasets), pipeline, plotting; see
docs/architecture.md.

``simulate``, ``simulate_batch``, ``design``, ``lyapunov``, ``SimulationResult``,
``IMPACT_DTYPE`` and the general host's ``HostModel``, ``read_model`` and ``simulate_model``
(``vines.multimode``) are imported on first use, so that code which only reads datasets or draws
figures does not load numba and the compiled kernels; ``open_run`` (a finished run's
datasets as one ``xarray.DataTree``) likewise, so that ``import vines`` does not load xarray.
"""
from ._lazy import lazy_attributes as _lazy_attributes
from ._numba_cache import refresh as _refresh_numba_cache

_refresh_numba_cache()   # before any jitted function is loaded from the cache

from .core.params import D_DEFAULT, L_HALF_M, ModelParams, ParameterError, SolverSettings  # noqa: E402

#: public names loaded on first access, and their modules
_LAZY = {"simulate": ".solvers", "simulate_batch": ".core.simulation",
         "SimulationResult": ".core.result", "IMPACT_DTYPE": ".core.result",
         "design": ".studies.design", "lyapunov": ".attractors.lyapunov",
         "open_run": ".data.run", "HostModel": ".multimode.model",
         "simulate_model": ".multimode.simulate", "read_model": ".multimode.modelfile"}

__all__ = ["simulate", "simulate_batch", "design", "lyapunov", "open_run", "HostModel",
           "simulate_model", "read_model", "ModelParams",
           "SolverSettings", "ParameterError", "SimulationResult", "IMPACT_DTYPE", "D_DEFAULT",
           "L_HALF_M", "__version__"]


def _version() -> str:
    """One version: pyproject.toml's, as installed (read on first use: importlib.metadata
    costs more than the rest of ``import vines``)."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("vines")
    except PackageNotFoundError:   # sources used without installing (not a release)
        return "0+unknown"


__getattr__, __dir__ = _lazy_attributes(__name__, _LAZY, {"__version__": _version})
