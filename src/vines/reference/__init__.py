"""Independent reference solvers, the test oracles of the closed-form solver: ``run_rk``
integrates the model numerically with ``scipy.integrate.solve_ivp`` (terminal events for
impacts, sticking and release; one of ``METHODS``), and ``reference_run`` computes a
high-precision trajectory in mpmath (closed-form segments, 40 digits by default) for
measuring the solvers' errors. Neither shares numerical code with ``vines.core``: they import
only its containers (``ModelParams``, ``SolverSettings``, ``IMPACT_DTYPE``, ``RawRun``)."""
from .hiprec import reference_run
from .rk import METHODS, run_rk

__all__ = ["run_rk", "reference_run", "METHODS"]
