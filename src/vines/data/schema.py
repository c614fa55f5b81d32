"""The one dataset schema of vines: every variable's CF ``long_name`` and ``units``.

Builders (``vines.data.builders``) take names from here, so a
quantity has one name and one description in every dataset. ``units`` is ``"1"`` for
dimensionless numbers and ``""`` for labels (strings). How the datasets meet the CF checkers
(and where they knowingly deviate): docs/cf-compliance.md.
"""
from __future__ import annotations

import numpy as np

from ..core.params import PARAM_NAMES

#: dimensions of the grid datasets, in order: the model parameters (eta, omega, F)
DIMS = PARAM_NAMES

CONVENTIONS = "CF-1.10"

COORD_ATTRS = {
    "eta": {"long_name": "ball-to-LO mass ratio eta = m/M", "units": "1"},
    "omega": {"long_name": "forcing frequency ratio omega = w/w0", "units": "1"},
    "F": {"long_name": "forcing amplitude F = A/L", "units": "1"},
}

#: CF discrete sampling geometry (CF 9) of the ragged datasets (sweeps, time histories): each
#: instance is one parameter point (eta, omega, F) whose samples are in time order, i.e. a
#: time series at a fixed "station" of parameter space (docs/cf-compliance.md: why not another)
FEATURE_TYPE = "timeSeries"
#: dtype of the count variable ``row_size`` of contiguous ragged arrays: CF 9.3.3 asks for an
#: integer type; the NCAS cfchecker accepts only 32-bit ``int`` (not ``int64``)
COUNT_DTYPE = np.dtype("i4")

#: fields of ``vines.simulate_batch`` stored per grid point: name -> (long_name, units)
BATCH_ATTRS = {
    "ke_ratio": ("kinetic energy ratio K_b/(K_m+K_b)", "1"),
    "xmax": ("max |z_m| over the window (dimensionless)", "1"),
    "xmax_whole_run": ("max |z_m| over the whole run (dimensionless)", "1"),
    "n_impacts": ("impacts in the whole run", "1"),
    "impacts_per_period": ("impacts per forcing period in the window", "1"),
    "t_stuck": ("time stuck in the window (dimensionless time)", "1"),
    "period": ("period of the stroboscopic section in forcing periods (0: none)", "1"),
    "regime": ("regime of the post-transient motion", ""),
    "status": ("solver status", ""),
    "shortcut_time": ("time from which the run was completed from one period of a settled "
                      "periodic orbit (NaN: integrated to t_end)", "1"),
}

#: variables derived from the batch fields by ``vines.core.measures.derived_measures``
DERIVED_ATTRS = {
    "xmax_m": ("max |x_m| over the window", "m"),
    "xmax_whole_run_m": ("max |x_m| over the whole run", "m"),
    "xmax_stuck_linear": ("steady-state amplitude of the stuck linear system (Eq. 28)", "1"),
    "xmax_stuck_linear_m": ("steady-state amplitude of the stuck linear system (Eq. 28)", "m"),
    "impacting": ("1 where the post-transient motion has impacts", "1"),
    "chatter": ("1 where the post-transient regime is chatter", "1"),
    "failed": ("1 where the run did not finish (status != ok)", "1"),
}

#: bifurcation sweeps: instance (one per swept value) and sample (one per impact) variables
SWEEP_INSTANCE_ATTRS = {
    "direction": ("sweep direction (+1 up, -1 down)", "1"),
    "line": ("index of the sweep line (outer value, direction)", "1"),
    "phi": ("forcing phase at the start of the point", "rad"),
    "status": ("solver status of the point", ""),
    "shortcut_time": ("time of the point's run (from its start) from which it was completed "
                      "from one period of a settled periodic orbit (NaN: not taken)", "1"),
}
SWEEP_SAMPLE_ATTRS = {
    "dw": ("relative velocity w' = z_m' - z_b' just before impact", "1"),
    "phase": ("impact phase mod(omega t + phi, 2 pi)", "rad"),
    "wall": ("wall hit (+1 left end L, -1 right end R)", "1"),
}

#: Lyapunov exponents along a sweep (``vines.attractors.lyapunov_sweep``), one per point
LYAPUNOV_SWEEP_ATTRS = {
    "exponents": ("Lyapunov exponents of the point's window, descending (-inf: direction "
                  "removed by sticking)", "1"),
    "exponents_ci": ("95 % batch-means interval of the Lyapunov exponents", "1"),
    "lambda_1": ("leading Lyapunov exponent of the point's window", "1"),
    "regime": ("regime of the point's window", ""),
    "n_impacts": ("impacts in the point's window", "1"),
    "n_sticks": ("sticking phases started in the point's window", "1"),
}

