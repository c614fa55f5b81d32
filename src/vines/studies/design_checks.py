"""Defaults and validation of the inputs of ``vines.design``: each check raises
ParameterError naming the argument, the value and what is allowed. Numbers only; no
simulation is loaded here."""
from __future__ import annotations

import math
from collections.abc import Sequence

from ..core.params import (
    C_DAMP_NS_PER_M,
    D_MAX,
    ETA_MAX,
    F_MAX,
    K_SPRING_N_PER_M,
    M_LO_KG,
    OMEGA_MAX,
    ParameterError,
    check_int,
    check_param,
    check_real,
)

#: defaults of ``vines.design`` (here, numba-free, so that ``vines design --help`` shows them
#: without loading the simulation)
DEFAULT_BAND = (0.8, 1.2)
DEFAULT_N_OMEGA = 21
#: base amplitudes [m] at F = 0.05, 0.2 and 0.4 for the paper's clearance L = 0.015 m
DEFAULT_AMPLITUDES_M = (0.00075, 0.003, 0.006)
N_ETA_DEFAULT = 5
N_CLEARANCE_DEFAULT = 13
CENSUS_N_DEFAULT = 64
#: restitution search (``r_range``): grid points in r; the restitutions of ``r_trade``
N_R_DEFAULT = 5
R_TRADE = (0.0, 0.3, 0.5, 0.65, 0.8)
#: attractor views of the design's worst case (``design.VIEWS``)
VIEW_NAMES = ("t_end",)


def _pair(name, value) -> tuple:
    try:
        pair = tuple(value)
    except TypeError:
        raise ParameterError(name, value, "must be two numbers (LO, HI)") from None
    if len(pair) != 2:
        raise ParameterError(name, value, "must be two numbers (LO, HI)")
    return pair


def check_band(band: Sequence[float], name: str = "omega_band") -> tuple[float, float]:
    """omega band (lo, hi): 0 < lo < hi <= OMEGA_MAX."""
    lo, hi = _pair(name, band)
    lo = check_real(name, lo, lo=0.0, lo_open=True, hi=OMEGA_MAX)
    hi = check_real(name, hi, lo=lo, lo_open=True, hi=OMEGA_MAX)
    return lo, hi


def check_amplitudes(amplitudes: float | Sequence[float], amplitude_max: float,
                     n_max: int) -> tuple:
    """Base amplitudes [m]: 1..n_max numbers, each > 0 and <= amplitude_max."""
    if isinstance(amplitudes, (int, float, str)):
        amplitudes = [amplitudes]
    try:
        values = list(amplitudes)
    except TypeError:
        raise ParameterError("amplitude", amplitudes, "must be one or more numbers") from None
    if not 1 <= len(values) <= n_max:
        raise ParameterError("amplitude", amplitudes, f"must be 1 to {n_max} numbers")
    return tuple(check_real("amplitude", a, lo=0.0, lo_open=True, hi=amplitude_max)
                 for a in values)


def check_structure(M_kg: float | None, k_N_per_m: float | None, c_Ns_per_m: float | None,
                    d: float | None) -> tuple[float, float, float, float]:
    """(M, k, c, d) of the LO: M, k > 0; give c >= 0 or d >= 0 (not both; default: Table 1's
    c); d = c / (M w0) = c / sqrt(k M)."""
    M = check_real("M", M_LO_KG if M_kg is None else M_kg, lo=0.0, lo_open=True)
    k = check_real("k", K_SPRING_N_PER_M if k_N_per_m is None else k_N_per_m, lo=0.0,
                   lo_open=True)
    if c_Ns_per_m is not None and d is not None:
        raise ParameterError("d", d, "give the damping as c or as d, not both")
    if d is None:
        c = check_real("c", C_DAMP_NS_PER_M if c_Ns_per_m is None else c_Ns_per_m, lo=0.0)
        d = c / math.sqrt(k * M)
        if d > D_MAX:
            raise ParameterError("c", c_Ns_per_m, f"gives d = c/sqrt(k M) = {d:g} > {D_MAX:g}")
    else:
        d = check_param("d", d)
        c = d * math.sqrt(k * M)
    return M, k, c, d


def check_mode(eta: float | None, clearance_m: float | None, eta_max: float | None,
               clearance_range_m: Sequence[float] | None) -> str:
    """'evaluate' (eta and clearance given) or 'optimise' (eta_max given, clearance range
    optional); anything else is refused."""
    if eta_max is not None:
        if eta is not None or clearance_m is not None:
            raise ParameterError("eta_max", eta_max,
                                 "optimises a design: do not give eta or clearance with it")
        return "optimise"
    if clearance_range_m is not None:
        raise ParameterError("clearance_range", clearance_range_m,
                             "is the search range of an optimisation: give eta_max with it")
    if eta is None or clearance_m is None:
        missing = "eta" if eta is None else "clearance"
        raise ParameterError(missing, None, "give eta and clearance (evaluate a design) or "
                                            "eta_max (optimise one)")
    return "evaluate"


def check_clearance(name: str, L: float, amplitudes: Sequence[float]) -> float:
    """A clearance [m] large enough that F = A/L <= F_MAX for every amplitude A."""
    lo = max(amplitudes) / F_MAX
    return check_real(name, L, lo=lo, hi=1e6)


def check_clearance_range(rng: Sequence[float] | None, amplitudes: Sequence[float],
                          factors: tuple[float, float]) -> tuple[float, float]:
    """(lo, hi) [m], lo < hi, F = A/lo <= F_MAX; default (factors[0] A_max,
    factors[1] A_min), or (factors[0] A_max, factors[1] A_max) if that is empty."""
    if rng is None:
        lo, hi = factors[0] * max(amplitudes), factors[1] * min(amplitudes)
        rng = (lo, hi if hi > lo else factors[1] * max(amplitudes))
    lo, hi = _pair("clearance_range", rng)
    lo = check_clearance("clearance_range", lo, amplitudes)
    hi = check_real("clearance_range", hi, lo=lo, lo_open=True, hi=1e6)
    return lo, hi


def check_r_range(rng: Sequence[float]) -> tuple[float, float]:
    """Restitutions searched (lo, hi): 0 <= lo < hi <= 1."""
    lo, hi = _pair("r_range", rng)
    lo = check_real("r_range", lo, lo=0.0, hi=1.0)
    hi = check_real("r_range", hi, lo=lo, lo_open=True, hi=1.0)
    return lo, hi


def check_eta(name: str, eta: float) -> float:
    return check_real(name, eta, lo=0.0, lo_open=True, hi=ETA_MAX)


def check_count(name: str, value: int, lo: int, hi: int) -> int:
    return check_int(name, value, lo=lo, hi=hi)
