"""The design problem of ``vines design`` answered by the slow flow (``vines.slowflow``): a
first pass in well under a second, and its difference from the exact answer.

Same inputs and checks as ``studies.design.design`` (``design_checks``). Evaluate mode
(eta, clearance): the design's worst transmissibility x_max/A over the band and the
amplitudes from the slow flow, and the slow flow's best clearance for that eta. Optimise
mode (eta_max): the slow flow's best clearance (``slowflow.optimal_clearance``) for each of
n_eta ball masses eta_max k/n_eta, the best of them. numba-free.
"""
from __future__ import annotations

import time
from collections.abc import Sequence

from ..core.params import R_DEFAULT
from ..slowflow.optimal import Optimum, design_ratio, optimal_clearance
from . import design_checks as _chk
from .design_checks import DEFAULT_AMPLITUDES_M, DEFAULT_BAND, N_ETA_DEFAULT
from .tmd import lo_worst

#: search ranges as ``studies.design`` (A_max/2 .. 100 A_min)
CLEARANCE_RANGE_FACTORS = (0.5, 100.0)


def _design(eta: float, opt: Optimum, amps) -> dict:
    return dict(eta=eta, clearance_m=opt.clearance_m, worst_ratio=opt.worst_ratio,
                worst_omega=opt.omega_peak, F=[A / opt.clearance_m for A in amps],
                warnings=list(opt.warnings))


def slowflow_design(*, omega_band: Sequence[float] = DEFAULT_BAND,
                    amplitudes_m=DEFAULT_AMPLITUDES_M, M_kg=None, k_N_per_m=None,
                    c_Ns_per_m=None, d=None, r=R_DEFAULT, eta=None, clearance_m=None,
                    eta_max=None, clearance_range_m=None, n_eta: int = N_ETA_DEFAULT) -> dict:
    """The slow flow's design (module docstring) as a JSON-ready dict: inputs, vines (the
    design, its worst ratio and frequency), optimal (evaluate mode: the best clearance for
    that eta), lo_alone, cost. ParameterError naming the bad argument."""
    t0 = time.perf_counter()
    mode = _chk.check_mode(eta, clearance_m, eta_max, clearance_range_m)
    band = _chk.check_band(omega_band)
    amps = _chk.check_amplitudes(amplitudes_m, 1e3, 100)
    M, k, c, d = _chk.check_structure(M_kg, k_N_per_m, c_Ns_per_m, d)
    out = dict(model="slowflow", inputs=dict(mode=mode, omega_band=list(band),
                                             amplitude_m=list(amps), M_kg=M, k_N_per_m=k,
                                             c_Ns_per_m=c, d=d, r=r))
    if mode == "evaluate":
        eta = _chk.check_eta("eta", eta)
        clearance_m = _chk.check_clearance("clearance", clearance_m, amps)
        ratio, w = design_ratio(eta, amps, clearance_m, band, r=r, d=d)
        out["vines"] = dict(eta=eta, clearance_m=clearance_m, worst_ratio=ratio,
                            worst_omega=w, F=[A / clearance_m for A in amps])
        out["optimal"] = _design(eta, optimal_clearance(eta, amps, band, r=r, d=d), amps)
    else:
        eta_max = _chk.check_eta("eta_max", eta_max)
        rng = _chk.check_clearance_range(clearance_range_m, amps, CLEARANCE_RANGE_FACTORS)
        n = _chk.check_count("n_eta", n_eta, 1, 1000)
        tried = [_design(eta_max * j / n, optimal_clearance(eta_max * j / n, amps, band, r=r,
                                                            d=d, clearance_range_m=rng), amps)
                 for j in range(1, n + 1)]
        out["vines"] = min(tried, key=lambda x: x["worst_ratio"])
        out["search"] = dict(eta=[x["eta"] for x in tried],
                             clearance_m=[x["clearance_m"] for x in tried],
                             worst_ratio=[x["worst_ratio"] for x in tried])
    worst_lo, w_lo = lo_worst(band, d)
    out["lo_alone"] = dict(worst_ratio=worst_lo, worst_omega=w_lo)
    out["cost"] = dict(wall_s=time.perf_counter() - t0)
    return out


def difference(exact: dict, slow: dict) -> dict:
    """The slow flow's answer minus the exact one: worst ratio (absolute, relative), and in
    optimise mode the designs' eta and clearance."""
    e, s = exact["vines"], slow["vines"]
    out = dict(worst_ratio=s["worst_ratio"] - e["worst_ratio"],
               worst_ratio_relative=(s["worst_ratio"] - e["worst_ratio"]) / e["worst_ratio"])
    if exact["inputs"]["mode"] == "optimise":
        out.update(eta=s["eta"] - e["eta"], clearance_m=s["clearance_m"] - e["clearance_m"],
                   clearance_ratio=s["clearance_m"] / e["clearance_m"])
    out["speedup"] = exact["cost"]["wall_s"] / max(slow["cost"]["wall_s"], 1e-9)
    return out