#: 1:1 branches (map-solve)
BRANCH_ATTRS = {
    "lambda_max": ("largest |eigenvalue| of the 1:1 map", "1"),
    "abs_eigenvalues": ("|eigenvalues| of J_P2 J_P1, decreasing", "1"),
    "stable": ("1 if all |lambda| < 1", "1"),
    "symmetric": ("1 if symmetric 1:1 orbit", "1"),
    "admissible": ("1 if admissible (no earlier contact)", "1"),
    "dw_L": ("relative velocity just before the L impact", "1"),
    "dw_R": ("relative velocity just before the R impact", "1"),
    "phase_L": ("phase of the L impact", "rad"),
    "phase_R": ("phase of the R impact", "rad"),
    "event_type": ("bifurcation / admissibility event type", ""),
    "event_branch": ("index of the branch on which the event lies", "1"),
    "family": ("orbit family of the branch (symmetric or asymmetric)", ""),
    "stopped": ("why the continuation of the branch ended", ""),
    "born_at": ("continued-parameter value of the symmetry-breaking point the branch "
                "starts from (NaN: the continued branch itself)", "1"),
}

#: boundary curves (boundaries): one instance per curve, one sample per curve point
BOUNDARY_CURVE_ATTRS = {
    "curve_type": ("codimension-one condition along the curve (fold, flip, "
                   "neimark-sacker, symmetry-breaking, grazing)", ""),
    "family": ("orbit family of the curve (symmetric or asymmetric)", ""),
    "flight": ("grazing flight (1: L->R, 2: R->L; 0: not a grazing curve)", "1"),
    "wall": ("grazing wall (start, target or arrival; empty: not a grazing curve)", ""),
}
#: the same variables where the curves are of a named wall sequence (not 1:1)
FAMILY_CURVE_ATTRS = {
    **BOUNDARY_CURVE_ATTRS,
    "family": ("orbit family of the curve (WALLS/N[-sym|-asym])", ""),
    "flight": ("grazing flight k (from impact k to impact k + 1 of the sequence; 0: not a "
               "grazing curve)", "1"),
    "wall": ("grazing wall (L or R: touched inside the flight; arrival: zero relative "
             "velocity at the impact; empty: not a grazing curve)", ""),
}

#: stability maps over (eta, omega)
STABILITY_ATTRS = {
    "lambda_max": ("largest |eigenvalue| of the 1:1 orbit", "1"),
    "cls": ("class of the 1:1 orbit", "1"),
    "dw_L": ("relative velocity just before the L impact", "1"),
    "symmetric": ("1 if symmetric", "1"),
}
STABILITY_CLASS_FLAGS = {
    "flag_values": np.array([0, 1, 2, 3], dtype="i1"),
    "flag_meanings": "no_admissible_1to1 symmetric_stable asymmetric_stable unstable",
}

#: time histories: per point, per sample (last periods), per window sample (the whole
#: measurement window, coarser) and per impact (the whole window) variables
TIMEHISTORY_ATTRS = {
    "t": ("time t = w0 t_dim", "1"),
    "z_m": ("LO displacement z_m (units of L)", "1"),
    "v_m": ("LO velocity z_m'", "1"),
    "z_b": ("ball displacement z_b (units of L)", "1"),
    "v_b": ("ball velocity z_b'", "1"),
    "window_t": ("time t = w0 t_dim, whole measurement window", "1"),
    "window_z_m": ("LO displacement z_m (units of L), whole measurement window", "1"),
    "window_v_m": ("LO velocity z_m', whole measurement window", "1"),
    "window_z_b": ("ball displacement z_b (units of L), whole measurement window", "1"),
    "window_v_b": ("ball velocity z_b', whole measurement window", "1"),
    "ke_ratio": BATCH_ATTRS["ke_ratio"],
    "xmax": BATCH_ATTRS["xmax"],
    "regime": BATCH_ATTRS["regime"],
    "status": BATCH_ATTRS["status"],
    "shortcut_time": BATCH_ATTRS["shortcut_time"],
    "impact_t": ("impact time", "1"),
    "impact_dw": ("relative velocity w' just before impact", "1"),
    "impact_phase": ("impact phase mod(omega t + phi, 2 pi)", "rad"),
    "impact_wall": ("wall hit (+1 L, -1 R)", "1"),
}


#: robust-TET maps over (eta, omega) (``vines.attractors.census_maps.robust_point``)
ROBUST_ATTRS = {
    "efficient_fraction": ("basin fraction of attractors with KE ratio above the threshold", "1"),
    "stable_1to1_fraction": ("basin fraction of the stable 1:1 orbit", "1"),
    "unsettled_fraction": ("fraction of initial states whose run stopped early", "1"),
    "n_attractors": ("number of attractors reached by the sampled initial states", "1"),
    "from_rest_efficient": ("1 where the start from rest reaches KE ratio above the threshold", "1"),
    "from_rest_ke_ratio": ("KE ratio of the attractor reached from rest", "1"),
}

#: the asymptotic view of a robust-TET map (``robust_point`` with t_max)
ROBUST_ASYMPTOTIC_ATTRS = {
    "efficient_fraction_asymptotic": ("basin fraction of attractors with KE ratio above the "
                                      "threshold, states followed to t_max", "1"),
    "stable_1to1_fraction_asymptotic": ("basin fraction of the stable 1:1 orbit, states "
                                        "followed to t_max", "1"),
    "escaped_fraction": ("fraction of initial states on another attractor at t_max than at "
                         "t_end (escaped from a transient)", "1"),
    "from_rest_efficient_asymptotic": ("1 where the start from rest is on an attractor with "
                                       "KE ratio above the threshold at t_max", "1"),
}

