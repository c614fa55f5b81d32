"""Cheap valid calls of every public function and the junk and extreme values fed to them.

Used by test_public_api_fuzz.py: each case is (function, valid keyword arguments); a fuzzed
call replaces one argument by a drawn value. Arguments whose in-range values can make a call
long (run lengths, counts, grid sizes) draw only from small valid values besides the junk.
"""
from __future__ import annotations

import math
from importlib import import_module

import numpy as np

from vines.core.params import ModelParams

NAN, INF = math.nan, math.inf
#: values of the wrong type or outside every range
JUNK = ("", {}, [], (), None, "abc", "1e3x", np.array([1.0, NAN]), np.array([]), NAN, INF, -INF,
        -1, -1e-300, 2**70, 1e308, -1e308, True, object(), [[1.0, 2.0]], np.array([[0.5]]),
        (1.0,), (NAN, 1.0), {"eta": 1.0})
#: in-range and boundary values of numeric arguments (each case refuses or answers)
EXTREMES = (0, 0.0, -0.0, 5e-324, 1e-300, 1e-12, 0.5, 1, 1.0, 2.0, 1e3, 1e4, 1e9, "0.5", 3)
#: valid values of arguments whose large values make a call long (run lengths, counts)
SMALL = (0, 1, 2, 3, 0.5, 5e-324, 1e-300, 10.0, 20.0)

P = dict(eta=0.05, omega=1.0, F=0.05)
SIM = dict(t_end=20.0, t_transient=10.0)


def _fn(module, name):
    return getattr(import_module(module), name)


