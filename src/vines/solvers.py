"""``simulate`` one parameter point with any solver, and the solver registry.

The registry lives above ``core`` (as scipy keeps ``METHODS`` in ``ivp.py``, not in
``base.py``): ``core`` holds the production solver and knows nothing of the reference
oracles of ``vines.reference``.
"""
from __future__ import annotations

from .core.exact import run_exact
from .core.params import (
    D_DEFAULT,
    MAX_IMPACTS_DEFAULT,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    RTOL_DEFAULT,
    RTOL_MAX,
    RTOL_MIN,
    T_END_DEFAULT,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_bool,
    check_real,
)
from .core.result import RawRun, SimulationResult
from .core.simulation import simulate_exact, simulation_result

#: scipy methods of the RK reference solver (``vines.reference.rk``)
RK_METHODS = ("DOP853", "RK45", "LSODA", "Radau")


def _run_rk(p: ModelParams, st: SolverSettings, *, method, rtol, atol) -> RawRun:
    """The independent RK reference (imported on first use: scipy's event loop)."""
    from .reference.rk import run_rk
    return run_rk(p, st, method=method, rtol=rtol, atol=atol)


#: solver registry: name -> function(params, settings, **options) -> RawRun; the API,
#: the CLI (--solver) and the work-precision study take their names from here
SOLVERS = {"exact": run_exact, "rk": _run_rk}


def simulate(eta, omega, F, r=R_DEFAULT, d=D_DEFAULT, phi=0.0, *, t_end=T_END_DEFAULT,
             t_transient=T_TRANSIENT_DEFAULT, solver="exact", rtol=RTOL_DEFAULT, atol=None,
             method="DOP853", v_stick=V_STICK_DEFAULT, max_impacts=MAX_IMPACTS_DEFAULT,
             root_tol=ROOT_TOL_DEFAULT, state0=(0.0, 0.0, 0.0, 0.0),
             periodic_shortcut=True, keep_impacts=True) -> SimulationResult:
    """Simulate the VINES from ``state0`` at t = 0 to ``t_end`` (dimensionless time).

    solver="exact" uses the closed-form event-driven kernel (``root_tol``: contact is
    declared within this distance of the wall, in units of L); solver="rk" integrates the
    same model with scipy's ``method`` at ``rtol``/``atol`` (the independent reference).
    Measures are exact time averages over [t_transient, t_end]. ``periodic_shortcut``
    (exact solver only): once the motion has settled on a periodic orbit, complete the run
    from one period of it (``vines.core.shortcut``; the result's ``shortcut_time`` says
    when, NaN if never). ``keep_impacts`` (exact solver only): keep the impact list and
    the whole trajectory; with False the measures are accumulated as the run goes and
    memory does not grow with t_end or max_impacts: ``impacts`` is then empty and
    ``state_at`` covers only the last stroboscopic periods of the window (``regime``).
    Raises ParameterError for bad input.
    """
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d, phi=phi)
    st = SolverSettings(t_end=t_end, t_transient=t_transient, v_stick=v_stick,
                        max_impacts=max_impacts, root_tol=root_tol, state0=state0)
    # the tolerances of the rk solver are checked whichever solver runs (same values as the CLI)
    rtol = check_real("rtol", rtol, lo=RTOL_MIN, hi=RTOL_MAX)
    if atol is not None:
        atol = check_real("atol", atol, lo=0.0, lo_open=True, hi=RTOL_MAX)
    return run_simulation(p, st, solver=solver, rtol=rtol, atol=atol, method=method,
                          periodic_shortcut=periodic_shortcut, keep_impacts=keep_impacts)


def run_simulation(p: ModelParams, st: SolverSettings, *, solver: str = "exact",
                   rtol: float = RTOL_DEFAULT, atol: float | None = None,
                   method: str = "DOP853", periodic_shortcut: bool = True,
                   keep_impacts: bool = True) -> SimulationResult:
    """``simulate`` on validated model and settings (``rtol``/``atol`` already checked)."""
    if not isinstance(solver, str) or solver not in SOLVERS:
        raise ParameterError("solver", solver, f"must be one of {', '.join(SOLVERS)}")
    if solver == "exact":   # the exact solver's own front end (one copy of its options)
        return simulate_exact(p, st,
                              periodic_shortcut=check_bool("periodic_shortcut", periodic_shortcut),
                              keep_impacts=check_bool("keep_impacts", keep_impacts))
    if not isinstance(method, str) or method not in RK_METHODS:
        raise ParameterError("method", method, f"must be one of {', '.join(RK_METHODS)}")
    raw = SOLVERS[solver](p, st, method=method, rtol=rtol, atol=atol)
    options = {"method": method, "rtol": rtol, "atol": raw.solver_info.get("atol", atol)}
    return simulation_result(p, st, raw, solver, options)