#: basin slices (``vines.attractors.census_maps.basin_slice``): per slice point, per attractor
BASIN_SLICE_ATTRS = {
    "z_m0": ("initial LO displacement z_m(0) (units of L)", "1"),
    "v_m0": ("initial LO velocity z_m'(0)", "1"),
    "attractor": ("index of the attractor reached (-1: run stopped early)", "1"),
    "regime": BATCH_ATTRS["regime"],
    "period": ("period of the attractor in forcing periods (0: not periodic)", "1"),
    "ke_ratio": ("KE ratio of the attractor (exact over one period, or mean)", "1"),
    "xmax_m": DERIVED_ATTRS["xmax_m"],
    "basin_fraction": ("fraction of the slice's points reaching the attractor", "1"),
    "from_rest": ("index of the attractor reached from rest (-1: stopped early)", "1"),
    "attractor_asymptotic": ("index of the attractor the point is on at t_max (-1: run "
                             "stopped early)", "1"),
    "basin_fraction_asymptotic": ("fraction of the slice's points on the attractor at t_max",
                                  "1"),
    "status": ("persistent, transient or unresolved (states followed to t_max)", ""),
    "regime_asymptotic": ("regime of the attractor at t_max: the window's label, or "
                          "quasi-periodic for a lasting motion whose strobe points fill a "
                          "closed curve", ""),
    "from_rest_asymptotic": ("index of the attractor the start from rest is on at t_max "
                             "(-1: stopped early)", "1"),
}


def attrs(table: dict, name: str, **extra) -> dict:
    """CF attributes of ``name`` from one of the tables above (plus ``extra``)."""
    long_name, units = table[name]
    return {"long_name": long_name, "units": units, **extra}


# ------------------------------------------------------------------ solver studies

#: per-run variables of the work-precision datasets: name -> (long_name, units)
WORK_PRECISION_ATTRS = {
    "solver": ("solver", ""),
    "method": ("method (exact: closed-form event kernel; else scipy solve_ivp)", ""),
    "knob": ("accuracy setting varied in this run", ""),
    "tolerance": ("value of the varied setting (root_tol, v_stick or rtol)", "1"),
    "v_stick": ("sticking threshold of the run", "1"),
    "t_error": ("max |impact time - reference| over visible impacts (NaN: sequence differs)", "1"),
    "ke_error": ("|KE ratio - reference|", "1"),
    "xmax_error": ("|x_max - reference| (dimensionless, units of L)", "1"),
    "seconds": ("wall-clock time per run", "s"),
    "impacts_per_second": ("impacts simulated per second of wall-clock time", "s-1"),
    "n_impacts": ("impacts in the run", "1"),
    "n_visible": ("visible impacts compared (|w'-| >= v_visible)", "1"),
    "sequence_ok": ("visible impacts in the reference's order on the same walls", "1"),
    "status": ("solver status", ""),
}
#: flag attributes of 0/1 variables, by variable name (flag_values int8 like the variable)
FLAG_MEANINGS = {
    "sequence_ok": "differs same",
    "converged": "not_converged converged",
    "regime_same": "regime_differs regime_same",
}

#: fixed variables and coordinates of the convergence datasets: name -> (long_name, units)
CONVERGENCE_ATTRS = {
    "point": ("parameter point index", "1"),
    "label": ("parameter point", ""),
    "t_end": ("end of the run (from rest at t = 0)", "1"),
    "window": ("window rule index", "1"),
    "window_rule": ("window rule: fixed length or fraction of the run", ""),
    "window_length": ("window length t_end - t_transient (length rules)", "1"),
    "window_fraction": ("window length as a fraction of t_end (fraction rules)", "1"),
    "t_transient": ("start of the measurement window", "1"),
    "converged_from_t_end": ("shortest run from which every longer run of the same window "
                             "rule is converged", "1"),
    "reference_t_transient": ("window start of the reference run", "1"),
    "v_stick": ("sticking threshold on the relative velocity after an impact", "1"),
    "run_time": ("wall-clock time of the run (time.perf_counter)", "s"),
    "converged_below": ("largest v_stick at and below which every run is converged", "1"),
    "resolution": ("grid points per axis", "1"),
    "stride": ("index step of the grid in the finest grid", "1"),
    "spacing_eta": ("grid spacing in eta", "1"),
    "spacing_omega": ("grid spacing in omega", "1"),
    "contour_dist_mean": ("arc-length mean distance of the contour to the finest grid's "
                          "contour", "1"),
    "contour_dist_max": ("max distance of the contour to the finest grid's contour "
                         "(one-sided Hausdorff)", "1"),
    "contour_hausdorff": ("symmetric Hausdorff distance of the contour and the finest "
                          "grid's contour", "1"),
    "contour_length": ("length of the contour in the (omega, eta) plane", "1"),
    "area_fraction": ("fraction of the (eta, omega) rectangle where the KE ratio exceeds "
                      "the level", "1"),
    "d_area_fraction": ("area fraction minus the finest grid's", "1"),
}
#: the reference each convergence study compares with (in long_names and attrs)
REFERENCES = {"window": "longest run's widest window", "vstick": "smallest v_stick"}
TITLES = {
    "window": "convergence of the measures with run length and window",
    "vstick": "convergence of the measures with the sticking threshold v_stick",
    "grid": "convergence of the KE-ratio contour with grid resolution",
}
#: per-run measures of the window and v_stick datasets: long_name, units from the schema
MEASURE_ATTRS = {**BATCH_ATTRS, "xmax_m": DERIVED_ATTRS["xmax_m"]}


