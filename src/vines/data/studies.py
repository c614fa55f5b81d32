"""Dataset builders of the solver studies (``vines.studies``): result objects in, CF datasets out.

* :func:`work_precision_dataset`: a ``WorkPrecisionResult`` over dimension ``run``;
* :func:`convergence_dataset` (``window_dataset``, ``vstick_dataset``, ``grid_dataset``):
  the results of ``vines.studies.convergence`` over (point, window, t_end), (point,
  v_stick) and (eta, omega) + resolution.

Every variable gets ``long_name`` and ``units`` (``"1"`` dimensionless, ``""`` labels) from
the tables below or from ``vines.data.schema``; 0/1 flags are int8 with int8
``flag_values``. ``attrs`` (e.g. ``vines.data.provenance.provenance_attrs``) are merged
over the study's own global attributes.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from .schema import BATCH_ATTRS, CONVENTIONS, COORD_ATTRS, DERIVED_ATTRS

# ------------------------------------------------------------------ work precision

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


def _flag_attrs(name: str) -> dict:
    return {"flag_values": np.array([0, 1], dtype="i1"), "flag_meanings": FLAG_MEANINGS[name]}


def _var(dims, data, long_name, units, **extra) -> xr.Variable:
    return xr.Variable(dims, data, {"long_name": long_name, "units": units, **extra})


def work_precision_dataset(result, attrs: dict | None = None) -> xr.Dataset:
    """Dataset over dimension ``run`` of a ``vines.studies.workprecision.WorkPrecisionResult``."""
    data = {}
    for k, (long_name, units) in WORK_PRECISION_ATTRS.items():
        extra = _flag_attrs(k) if k in FLAG_MEANINGS else {}
        values = result.runs[k].astype("i1") if extra else result.runs[k]
        data[k] = _var("run", values, long_name, units, **extra)
    c, ref, lim = result.case, result.reference, result.reference_limit
    own = {f"case_{k}": c[k] for k in ("eta", "omega", "F", "r", "d")}
    own.update({k: c[k] for k in ("t_end", "t_transient", "v_visible")})
    own.update({
        "reference": f"vines.hiprec at {ref['dps']} digits, sampling step {ref['h_sample']}",
        **{f"reference_{k}": ref[k] for k in ("v_stick", "n_impacts", "ke_ratio", "xmax",
                                              "n_sticks")},
        "comment": "seconds are wall-clock measurements: they vary from run to run",
    })
    if lim is not None:
        own.update({f"reference_limit_{k}": lim[k]
                    for k in ("v_stick", "n_impacts", "ke_ratio", "xmax")})
    return xr.Dataset(data, attrs={**own, **(attrs or {})})


# ------------------------------------------------------------------ convergence

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


def _cv(name, dims, data, **extra) -> xr.Variable:
    return _var(dims, data, *CONVERGENCE_ATTRS[name], **extra)


def _difference_vars(dims, diff: dict, ke_tol, xmax_rtol, ref: str) -> dict:
    """d_ke, rel_d_xmax and the 0/1 flags converged, regime_same over ``dims``."""
    conv = (f"1 where |d_ke| <= {ke_tol:g} and |rel_d_xmax| <= {xmax_rtol:g} "
            f"(difference to the {ref})")
    return {
        "d_ke": _var(dims, diff["d_ke"], f"KE ratio minus its value at the {ref}", "1"),
        "rel_d_xmax": _var(dims, diff["rel_d_xmax"],
                           f"relative difference of x_max to the {ref}", "1"),
        "converged": _var(dims, np.asarray(diff["converged"]).astype("i1"), conv, "1",
                          **_flag_attrs("converged")),
        "regime_same": _var(dims, np.asarray(diff["regime_same"]).astype("i1"),
                            f"1 where the regime equals the {ref}'s", "1",
                            **_flag_attrs("regime_same")),
    }


def _tested_vars(data: dict, tested: dict, where: str) -> dict:
    """``tested_<name>``: the differences at the tested setting (over ``point``)."""
    out = {}
    for name in ("d_ke", "rel_d_xmax", "converged", "regime_same"):
        v = data[name]
        out[f"tested_{name}"] = _var(("point",), np.asarray(tested[name]).astype(v.dtype),
                                     f"{v.attrs['long_name']}, at the tested {where}",
                                     v.attrs["units"],
                                     **{a: v.attrs[a] for a in ("flag_values", "flag_meanings")
                                        if a in v.attrs})
    return out


def _measure_vars(dims, measures: dict) -> dict:
    return {k: _var(dims, a, *MEASURE_ATTRS[k]) for k, a in measures.items()}


def _point_coords(pts: list[dict]) -> dict:
    c = {"point": _cv("point", ("point",), np.arange(len(pts)))}
    for k in ("eta", "omega", "F"):
        c[k] = xr.Variable(("point",), np.array([p[k] for p in pts]), COORD_ATTRS[k])
    c["label"] = _cv("label", ("point",), np.array([p["label"] for p in pts]))
    return c


def _global_attrs(study: str, own: dict, solver: dict, attrs: dict | None) -> dict:
    base = {"Conventions": CONVENTIONS, "title": TITLES[study], **own,
            **{f"solver_{k}": v for k, v in solver.items()}}
    return {**base, **(attrs or {})}


def window_dataset(result, attrs: dict | None = None) -> xr.Dataset:
    """Dataset over (point, window, t_end) of a ``WindowConvergence``."""
    dims = ("point", "window", "t_end")
    ref = REFERENCES["window"]
    data = _measure_vars(dims, result.measures)
    data.update(_difference_vars(dims, result.differences, result.ke_tol, result.xmax_rtol,
                                 ref))
    data["t_transient"] = _cv("t_transient", dims, result.t_transient)
    data["converged_from_t_end"] = _cv("converged_from_t_end", ("point", "window"),
                                       result.converged_from_t_end)
    data["reference_t_transient"] = _cv("reference_t_transient", ("point",),
                                        result.reference_t_transient)
    data.update(_tested_vars(data, result.tested,
                             f"setting t_end = {result.tested_t_end:g}, t_transient = "
                             f"{result.tested_t_transient:g}"))
    rules = result.rules
    coords = _point_coords(result.points)
    coords["t_end"] = _cv("t_end", ("t_end",), result.t_end)
    coords["window"] = _cv("window", ("window",), np.arange(len(rules)))
    coords["window_rule"] = _cv("window_rule", ("window",), np.array([k for k, _ in rules]))
    coords["window_length"] = _cv("window_length", ("window",), np.array(
        [x if k == "length" else np.nan for k, x in rules]))
    coords["window_fraction"] = _cv("window_fraction", ("window",), np.array(
        [x if k == "fraction" else np.nan for k, x in rules]))
    own = {"reference": "largest t_end, widest window", "ke_tol": result.ke_tol,
           "xmax_rtol": result.xmax_rtol, "whole_periods": int(result.whole_periods),
           "tested_t_end": result.tested_t_end,
           "tested_t_transient": result.tested_t_transient,
           "tested_window": result.tested_window}
    return xr.Dataset(data, coords=coords,
                      attrs=_global_attrs("window", own, result.solver, attrs))


def vstick_dataset(result, attrs: dict | None = None) -> xr.Dataset:
    """Dataset over (point, v_stick) of a ``VStickConvergence``."""
    dims = ("point", "v_stick")
    data = _measure_vars(dims, result.measures)
    data.update(_difference_vars(dims, result.differences, result.ke_tol, result.xmax_rtol,
                                 REFERENCES["vstick"]))
    data["run_time"] = _cv("run_time", dims, result.run_time)
    data["converged_below"] = _cv("converged_below", ("point",), result.converged_below)
    data.update(_tested_vars(data, result.tested, f"v_stick = {result.tested_v_stick:g}"))
    coords = _point_coords(result.points)
    coords["v_stick"] = _cv("v_stick", ("v_stick",), result.v_stick)
    own = {"reference": REFERENCES["vstick"], "ke_tol": result.ke_tol,
           "xmax_rtol": result.xmax_rtol, "tested_v_stick": result.tested_v_stick}
    return xr.Dataset(data, coords=coords,
                      attrs=_global_attrs("vstick", own, result.solver, attrs))


def grid_dataset(result, attrs: dict | None = None) -> xr.Dataset:
    """Dataset over (eta, omega) and ``resolution`` of a ``GridConvergence``."""
    grid = ("eta", "omega")
    data = {k: _var(grid, result.fields[k], *BATCH_ATTRS[k])
            for k in ("ke_ratio", "xmax", "regime")}
    data.update({k: _cv(k, ("resolution",), a) for k, a in result.per_resolution.items()})
    coords = {"eta": xr.Variable(("eta",), result.eta, COORD_ATTRS["eta"]),
              "omega": xr.Variable(("omega",), result.omega, COORD_ATTRS["omega"]),
              "resolution": _cv("resolution", ("resolution",), result.resolution)}
    own = {"F": result.F, "level": result.level,
           "distance": "Euclidean in the (omega, eta) plane, parameter units"}
    return xr.Dataset(data, coords=coords,
                      attrs=_global_attrs("grid", own, result.solver, attrs))


#: dataset builder of each convergence study
CONVERGENCE_BUILDERS = {"window": window_dataset, "vstick": vstick_dataset,
                        "grid": grid_dataset}


def convergence_dataset(study: str, result, attrs: dict | None = None) -> xr.Dataset:
    """Dataset of the convergence study ``study`` (window, vstick or grid) from its result."""
    try:
        build = CONVERGENCE_BUILDERS[study]
    except KeyError:
        raise ValueError(f"unknown convergence study {study!r}: one of "
                         f"{', '.join(CONVERGENCE_BUILDERS)}") from None
    return build(result, attrs)