def cases() -> dict:
    """name -> (function, valid cheap keyword arguments, bounded arguments).

    Bounded arguments (a set of names, or a dict name -> values) draw their valid values
    from SMALL (or the values given) instead of EXTREMES."""
    params = ModelParams(eta=0.2, omega=1.0, F=0.1)
    return {
        "simulate": (_fn("vines.solvers", "simulate"), {**P, **SIM},
                     {"t_end", "t_transient", "max_impacts"}),
        "simulate_batch": (_fn("vines.core.simulation", "simulate_batch"),
                           {**P, **SIM, "n_threads": 1}, {"t_end", "t_transient", "max_impacts"}),
        "find_1to1": (_fn("vines.orbits.family.periodic", "find_1to1"), {**P, "simulation": False}, set()),
        "find_sequence": (_fn("vines.orbits.family.sequence", "find_sequence"),
                          dict(params=params, walls="LR", periods=1, simulation=False), {"periods"}),
        "atlas_point": (_fn("vines.orbits.atlas.atlas", "atlas_point"),
                        dict(params=params, simulation=False, sim_t_end=20.0), {"sim_t_end"}),
        "continue_branch": (_fn("vines.orbits.continuation.one_to_one", "continue_branch"),
                            dict(param="F", start=0.1, stop=0.09, step=0.005,
                                 fixed={"eta": 0.2, "omega": 1.0}, max_points=20),
                            {"start", "stop", "step", "max_points", "min_step"}),
        "continue_sequence": (_fn("vines.orbits.continuation.sequence", "continue_sequence"),
                              dict(params=params, walls="LR", periods=1, param="F", stop=0.09,
                                   settings=_fn("vines.orbits.continuation.sequence",
                                                "ContinueSettings")(step=0.005, max_points=5)),
                              {"stop", "periods"}),
        "stability_map": (_fn("vines.orbits.atlas.stability_map", "stability_map"),
                          dict(eta=[0.05, 0.1], omega=[1.0], F=0.05, n_threads=1), set()),
        "census": (_fn("vines.attractors.census", "census"),
                   {**P, **SIM, "n": 2, "n_threads": 1}, {"n", "t_end", "t_transient", "max_impacts"}),
        "robust_point": (_fn("vines.attractors.census_maps", "robust_point"),
                         {**P, **SIM, "threshold": 0.5, "n": 2, "n_threads": 1},
                         {"n", "t_end", "t_transient", "max_impacts"}),
        "basin_slice": (_fn("vines.attractors.census_maps", "basin_slice"),
                        {**P, **SIM, "z_m0": [0.0, 0.5], "v_m0": [0.0], "n_threads": 1},
                        {"t_end", "t_transient", "max_impacts"}),
        "bifurcation_sweep": (_fn("vines.core.sweep", "bifurcation_sweep"),
                              dict(param="F", values=[0.05, 0.06], eta=0.05, omega=1.0,
                                   t_settle=20.0, t_step=10.0, n_record=2),
                              {"t_settle", "t_step", "n_record", "max_impacts_per_period"}),
        # no 1:1 orbit in this box (F small, omega = 3): the seeds end at once
        "boundaries": (_fn("vines.orbits.curves.boundaries", "boundaries"),
                       dict(F=0.001, eta_range=(0.05, 0.06), omega_range=(3.0, 3.1), n_scan=1,
                            max_points=2, n_map=2),
                       {"F": (0, 0.0, 1e-3, 2e-3), "r": (0.0, 0.65), "d": (0.01, 0.1),
                        "n_scan": (1, 2), "max_points": (1, 2), "n_map": (0, 1, 2),
                        "step": (1e-5, 0.01, 1.0), "eta_range": ((0.05, 0.06),),
                        "omega_range": ((3.0, 3.1), (3.0, 3.05)), "walls": ("LR", "LLRR"),
                        "periods": (1, 2)}),
        "design": (_fn("vines.studies.design", "design"),
                   dict(n_omega=2, amplitudes_m=(0.003,), eta=0.05, clearance_m=0.015,
                        census_n=0, t_end=20.0, t_transient=10.0, n_threads=1),
                   {"n_omega", "census_n", "t_end", "t_transient", "max_impacts", "n_eta",
                    "n_clearance"}),
        "slowflow_response": (_fn("vines.slowflow", "response"), P, set()),
        "slowflow_frc": (_fn("vines.slowflow", "frc"),
                         dict(eta=0.05, omegas=[0.9, 1.0, 1.1], F=0.05), set()),
        "optimal_F": (_fn("vines.slowflow", "optimal_F"), dict(eta=0.05, n_omega=5, n_grid=5),
                      {"n_omega": (3, 5), "n_grid": (3, 5)}),
        "optimal_clearance": (_fn("vines.slowflow", "optimal_clearance"),
                              dict(eta=0.05, amplitudes_m=(0.003,), n_omega=5, n_grid=5),
                              {"n_omega": (3, 5), "n_grid": (3, 5)}),
        "slowflow_design": (_fn("vines.studies.design_slowflow", "slowflow_design"),
                            dict(amplitudes_m=(0.003,), eta=0.05, clearance_m=0.015),
                            {"n_eta": (1, 2)}),
        "optimal_tmd": (_fn("vines.studies.tmd", "optimal_tmd"),
                        dict(mu=0.05, d=0.012, band=(0.8, 1.2), max_travel=100.0), set()),
        "work_precision": (_fn("vines.studies.workprecision", "work_precision"),
                           {**P, "t_end": 2.0, "t_transient": 1.0, "rk_methods": ("RK45",),
                            "rtols": (1e-4,), "dps": 20, "max_impacts": 1000, "min_time": 1e-3},
                           {"t_end": (1.0, 2.0, 10.0, 20.0), "t_transient": (0, 0.0, 1.0, 10.0),
                            "dps": (20, 25), "max_impacts": (1, 2, 1000),
                            "rtols": ((1e-4,), (1e-2,)), "root_tols": ((1e-13,), (1e-3,)),
                            "h_sample": (0.05, 0.5), "min_time": (1e-3, 0.01),
                            "v_stick_reference": (1e-14, 1e-6), "v_sticks": ((), (1e-3,)),
                            "eta": (0.05, 1.0), "omega": (0.5, 1.0, 3.0), "F": (0, 0.05, 0.5),
                            "r": (0, 0.65, 1), "d": (0, 0.012, 1.0), "v_stick": (0, 1e-6, 1.0),
                            "v_visible": (1e-3, 1.0)}),
        "window_convergence": (_fn("vines.studies.convergence", "window_convergence"),
                               dict(points=[P], t_ends=(20.0, 30.0), window_lengths=(10.0,),
                                    window_fractions=(0.5,), t_end=20.0, t_transient=10.0,
                                    n_threads=1),
                               {"t_ends", "window_lengths", "t_end", "t_transient",
                                "max_impacts"}),
        "grid_convergence": (_fn("vines.studies.convergence", "grid_convergence"),
                             dict(eta_range=(0.05, 0.1), omega_range=(0.9, 1.1), F=0.05,
                                  resolutions=(2, 3), t_end=20.0, t_transient=10.0,
                                  n_threads=1),
                             {"resolutions", "t_end", "t_transient", "max_impacts"}),
        "vstick_convergence": (_fn("vines.studies.convergence", "vstick_convergence"),
                               dict(points=[P], v_sticks=(1e-3, 1e-6), t_end=20.0,
                                    t_transient=10.0, n_threads=1),
                               {"t_end", "t_transient", "max_impacts"}),
    }