# ------------------------------------------------------------------ design, orbit atlas

#: design datasets (``vines.studies.design``): coordinates, curves, per-amplitude values,
#: the search grid and the scalars of the designs compared
DESIGN_ATTRS = {
    "omega": COORD_ATTRS["omega"]["long_name"],
    "amplitude": "base displacement amplitude A",
    "search_eta": "ball-to-LO mass ratio m/M of the search grid",
    "search_clearance": "clearance L (half the cavity length) of the search grid",
    "lo_alone_ratio": "transmissibility x_max/A of the LO alone (closed form)",
    "tmd_ratio": "transmissibility x_max/A with the optimal TMD (closed form)",
    "vines_ratio": "transmissibility x_max/A of the VI NES from rest",
    "vines_ratio_any_attractor": "largest transmissibility x_max/A over the attractors "
                                 "holding >= basin_min of the census states and the start "
                                 "from rest",
    "F": "forcing amplitude F = A/L of the design",
    "vines_peak_ratio": "largest transmissibility from rest found per amplitude (grid and "
                        "refinement in omega)",
    "vines_peak_omega": "forcing frequency ratio of vines_peak_ratio",
    "vines_peak_ratio_any_attractor": "worst-case transmissibility over the attractors per "
                                      "amplitude",
    "search_worst_ratio": "worst-case transmissibility from rest of each grid design",
    "lo_alone_worst_ratio": "worst-case transmissibility of the LO alone over the band (exact)",
    "lo_alone_worst_omega": "forcing frequency ratio of lo_alone_worst_ratio",
    "tmd_eta": "TMD mass ratio m_a/M",
    "tmd_frequency_ratio": "TMD tuning w_a/w0",
    "tmd_damping_ratio": "TMD damping ratio c_a/(2 m_a w_a)",
    "tmd_worst_ratio": "worst-case transmissibility with the TMD over the band",
    "tmd_worst_omega": "forcing frequency ratio of tmd_worst_ratio",
    "tmd_mass": "TMD mass m_a",
    "tmd_stiffness": "TMD spring stiffness",
    "tmd_damping": "TMD damping coefficient",
    "vines_eta": "ball-to-LO mass ratio m/M of the VI NES design",
    "vines_clearance": "clearance L (half the cavity length) of the VI NES design",
    "vines_mass": "ball mass m of the VI NES design",
    "vines_worst_ratio": "worst-case transmissibility of the VI NES from rest",
    "vines_worst_ratio_any_attractor": "worst-case transmissibility of the VI NES over "
                                       "attractors",
    "unsettled_fraction_max": "largest share of census runs that stopped early",
    "tmd_travel": "travel |u - x|/A of the optimal TMD's mass relative to the LO (closed "
                  "form)",
    "tmd_worst_travel": "largest travel |u - x|/A of the optimal TMD over the band",
    "tmd_stroke": "stroke of the optimal TMD: tmd_worst_travel times the largest amplitude",
    "vines_stroke": "travel of the ball relative to the LO: +-L, the clearance",
    "tmd_equal_travel_ratio": "transmissibility x_max/A with the TMD whose stroke stays "
                              "within the VI NES's clearance (closed form)",
    "tmd_equal_travel_frequency_ratio": "tuning w_a/w0 of the TMD of equal travel",
    "tmd_equal_travel_damping_ratio": "damping ratio of the TMD of equal travel",
    "tmd_equal_travel_worst_ratio": "worst-case transmissibility with the TMD of equal "
                                    "travel over the band",
    "tmd_equal_travel_stroke": "stroke of the TMD of equal travel at the largest amplitude",
}
#: units of the design variables that are not dimensionless
DESIGN_UNITS = {"amplitude": "m", "search_clearance": "m", "tmd_mass": "kg",
                "tmd_stiffness": "N m-1", "tmd_damping": "N s m-1",
                "vines_clearance": "m", "vines_mass": "kg", "tmd_stroke": "m",
                "vines_stroke": "m", "tmd_equal_travel_stroke": "m"}

#: design_robust datasets (``vines.studies.mistuning``): worst cases over the host's drift
#: delta (nominal designs on ``delta``, robust ones on ``robust_delta``) and the designs
DESIGN_ROBUST_ATTRS = {
    "delta": "host frequency drift: natural frequency (1 + delta) w0 (nominal designs)",
    "robust_delta": "host frequency drift: natural frequency (1 + delta) w0 (robust "
                    "designs)",
    "lo_alone": "worst-case transmissibility x_max/A over band and amplitudes of the LO "
                "alone",
    "tmd": "worst-case transmissibility over band and amplitudes with the TMD",
    "vines": "worst-case transmissibility over band and amplitudes of the VI NES from rest",
    "vines_any_attractor": "worst-case transmissibility over band and amplitudes of the "
                           "VI NES over attractors",
    "tmd_frequency_ratio": "TMD tuning w_a/w0",
    "tmd_damping_ratio": "TMD damping ratio c_a/(2 m_a w_a)",
    "vines_eta": "ball-to-LO mass ratio m/M of the VI NES design",
    "vines_clearance": "clearance L (half the cavity length) of the VI NES design",
    "worst_lo_alone": "largest worst-case transmissibility over delta of the LO alone",
    "worst_tmd": "largest worst-case transmissibility over delta with the TMD",
    "worst_vines": "largest worst-case transmissibility over delta of the VI NES from rest",
    "worst_vines_any_attractor": "largest worst-case transmissibility over delta of the "
                                 "VI NES over attractors",
}
DESIGN_ROBUST_UNITS = {"vines_clearance": "m"}
#: uncertain parts of a design (``vines.studies.uncertainty``): name -> (long_name, units);
#: per point, per parameter, per regime group and the scalars of the two absorbers
UNCERTAINTY_ATTRS = {
    "parameter": ("uncertain part (frequency, clearance, mass: relative deviations; r: the "
                  "restitution)", ""),
    "bound": ("end of a 95 % bootstrap confidence interval", ""),
    "regime_group": ("regime of the VI NES at a point's worst (omega, amplitude), grouped", ""),
    "block": ("pick-freeze block of the point (A, B, or AB_<parameter>)", ""),
    "value": ("value of the uncertain part at the point", "1"),
    "vines_worst_ratio": ("worst-case transmissibility x_max/A of the VI NES from rest", "1"),
    "vines_regime": ("regime of the run from rest at the VI NES's worst point", ""),
    "tmd_worst_ratio": ("worst-case transmissibility x_max/A with the TMD (closed form)", "1"),
    "regime_share": ("share of the points whose worst point is in the regime group", "1"),
    "vines_first_order": ("first-order Sobol index of the VI NES's worst ratio", "1"),
    "vines_total_order": ("total Sobol index of the VI NES's worst ratio", "1"),
    "vines_first_order_ci": ("95 % bootstrap interval of vines_first_order", "1"),
    "vines_total_order_ci": ("95 % bootstrap interval of vines_total_order", "1"),
    "vines_index_reliable": ("1 where both intervals of the VI NES's indices are narrow", "1"),
    "tmd_first_order": ("first-order Sobol index of the TMD's worst ratio", "1"),
    "tmd_total_order": ("total Sobol index of the TMD's worst ratio", "1"),
    "tmd_first_order_ci": ("95 % bootstrap interval of tmd_first_order", "1"),
    "tmd_total_order_ci": ("95 % bootstrap interval of tmd_total_order", "1"),
    "tmd_index_reliable": ("1 where both intervals of the TMD's indices are narrow", "1"),
    "vines_nominal": ("worst-case transmissibility of the VI NES with exact parts", "1"),
    "vines_mean": ("mean of vines_worst_ratio over the points", "1"),
    "vines_q95": ("95 % quantile of vines_worst_ratio over the points", "1"),
    "tmd_nominal": ("worst-case transmissibility of the TMD with exact parts", "1"),
    "tmd_mean": ("mean of tmd_worst_ratio over the points", "1"),
    "tmd_q95": ("95 % quantile of tmd_worst_ratio over the points", "1"),
    "efficient_probability": ("share of the points whose worst point is in the efficient "
                              "1:1 regime", "1"),
    "vines_better_probability": ("share of the points where the VI NES's worst ratio is "
                                 "below the TMD's", "1"),
    "vines_eta": ("ball-to-LO mass ratio m/M of the VI NES design (exact parts)", "1"),
    "vines_clearance": ("clearance L of the VI NES design (exact parts)", "m"),
    "tmd_eta": ("TMD mass ratio m_a/M (exact parts)", "1"),
}

#: orbit atlases (``vines.orbits.atlas.atlas``): per family, and per family and grid point
ATLAS_FAMILY_ATTRS = {
    "family": ("periodic orbit family (wall sequence/forcing periods, -sym/-asym; "
               "docs/bifurcation.md)", ""),
    "paper_label": ("the paper's p:q wording of the family (1:1, 2:2, 2:1, 3:2, 3:3, "
                    "period-2)", ""),
    "walls": ("wall sequence of the family's orbits, one letter per impact (L, R)", ""),
    "periods": ("forcing periods of one orbit period", "1"),
}
ATLAS_ATTRS = {
    "found": ("1 if an orbit of the family was found (admissible or not)", "1"),
    "admissible": ("1 if an admissible orbit of the family was found", "1"),
    "stable": ("1 if a stable admissible orbit of the family was found", "1"),
    "lambda_max": ("least largest |eigenvalue| among the admissible orbits of the family "
                   "found (NaN: none)", "1"),
}
#: flag attributes of the atlas's 0/1 variables
ATLAS_FLAGS = {"flag_values": np.array([0, 1], dtype="i1"), "flag_meanings": "no yes"}
ATLAS_NOTE = ("finite search: a family marked absent may exist where no seed reached it "
              "(docs/bifurcation.md)")

# ------------------------------------------------------------------ shock

#: shock datasets (``vines.studies.shock``): the curve against the initial energy (VI NES per
#: energy, the linear systems once: their fractions do not depend on it), the decays in time
SHOCK_ATTRS = {
    "energy": ("initial energy E0 = M V0^2/2 of the LO", "J"),
    "velocity": ("initial LO velocity V0 of the impulse", "m s-1"),
    "history_energy": ("initial energy E0 of a decay in time", "J"),
    "time_periods": ("time after the shock in natural periods 2 pi/w0 of the LO", "1"),
    "vines_dissipated_fraction": ("fraction of E0 dissipated within the window by the LO "
                                  "with the VI NES", "1"),
    "vines_by_damping": ("fraction of E0 dissipated by the LO's damping (VI NES)", "1"),
    "vines_by_impacts": ("fraction of E0 dissipated by the impacts (VI NES)", "1"),
    "vines_n_impacts": ("impacts within the window (VI NES)", "1"),
    "vines_n_sticks": ("sticking events within the window (VI NES)", "1"),
    "vines_t_10": ("time to decay to 10 % of E0 (VI NES; NaN: not within the window)", "s"),
    "vines_t_1": ("time to decay to 1 % of E0 (VI NES; NaN: not within the window)", "s"),
    "vines_t_reached": ("end of the VI NES run: the window's end unless the solver stopped "
                        "early (status)", "s"),
    "vines_status": ("solver status of the VI NES run", ""),
    "tmd_dissipated_fraction": ("fraction of E0 dissipated within the window with the TMD "
                                "(any E0)", "1"),
    "tmd_by_damping": ("fraction of E0 dissipated by the LO's damping with the TMD", "1"),
    "tmd_by_absorber": ("fraction of E0 dissipated by the TMD's damper", "1"),
    "tmd_t_10": ("time to decay to 10 % of E0 with the TMD (NaN: not within the window)", "s"),
    "tmd_t_1": ("time to decay to 1 % of E0 with the TMD (NaN: not within the window)", "s"),
    "tmd_frequency_ratio": ("TMD tuning w_a/w0 (tuned for omega_band as vines design)", "1"),
    "tmd_damping_ratio": ("TMD damping ratio c_a/(2 m_a w_a)", "1"),
    "lo_alone_dissipated_fraction": ("fraction of E0 dissipated within the window by the LO "
                                     "alone (any E0)", "1"),
    "lo_alone_t_10": ("time to decay to 10 % of E0, LO alone (NaN: not within the window)",
                      "s"),
    "lo_alone_t_1": ("time to decay to 1 % of E0, LO alone (NaN: not within the window)", "s"),
    "activation_energy": ("least E0 at which the ball is hit (the free LO's first peak "
                          "reaches the wall)", "J"),
    "activation_velocity": ("initial LO velocity of activation_energy", "m s-1"),
    "optimal_energy": ("E0 of the curve at which the VI NES dissipates most", "J"),
    "optimal_dissipated_fraction": ("largest dissipated fraction of the VI NES on the curve",
                                    "1"),
    "vines_remaining": ("energy left with the VI NES, fraction of E0 (NaN: after the run "
                        "stopped)", "1"),
    "vines_history_by_impacts": ("fraction of E0 dissipated by impacts so far (VI NES)", "1"),
    "vines_history_n_impacts": ("impacts so far (VI NES; -1: after the run stopped)", "1"),
    "tmd_remaining": ("energy left with the TMD, fraction of E0", "1"),
    "vines_stroke": ("travel of the ball relative to the LO: +-L, the clearance", "m"),
    "lo_alone_x_max": ("peak |x| of the LO alone after the shock", "m"),
    "tmd_stroke": ("peak |y - x| of the band-tuned TMD's mass relative to the LO after the "
                   "shock", "m"),
    "tmd_fastest_stroke": ("peak |y - x| of the fastest-decaying TMD after the shock", "m"),
    "tmd_equal_travel_stroke": ("peak |y - x| of the fastest TMD whose stroke stays within "
                                "L at the largest energy, after the shock", "m"),
    "tmd_decay_rate": ("slowest decay rate of LO + band-tuned TMD", "s-1"),
    "tmd_fastest_decay_rate": ("slowest decay rate of LO + TMD, maximised (the modes "
                               "coalesce)", "s-1"),
    "tmd_equal_travel_decay_rate": ("slowest decay rate of LO + TMD, maximised with the "
                                    "stroke within L at the largest energy", "s-1"),
    "tmd_fastest_dissipated_fraction": ("fraction of E0 dissipated within the window with "
                                        "the fastest-decaying TMD (any E0)", "1"),
    "tmd_fastest_t_1": ("time to decay to 1 % of E0 with the fastest-decaying TMD (NaN: "
                        "not within the window)", "s"),
    "tmd_fastest_frequency_ratio": ("tuning w_a/w0 of the fastest-decaying TMD", "1"),
    "tmd_fastest_damping_ratio": ("damping ratio of the fastest-decaying TMD", "1"),
    "tmd_equal_travel_dissipated_fraction": ("fraction of E0 dissipated within the window "
                                             "with the TMD of equal travel (any E0)", "1"),
    "tmd_equal_travel_t_1": ("time to decay to 1 % of E0 with the TMD of equal travel "
                             "(NaN: not within the window)", "s"),
    "tmd_equal_travel_frequency_ratio": ("tuning w_a/w0 of the TMD of equal travel", "1"),
    "tmd_equal_travel_damping_ratio": ("damping ratio of the TMD of equal travel", "1"),
    "ball_position": ("ball's position at the moment of the shock, units of L from the "
                      "cavity centre (uniform over the cavity, seeded)", "1"),
    "ball_velocity_fraction": ("ball's velocity at the moment of the shock, fraction of the "
                               "LO's V0 (uniform in (-1, 1), seeded)", "1"),
    "vines_start_dissipated_fraction": ("fraction of the initial energy (LO and ball) "
                                        "dissipated within the window by the VI NES from "
                                        "each ball start", "1"),
    "vines_start_quantile": ("quantiles of vines_start_dissipated_fraction over the ball "
                             "starts", "1"),
    "quantile": ("probability level of vines_start_quantile", "1"),
    "lo_alone_remaining": ("energy left, LO alone, fraction of E0", "1"),
}

# ------------------------------------------------------------------ model ladder

#: model-ladder datasets (``vines.studies.model_ladder``): per panel (eta) the grid, the
#: slow flow's and the exact orbits' amplitudes (padded rows), the continued branches, the
#: simulation from rest, the slow flow's error and each model's cost
MODEL_LADDER_ATTRS = {
    "eta": (COORD_ATTRS["eta"]["long_name"] + " of the panel", "1"),
    "sigma": ("scaled detuning sigma = (omega - 1)/eta of the grid", "1"),
    "sigma_dense": ("scaled detuning of the slow flow's dense curve", "1"),
    "model": ("model of the ladder", ""),
    "tolerance": ("relative amplitude error tolerance of a band", "1"),
    "F": ("forcing amplitude F = f eta of the panel", "1"),
    "omega": (COORD_ATTRS["omega"]["long_name"] + " of the grid", "1"),
    "omega_dense": (COORD_ATTRS["omega"]["long_name"] + " of the dense curve", "1"),
    "xi_min": ("activation threshold of the slow flow: the LO amplitude at the fold of its "
               "slow invariant manifold", "1"),
    "slowflow_amplitude": ("LO amplitude max |z_m| of each slow-flow fixed point (units of "
                           "L; NaN: no more fixed points)", "1"),
    "slowflow_stable": ("1 where the slow-flow fixed point is stable", "1"),
    "slowflow_error": ("relative difference of the slow flow's amplitude from the nearest "
                       "exact symmetric 1:1 orbit at the same omega (NaN: none)", "1"),
    "dense_amplitude": ("LO amplitude of each slow-flow fixed point on the dense curve", "1"),
    "dense_stable": ("1 where the fixed point on the dense curve is stable", "1"),
    "exact_amplitude": ("LO amplitude max |z_m| over a period of each exact admissible "
                        "symmetric 1:1 orbit (map solve; NaN: no more orbits)", "1"),
    "exact_stable": ("1 where the exact orbit is stable (map eigenvalues)", "1"),
    "continuation_omega": ("omega along a continued exact branch (NaN: padding)", "1"),
    "continuation_amplitude": ("LO amplitude along a continued exact branch (NaN: not "
                               "admissible or padding)", "1"),
    "continuation_stable": ("1 where the continued orbit is stable", "1"),
    "simulation_xmax": ("max |z_m| over the window of the exact simulation from rest "
                        "(units of L)", "1"),
    "simulation_regime": ("regime of the simulation from rest", ""),
    "n_slowflow": ("slow-flow fixed points at the grid frequency", "1"),
    "n_exact": ("exact admissible symmetric 1:1 orbits found at the grid frequency", "1"),
    "error_max": ("largest relative amplitude difference of the slow flow's fixed points from "
                  "the exact orbits, both sorted (0: neither has an orbit; NaN: their "
                  "numbers differ)", "1"),
    "band_lo": ("lowest omega of the widest run of grid frequencies within the tolerance "
                "(NaN: none)", "1"),
    "band_hi": ("highest omega of that run (NaN: none)", "1"),
    "share_within": ("share of the grid frequencies within the tolerance", "1"),
    "seconds": ("wall-clock time of the model over the panel's grid (time.perf_counter; "
                "the slow flow: mean of repeated calls)", "s"),
}

# ------------------------------------------------------------------ design map

#: design-map datasets (``vines.studies.design_map``): per cell (eta, half_width, span) the
#: slow flow's best VI NES, the TMD free and at equal travel, their ratios and the exact check
DESIGN_MAP_ATTRS = {
    "eta": ("ball-to-LO mass ratio eta = m/M (the TMD's mass ratio too)", "1"),
    "half_width": ("half width h of the band omega in [1 - h, 1 + h] around the host's "
                   "natural frequency (drift modelled as the band)", "1"),
    "span": ("amplitude span A_max/A_min of the base amplitudes", "1"),
    "restitution": ("coefficient of restitution r of the grid searched", "1"),
    "vines_worst_ratio": ("worst x_max/A over the band and amplitudes of the slow flow's best "
                          "VI NES (clearance and restitution optimised)", "1"),
    "vines_worst_omega": ("omega of the slow flow's worst case", "1"),
    "vines_clearance_m": ("clearance L (half the cavity) of the slow flow's best VI NES; the "
                          "ball's travel relative to the LO is +-L", "m"),
    "vines_restitution": ("restitution r of the slow flow's best VI NES", "1"),
    "vines_in_domain": ("1 where the slow flow's best design is inside its stated domain "
                        "(eta, d, F_max <= the warning limits, |omega - 1| <= 0.2: no "
                        "warning; r > 0: no sticking; docs/slowflow.md, section 8)", "1"),
    "vines_worst_ratio_by_restitution": ("slow flow's worst x_max/A at the best clearance "
                                         "for each restitution", "1"),
    "tmd_frequency_ratio": ("frequency ratio f = w_a/w0 of the band-optimal TMD (free)", "1"),
    "tmd_damping_ratio": ("damping ratio of the band-optimal TMD (free)", "1"),
    "tmd_worst_ratio": ("worst |X/Y| over the band of the band-optimal TMD (free)", "1"),
    "tmd_worst_omega": ("omega of the free TMD's worst case", "1"),
    "tmd_worst_travel": ("largest travel |U - X|/|Y| over the band of the free TMD, per unit "
                         "base amplitude", "1"),
    "tmd_equal_travel_frequency_ratio": ("frequency ratio of the band-optimal TMD with travel "
                                         "<= the VI NES's clearance at A_max", "1"),
    "tmd_equal_travel_damping_ratio": ("damping ratio of the TMD at equal travel", "1"),
    "tmd_equal_travel_worst_ratio": ("worst |X/Y| over the band of the TMD at equal travel",
                                     "1"),
    "tmd_equal_travel_worst_omega": ("omega of the equal-travel TMD's worst case", "1"),
    "tmd_equal_travel_worst_travel": ("largest travel per unit base amplitude of the TMD at "
                                      "equal travel", "1"),
    "ratio": ("slow flow's VI NES worst ratio over the free TMD's (> 1: the TMD wins)", "1"),
    "ratio_equal_travel": ("slow flow's VI NES worst ratio over the equal-travel TMD's (> 1: "
                           "the TMD wins)", "1"),
    "confirm": ("why the exact solver checked the cell", "1"),
    "vines_worst_ratio_exact": ("exact worst x_max/A from rest at the slow flow's design "
                                "(NaN: not checked)", "1"),
    "vines_worst_ratio_exact_by_restitution": ("exact worst x_max/A from rest at the slow "
                                               "flow's best clearance for each restitution "
                                               "(NaN: not checked)", "1"),
    "vines_restitution_exact": ("restitution of the exact check's best design (NaN: not "
                                "checked)", "1"),
    "vines_worst_ratio_exact_refined": ("exact worst x_max/A from rest of the exact check's "
                                        "best design: the best restitution, then a local "
                                        "search of the clearance (NaN: not checked)", "1"),
    "vines_clearance_m_exact_refined": ("clearance of the exact local search's best design "
                                        "(NaN: not checked)", "m"),
    "tmd_equal_travel_exact_worst_ratio": ("worst |X/Y| of the TMD with travel <= the exact "
                                           "check's clearance at A_max (NaN: not checked)",
                                           "1"),
    "exact_runs": ("exact runs from rest of the cell's check", "1"),
    "slowflow_relative_error": ("(slow flow - exact)/exact worst x_max/A at the slow flow's "
                                "design (NaN: not checked)", "1"),
    "verdict_ratio": ("VI NES worst ratio over the free TMD's: exact refined where checked, "
                      "else the slow flow's", "1"),
    "verdict_ratio_equal_travel": ("VI NES worst ratio over the equal-travel TMD's: where "
                                   "checked the exact refined design's over the TMD limited "
                                   "to its clearance, else the slow flow's", "1"),
    "verdict_differs": ("1 where the exact check and the slow flow name opposite winners "
                        "against the free TMD (a ratio within 5 % of 1: a tie)", "1"),
    "verdict_differs_equal_travel": ("1 where the exact check and the slow flow name "
                                     "opposite winners against the equal-travel TMD (a "
                                     "ratio within 5 % of 1: a tie)", "1"),
    "tmd_travel_over_clearance": ("travel the free TMD needs at A_max over the VI NES's "
                                  "clearance L", "1"),
}
#: flag attributes of the design map's ``confirm``
DESIGN_MAP_CONFIRM_FLAGS = {"flag_values": np.array([0, 1, 2], dtype="i1"),
                            "flag_meanings": "not_checked frontier sample"}
