"""One dataset builder per pipeline stage: plain arrays in, CF datasets out.

Names, ``long_name`` and ``units`` come from ``vines.data.schema``. Layouts:

* grids and measures over dims (eta, omega, F);
* bifurcation sweeps and time histories as CF contiguous ragged arrays (``row_size``, 32-bit
  int, with ``sample_dimension``) of the discrete sampling geometry ``featureType``
  ``timeSeries``: one instance per parameter point, whose (parameter, time) coordinates the
  ``coordinates`` attribute of every data variable names (docs/cf-compliance.md);
* 1:1 branches (``branch`` instances of ``point`` samples, plus ``event``) and boundary
  curves (``curve`` instances of ``point`` samples) as contiguous ragged arrays too;
  stability maps over (eta, omega);
* the solver studies (``vines.studies``): work precision over dimension ``run``; the
  convergence studies over (point, window, t_end), (point, v_stick) and (eta, omega) +
  resolution. 0/1 flags are int8 with int8 ``flag_values``; ``attrs`` (provenance) are
  merged over the study's own global attributes.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..core.conventions import BATCH_FIELDS
from ..core.params import PARAM_NAMES
from .schema import (
    ATLAS_ATTRS,
    ATLAS_FAMILY_ATTRS,
    ATLAS_FLAGS,
    ATLAS_NOTE,
    BASIN_SLICE_ATTRS,
    BATCH_ATTRS,
    BOUNDARY_CURVE_ATTRS,
    BRANCH_ATTRS,
    CONVENTIONS,
    CONVERGENCE_ATTRS,
    COORD_ATTRS,
    COUNT_DTYPE,
    DERIVED_ATTRS,
    DESIGN_ATTRS,
    DESIGN_MAP_ATTRS,
    DESIGN_MAP_CONFIRM_FLAGS,
    DESIGN_ROBUST_ATTRS,
    DESIGN_ROBUST_UNITS,
    DESIGN_UNITS,
    FAMILY_CURVE_ATTRS,
    FEATURE_TYPE,
    FLAG_MEANINGS,
    LYAPUNOV_SWEEP_ATTRS,
    MEASURE_ATTRS,
    MODEL_LADDER_ATTRS,
    REFERENCES,
    ROBUST_ASYMPTOTIC_ATTRS,
    ROBUST_ATTRS,
    SHOCK_ATTRS,
    STABILITY_ATTRS,
    STABILITY_CLASS_FLAGS,
    SWEEP_INSTANCE_ATTRS,
    SWEEP_SAMPLE_ATTRS,
    TIMEHISTORY_ATTRS,
    TITLES,
    UNCERTAINTY_ATTRS,
    WORK_PRECISION_ATTRS,
)
from .schema import attrs as cf

#: fill value of a grid point no chunk provided, by dtype kind
FILL = {"f": np.nan, "i": -1, "U": "", "b": False}


def _variables(dims, arrays: dict, table: dict) -> dict:
    return {k: xr.Variable(dims, np.asarray(a), cf(table, k)) for k, a in arrays.items()}


# ------------------------------------------------------------------ grids and measures

def _coords(axes: dict) -> dict:
    return {d: xr.Variable((d,), np.asarray(axes[d], dtype=float), COORD_ATTRS[d])
            for d in PARAM_NAMES}


def grid_dataset(axes: dict, fields: dict, attrs: dict) -> xr.Dataset:
    """Dataset over dims (eta, omega, F) holding ``fields`` (``simulate_batch`` arrays)."""
    data = {name: xr.Variable(PARAM_NAMES, np.asarray(arr).astype(BATCH_FIELDS[name]),
                              cf(BATCH_ATTRS, name))
            for name, arr in fields.items()}
    return xr.Dataset(data, coords=_coords(axes), attrs=attrs)


def merge_chunks(datasets, axes: dict) -> dict:
    """Place chunk datasets (each a sub-grid) into the full grid given by ``axes``.

    Values are matched exactly (chunks are cut from the same axes). Raises ValueError when a
    chunk value is not on an axis or a grid point is missing.
    """
    full = {d: np.asarray(axes[d], dtype=float) for d in PARAM_NAMES}
    shape = tuple(full[d].size for d in PARAM_NAMES)
    out = {k: np.full(shape, FILL[np.dtype(dt).kind], dtype=dt) for k, dt in BATCH_FIELDS.items()}
    seen = np.zeros(shape, dtype=bool)
    for ds in datasets:
        idx = []
        for d in PARAM_NAMES:
            v = ds[d].values
            pos = np.clip(np.searchsorted(full[d], v), 0, full[d].size - 1)
            if not np.array_equal(full[d][pos], v):
                raise ValueError(f"chunk values of {d} are not on the grid axis")
            idx.append(pos)
        ix = np.ix_(*idx)
        for k in BATCH_FIELDS:
            out[k][ix] = ds[k].values.astype(out[k].dtype)
        seen[ix] = True
    if not seen.all():
        raise ValueError(f"{int((~seen).sum())} grid points missing from the chunks")
    return out


def measures_dataset(grid: xr.Dataset, derived: dict, sections: dict) -> xr.Dataset:
    """The grid dataset plus derived measures and ``section_<dim>`` markers (int8 flags)."""
    ds = grid.copy()
    ds.update(_variables(PARAM_NAMES, derived, DERIVED_ATTRS))
    for dim, mark in sections.items():
        ds[f"section_{dim}"] = xr.Variable(
            (dim,), np.asarray(mark, dtype="i1"),
            {"long_name": f"1 where {dim} is one of the requested sections", "units": "1",
             "flag_values": np.array([0, 1], dtype="i1"),
             "flag_meanings": "not_section section"})
    return ds


# ------------------------------------------------------------------ ragged arrays

def count_variable(row_size, instance_dim: str, sample_dim: str, long_name: str) -> xr.Variable:
    """The CF count variable of a contiguous ragged array: ``row_size`` as 32-bit int
    (``COUNT_DTYPE``, values unchanged) with ``sample_dimension``."""
    rs = np.asarray(row_size)
    if rs.size and (rs.dtype.kind not in "iub" or rs.min() < 0
                    or rs.max() > np.iinfo(COUNT_DTYPE).max):
        raise ValueError(f"row_size must be non-negative integers that fit {COUNT_DTYPE}")
    return xr.Variable((instance_dim,), rs.astype(COUNT_DTYPE), {
        "long_name": long_name, "units": "1", "sample_dimension": sample_dim})


def _dsg(data: dict, attrs: dict, coordinates: dict) -> xr.Dataset:
    """Dataset of a discrete sampling geometry: global ``featureType`` and, on every variable
    named in ``coordinates`` (name -> blank-separated coordinate names), a CF ``coordinates``
    attribute."""
    for name, coords in coordinates.items():
        data[name].attrs = {**data[name].attrs, "coordinates": coords}
    return xr.Dataset(data, attrs={**attrs, "featureType": FEATURE_TYPE})


def ragged_dataset(instances: dict, samples: dict, row_size, *, instance_dim: str,
                   sample_dim: str, attrs: dict, coordinates=()) -> xr.Dataset:
    """CF contiguous ragged array: ``row_size`` samples per instance, one after another.

    ``instances`` / ``samples``: name -> (array, long_name, units); ``coordinates``: names of
    the instance variables that locate an instance (named in the ``coordinates`` attribute of
    every other instance and sample variable). The dataset gets the global ``featureType``.
    """
    data = {}
    for name, (arr, ln, un) in instances.items():
        data[name] = xr.Variable((instance_dim,), np.asarray(arr), {"long_name": ln, "units": un})
    for name, (arr, ln, un) in samples.items():
        data[name] = xr.Variable((sample_dim,), np.asarray(arr), {"long_name": ln, "units": un})
    count = count_variable(row_size, instance_dim, sample_dim,
                           f"number of {sample_dim}s of each {instance_dim}")
    n = int(count.values.sum(dtype=np.int64))
    for name, (arr, _, _) in samples.items():
        if np.asarray(arr).shape[0] != n:
            raise ValueError(f"{name}: {np.asarray(arr).shape[0]} samples, row_size sums to {n}")
    data["row_size"] = count
    coords = " ".join(coordinates)
    located = {k: coords for k in data if coords and k not in coordinates and k != "row_size"}
    return _dsg(data, attrs, located)


def ragged_rows(ds: xr.Dataset, name: str, row_size: str = "row_size") -> list[np.ndarray]:
    """Split a contiguous ragged sample variable into one array per instance."""
    rs = ds[row_size].values
    edges = np.concatenate([[0], np.cumsum(rs)])
    v = ds[name].values
    return [v[edges[i]:edges[i + 1]] for i in range(rs.size)]


def sweep_dataset(sweep: dict, param: str, outer: str, attrs: dict) -> xr.Dataset:
    """Bifurcation sweep lines (``pipeline.stages`` assembly) as a ragged array of impacts."""
    inst = {
        "value": (sweep["value"], f"swept parameter {param}: " + COORD_ATTRS[param]["long_name"], "1"),
        "outer_value": (sweep["outer_value"], f"outer parameter {outer}: "
                        + COORD_ATTRS[outer]["long_name"], "1"),
    }
    inst.update({k: (sweep[k], *SWEEP_INSTANCE_ATTRS[k]) for k in SWEEP_INSTANCE_ATTRS})
    samples = {k: (sweep[k], *SWEEP_SAMPLE_ATTRS[k]) for k in SWEEP_SAMPLE_ATTRS}
    return ragged_dataset(inst, samples, sweep["row_size"], instance_dim="point",
                          sample_dim="impact", attrs=attrs, coordinates=("value", "outer_value"))


def lyapunov_sweep_dataset(res: dict, param: str, outer: str, attrs: dict) -> xr.Dataset:
    """Lyapunov exponents along sweep lines (``pipeline.stages.lyapunov`` assembly): per
    point the spectrum, its intervals, the leading exponent, regime and event counts."""
    P = ("point",)
    inst = {"value": (res["value"], f"swept parameter {param}: "
                      + COORD_ATTRS[param]["long_name"], "1"),
            "outer_value": (res["outer_value"], f"outer parameter {outer}: "
                            + COORD_ATTRS[outer]["long_name"], "1")}
    inst.update({k: (res[k], *SWEEP_INSTANCE_ATTRS[k]) for k in ("direction", "line", "phi",
                                                                  "status")})
    data = {k: xr.Variable(P, np.asarray(v), {"long_name": ln, "units": u})
            for k, (v, ln, u) in inst.items()}
    a = LYAPUNOV_SWEEP_ATTRS
    data["exponents"] = xr.Variable(("point", "exponent"), np.asarray(res["exponents"], "f8"),
                                    cf(a, "exponents"))
    data["exponents_ci"] = xr.Variable(("point", "exponent", "bound"),
                                       np.asarray(res["ci"], "f8"), cf(a, "exponents_ci"))
    data["lambda_1"] = xr.Variable(P, np.asarray(res["exponents"], "f8")[:, 0],
                                   cf(a, "lambda_1"))
    data["regime"] = xr.Variable(P, np.asarray(res["regime"], "U16"), cf(a, "regime"))
    for k in ("n_impacts", "n_sticks"):
        data[k] = xr.Variable(P, np.asarray(res[k], "i4"), cf(a, k))
    coords = {k: data.pop(k) for k in ("value", "outer_value")}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def timehistory_dataset(points: list[dict], th: dict, attrs: dict) -> xr.Dataset:
    """Time histories (``core.measures.time_histories``) of ``points``: samples of the last
    periods per point (incomplete multidimensional array over (point, sample)), samples of
    the whole measurement window if any (over (point, window_sample)), impacts of the window
    as a contiguous ragged array; one ``timeSeries`` per point, located by (eta, omega, F)
    and timed by ``t`` / ``window_t`` / ``impact_t``."""
    dims_of = {"": ("point", "sample"), "window_": ("point", "window_sample")}
    data = {k: xr.Variable(("point",), np.asarray([p[k] for p in points]), COORD_ATTRS[k])
            for k in PARAM_NAMES}
    where = " ".join(PARAM_NAMES)
    coordinates = {}
    for k in [k for k in TIMEHISTORY_ATTRS if k in th]:
        prefix = "window_" if k.startswith("window_") else ""
        if k.startswith("impact_"):
            dims, time = ("impact",), "impact_t "
        elif k[len(prefix):] in ("t", "z_m", "v_m", "z_b", "v_b"):
            dims, time = dims_of[prefix], f"{prefix}t "
        else:
            dims, time = ("point",), ""
        data[k] = xr.Variable(dims, np.asarray(th[k]), cf(TIMEHISTORY_ATTRS, k))
        if k not in ("t", "window_t", "impact_t"):
            coordinates[k] = time + where
        if k == "status":
            data["row_size"] = count_variable(th["row_size"], "point", "impact",
                                              "number of impacts of each point")
    return _dsg(data, attrs, coordinates)


# ------------------------------------------------------------------ orbits

#: per-point variables of a branch dataset (besides eta, omega, F)
BRANCH_POINT_VARS = ("lambda_max", "stable", "symmetric", "admissible", "dw_L", "dw_R",
                     "phase_L", "phase_R")


def _branch_rows(br) -> list:
    """The continued branch, then the branches switched onto at its symmetry-breaking
    points (``Branch.switched``), in that order."""
    return [br] + list(getattr(br, "switched", []))


def branch_dataset(br, attrs: dict) -> xr.Dataset:
    """A continued 1:1 branch (``orbits.continuation.one_to_one.Branch``) and the asymmetric branches
    born at its symmetry-breaking points, as a CF contiguous ragged array: instance
    ``branch`` (row 0 the continued branch, ``row_size`` points each), samples ``point``
    in continuation order; events over ``event`` with the branch they lie on."""
    rows = _branch_rows(br)
    P = ("point",)
    cat = {k: np.concatenate([np.asarray(getattr(b, k)) for b in rows])
           for k in PARAM_NAMES + BRANCH_POINT_VARS}
    data = {k: xr.Variable(P, cat[k], COORD_ATTRS[k]) for k in PARAM_NAMES}
    for k in BRANCH_POINT_VARS:
        a = cat[k].astype("i1") if k in ("stable", "symmetric", "admissible") else cat[k]
        data[k] = xr.Variable(P, a, cf(BRANCH_ATTRS, k))
    data["abs_eigenvalues"] = xr.Variable(
        ("point", "eig"), np.concatenate([np.asarray(b.abs_eigenvalues).reshape(-1, 4)
                                          for b in rows]),
        cf(BRANCH_ATTRS, "abs_eigenvalues"))
    B = ("branch",)
    data["family"] = xr.Variable(B, np.asarray([b.family for b in rows], dtype="U16"),
                                 cf(BRANCH_ATTRS, "family"))
    data["stopped"] = xr.Variable(B, np.asarray([str(b.stopped) for b in rows], dtype="U64"),
                                  cf(BRANCH_ATTRS, "stopped"))
    data["born_at"] = xr.Variable(B, np.asarray(
        [float(b.born_at["at"]) if getattr(b, "born_at", None) else np.nan for b in rows]),
        cf(BRANCH_ATTRS, "born_at"))
    data["row_size"] = count_variable(np.asarray([len(b) for b in rows]), "branch", "point",
                                      "number of points of each branch")
    events = [(i, e) for i, b in enumerate(rows) for e in b.events]
    data["event_type"] = xr.Variable(("event",), np.asarray([e["type"] for _, e in events],
                                                             dtype="U32"),
                                     cf(BRANCH_ATTRS, "event_type"))
    data["event_at"] = xr.Variable(("event",), np.asarray([float(e["at"]) for _, e in events],
                                                          dtype=float),
                                   {"long_name": f"{br.param} value of the event", "units": "1"})
    data["event_branch"] = xr.Variable(("event",), np.asarray([i for i, _ in events], "i4"),
                                       cf(BRANCH_ATTRS, "event_branch"))
    where = " ".join(PARAM_NAMES)
    return _dsg(data, attrs, {k: where for k in BRANCH_POINT_VARS + ("abs_eigenvalues",)})


def boundaries_dataset(curves: list, F: float, attrs: dict,
                       named_family: bool = False) -> xr.Dataset:
    """Boundary curves (``orbits.curves.boundaries.Boundaries.curves``) at one F as a CF contiguous
    ragged array: instance ``curve``, samples ``point`` = (eta, omega) along the curve;
    named_family: the curves of a wall sequence named by its walls and periods (their
    variables' long names say so), not of the 1:1 orbit."""
    table = FAMILY_CURVE_ATTRS if named_family else BOUNDARY_CURVE_ATTRS
    pts = [np.asarray(c.points, float).reshape(-1, 2) for c in curves]
    allp = np.concatenate(pts) if pts else np.empty((0, 2))
    inst = {
        "curve_type": (np.asarray([c.type for c in curves], dtype="U32"),
                       *table["curve_type"]),
        "family": (np.asarray([c.family for c in curves],
                              dtype=f"U{max([16] + [len(c.family) for c in curves])}"),
                   *table["family"]),
        "flight": (np.asarray([c.graze[0] if c.graze else 0 for c in curves], "i4"),
                   *table["flight"]),
        "wall": (np.asarray([c.graze[1] if c.graze else "" for c in curves], dtype="U16"),
                 *table["wall"]),
    }
    samples = {q: (allp[:, k], COORD_ATTRS[q]["long_name"], COORD_ATTRS[q]["units"])
               for k, q in enumerate(("eta", "omega"))}
    ds = ragged_dataset(inst, samples, np.asarray([len(p) for p in pts], dtype="i8"),
                        instance_dim="curve", sample_dim="point", attrs={**attrs, "F": float(F)})
    # a curve point is located by (eta, omega): each names the other as its coordinate
    ds["eta"].attrs["coordinates"], ds["omega"].attrs["coordinates"] = "omega", "eta"
    return ds


def stability_dataset(eta, omega, res: dict, attrs: dict) -> xr.Dataset:
    """A stability map (``orbits.atlas.stability_map``) over (eta, omega)."""
    D = ("eta", "omega")
    for k in STABILITY_ATTRS:
        if np.shape(res[k]) != (np.size(eta), np.size(omega)):
            raise ValueError(f"stability_map returned {k} with shape {np.shape(res[k])}, "
                             f"expected (eta, omega) = {(np.size(eta), np.size(omega))}")
    data = {
        "lambda_max": xr.Variable(D, np.asarray(res["lambda_max"]), cf(STABILITY_ATTRS, "lambda_max")),
        "cls": xr.Variable(D, np.asarray(res["cls"], dtype="i1"),
                           cf(STABILITY_ATTRS, "cls", **STABILITY_CLASS_FLAGS)),
        "dw_L": xr.Variable(D, np.asarray(res["dw_L"]), cf(STABILITY_ATTRS, "dw_L")),
        "symmetric": xr.Variable(D, np.asarray(res["symmetric"], dtype="i1"),
                                 cf(STABILITY_ATTRS, "symmetric")),
    }
    return xr.Dataset(data, coords=_eta_omega_coords(eta, omega), attrs=attrs)


def _eta_omega_coords(eta, omega) -> dict:
    return {"eta": xr.Variable(("eta",), np.asarray(eta, float), COORD_ATTRS["eta"]),
            "omega": xr.Variable(("omega",), np.asarray(omega, float), COORD_ATTRS["omega"])}


def robust_dataset(eta, omega, fields: dict, attrs: dict) -> xr.Dataset:
    """A robust-TET map (``attractors.census_maps.robust_point`` fields) over (eta, omega)."""
    D = ("eta", "omega")
    shape = (np.size(eta), np.size(omega))
    data = {}
    for k in ROBUST_ATTRS:
        arr = np.asarray(fields[k])
        if arr.shape != shape:
            raise ValueError(f"robust map field {k} has shape {arr.shape}, expected {shape}")
        dtype = "i4" if k in ("n_attractors", "from_rest_efficient") else "f8"
        data[k] = xr.Variable(D, arr.astype(dtype), cf(ROBUST_ATTRS, k))
    for k in [k for k in ROBUST_ASYMPTOTIC_ATTRS if k in fields]:   # with t_max only
        dtype = "i4" if k == "from_rest_efficient_asymptotic" else "f8"
        data[k] = xr.Variable(D, np.asarray(fields[k]).astype(dtype).reshape(shape),
                              cf(ROBUST_ASYMPTOTIC_ATTRS, k))
    return xr.Dataset(data, coords=_eta_omega_coords(eta, omega), attrs=attrs)


def basin_slice_dataset(z_m0, v_m0, res: dict, attrs: dict) -> xr.Dataset:
    """A basin slice (``attractors.census_maps.basin_slice``): attractor index over (z_m0, v_m0)
    and the attractor table over ``attractor_index``."""
    a = BASIN_SLICE_ATTRS
    table = res["table"]
    n_att = len(table["regime"])
    data = {"attractor": xr.Variable(("z_m0", "v_m0"), np.asarray(res["attractor"], "i4"),
                                     cf(a, "attractor")),
            "from_rest": xr.Variable((), np.int32(res["from_rest"]), cf(a, "from_rest"))}
    for k, dt in (("regime", "U16"), ("period", "i4"), ("ke_ratio", "f8"), ("xmax_m", "f8"),
                  ("basin_fraction", "f8")):
        data[k] = xr.Variable(("attractor_index",), np.asarray(table[k], dt).reshape(n_att),
                              cf(a, k))
    if "attractor_asymptotic" in res:                          # with t_max only
        data["attractor_asymptotic"] = xr.Variable(
            ("z_m0", "v_m0"), np.asarray(res["attractor_asymptotic"], "i4"),
            cf(a, "attractor_asymptotic"))
        data["from_rest_asymptotic"] = xr.Variable((), np.int32(res["from_rest_asymptotic"]),
                                                   cf(a, "from_rest_asymptotic"))
        for k, dt in (("basin_fraction_asymptotic", "f8"), ("status", "U16"),
                      ("regime_asymptotic", "U16")):
            data[k] = xr.Variable(("attractor_index",),
                                  np.asarray(table[k], dt).reshape(n_att), cf(a, k))
    coords = {"z_m0": xr.Variable(("z_m0",), np.asarray(z_m0, float), cf(a, "z_m0")),
              "v_m0": xr.Variable(("v_m0",), np.asarray(v_m0, float), cf(a, "v_m0"))}
    return xr.Dataset(data, coords=coords, attrs=attrs)


# ------------------------------------------------------------------ solver studies: work precision



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


def window_convergence_dataset(result, attrs: dict | None = None) -> xr.Dataset:
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


def vstick_convergence_dataset(result, attrs: dict | None = None) -> xr.Dataset:
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


def grid_convergence_dataset(result, attrs: dict | None = None) -> xr.Dataset:
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
CONVERGENCE_BUILDERS = {"window": window_convergence_dataset,
                        "vstick": vstick_convergence_dataset,
                        "grid": grid_convergence_dataset}


def convergence_dataset(study: str, result, attrs: dict | None = None) -> xr.Dataset:
    """Dataset of the convergence study ``study`` (window, vstick or grid) from its result."""
    try:
        build = CONVERGENCE_BUILDERS[study]
    except KeyError:
        raise ValueError(f"unknown convergence study {study!r}: one of "
                         f"{', '.join(CONVERGENCE_BUILDERS)}") from None
    return build(result, attrs)


# ------------------------------------------------------------------ design, orbit atlas

def _dv(name, dims, data, dtype="f8") -> xr.Variable:
    return xr.Variable(dims, np.asarray(data, dtype=dtype),
                       {"long_name": DESIGN_ATTRS[name], "units": DESIGN_UNITS.get(name, "1")})


def _nan(x) -> float:
    return float("nan") if x is None else float(x)


def design_dataset(result, attrs: dict) -> xr.Dataset:
    """A design (``studies.design.DesignResult``): curves over (amplitude, omega), values
    per amplitude, the search grid (an optimisation only) and the scalars of the LO alone,
    the optimal TMD and the VI NES design. ``attrs`` (provenance) are merged over the
    design's own (mode, view, structure, census, run settings, how each worst case is
    taken)."""
    out = result.to_dict()
    pb, vin, tmd = result.problem, out["vines"], out["tmd"]
    A, W = ("amplitude",), ("omega",)
    coords = {"omega": _dv("omega", W, pb.omega), "amplitude": _dv("amplitude", A, pb.amplitudes_m)}
    data = {"lo_alone_ratio": _dv("lo_alone_ratio", W, result.lo_alone),
            "tmd_ratio": _dv("tmd_ratio", W, result.tmd_curve),
            "vines_ratio": _dv("vines_ratio", A + W, result.rest.curves),
            "F": _dv("F", A, vin["F"]),
            "vines_peak_ratio": _dv("vines_peak_ratio", A, result.rest.peak),
            "vines_peak_omega": _dv("vines_peak_omega", A, result.rest.peak_omega)}
    if result.vines_any_attractor is not None:
        data["vines_ratio_any_attractor"] = _dv("vines_ratio_any_attractor", A + W,
                                                result.vines_any_attractor)
        data["vines_peak_ratio_any_attractor"] = _dv("vines_peak_ratio_any_attractor", A,
                                                     result.worst_any_per_amplitude)
    if result.search is not None:
        g = result.search
        coords["search_eta"] = _dv("search_eta", ("search_eta",), g["eta"])
        coords["search_clearance"] = _dv("search_clearance", ("search_clearance",),
                                         g["clearance_m"])
        data["search_worst_ratio"] = _dv("search_worst_ratio",
                                         ("search_eta", "search_clearance"), g["worst_ratio"])
    scalars = {"lo_alone_worst_ratio": out["lo_alone"]["worst_ratio"],
               "lo_alone_worst_omega": out["lo_alone"]["worst_omega"],
               "tmd_eta": tmd["eta"], "tmd_frequency_ratio": tmd["frequency_ratio"],
               "tmd_damping_ratio": tmd["damping_ratio"],
               "tmd_worst_ratio": tmd["worst_ratio"], "tmd_worst_omega": tmd["worst_omega"],
               "tmd_mass": tmd["mass_kg"], "tmd_stiffness": tmd["stiffness_N_per_m"],
               "tmd_damping": tmd["damping_Ns_per_m"],
               "vines_eta": vin["eta"], "vines_clearance": vin["clearance_m"],
               "vines_mass": vin["mass_kg"], "vines_worst_ratio": vin["worst_ratio"],
               "vines_worst_ratio_any_attractor": vin["worst_ratio_any_attractor"],
               "unsettled_fraction_max": vin["unsettled_fraction_max"]}
    data.update({k: _dv(k, (), _nan(v)) for k, v in scalars.items()})
    data.update(_design_travel(result, out))
    own = {"Conventions": CONVENTIONS, "mode": out["inputs"].get("mode", ""),
           "view": pb.view, "view_description": vin["view_description"] or "not evaluated "
           "(census_n = 0)", "d": pb.model.d, "r": pb.model.r, "M_kg": pb.M_kg,
           "k_N_per_m": pb.k_N_per_m, "c_Ns_per_m": pb.c_Ns_per_m, "census_n": pb.census_n,
           "census_seed": pb.census_seed, "basin_min": pb.basin_min,
           "t_end": pb.settings.t_end, "t_transient": pb.settings.t_transient,
           **{f"worst_case_{k}": v for k, v in out["worst_case"].items()}}
    return xr.Dataset(data, coords=coords, attrs={**own, **attrs})


def _design_travel(result, out: dict) -> dict:
    """The strokes of a design and the TMD of equal travel (when one exists)."""
    W, omega, d = ("omega",), np.asarray(result.problem.omega), result.problem.model.d
    tmd, eq = out["tmd"], out["tmd_equal_travel"]
    data = {"tmd_travel": _dv("tmd_travel", W, result.tmd.travel(omega, d)),
            **{k: _dv(k, (), _nan(v)) for k, v in (
                ("tmd_worst_travel", tmd["worst_travel"]), ("tmd_stroke", tmd["stroke_m"]),
                ("vines_stroke", out["vines"]["stroke_m"]))}}
    if eq is not None:
        data["tmd_equal_travel_ratio"] = _dv("tmd_equal_travel_ratio", W,
                                             result.tmd_equal_travel.ratio(omega, d))
        data.update({f"tmd_equal_travel_{k}": _dv(f"tmd_equal_travel_{k}", (), _nan(eq[key]))
                     for k, key in (("frequency_ratio", "frequency_ratio"),
                                    ("damping_ratio", "damping_ratio"),
                                    ("worst_ratio", "worst_ratio"), ("stroke", "stroke_m"))})
    return data


def _rv(name, prefix, dims, data) -> xr.Variable:
    """A design_robust variable ``prefix + name``, attributes of ``name``."""
    long_name = DESIGN_ROBUST_ATTRS[name] + (" (robust designs)" if prefix else "")
    return xr.Variable(dims, np.asarray(data, dtype="f8"),
                       {"long_name": long_name, "units": DESIGN_ROBUST_UNITS.get(name, "1")})


def _mistuning_vars(block: dict, prefix: str, dim: str) -> dict:
    """One block of ``studies.mistuning.mistuning`` (nominal: prefix '', robust:
    'robust_'): the curves over its delta and the designs and worst cases as scalars."""
    out = {}
    for name in ("lo_alone", "tmd", "vines", "vines_any_attractor"):
        if block[name] is not None:
            out[prefix + name] = _rv(name, prefix, (dim,), block[name])
        out[f"{prefix}worst_{name}"] = _rv(f"worst_{name}", prefix, (),
                                           _nan(block["worst"][name]))
    des = block["design"]
    for name, value in (("tmd_frequency_ratio", des["tmd"]["frequency_ratio"]),
                        ("tmd_damping_ratio", des["tmd"]["damping_ratio"]),
                        ("vines_eta", des["vines"]["eta"]),
                        ("vines_clearance", des["vines"]["clearance_m"])):
        out[prefix + name] = _rv(name, prefix, (), value)
    return out


def design_robust_dataset(result, mistuning: dict, attrs: dict) -> xr.Dataset:
    """A design's worst cases over the host's drift (``studies.mistuning.mistuning``
    with robust=True): the nominal designs on ``delta``, the robust ones on
    ``robust_delta``; attributes: the structure, band, amplitudes, D, the TMD's mass
    ratio and how the host is detuned, over ``attrs`` (provenance)."""
    rob = mistuning["robust"]
    coords = {"delta": _rv("delta", "", ("delta",), mistuning["delta"]),
              "robust_delta": _rv("robust_delta", "", ("robust_delta",), rob["delta"])}
    data = _mistuning_vars(mistuning, "", "delta") | _mistuning_vars(rob, "robust_",
                                                                     "robust_delta")
    pb = result.problem
    own = {"Conventions": CONVENTIONS, "mistuning": mistuning["D"],
           "host": mistuning["host"], "tmd_eta": result.tmd.eta,
           "omega_band": list(pb.band), "n_omega": len(pb.omega),
           "amplitudes_m": list(pb.amplitudes_m), "d": pb.model.d, "r": pb.model.r,
           "M_kg": pb.M_kg, "k_N_per_m": pb.k_N_per_m, "census_n": pb.census_n,
           "robust_search_delta": rob["search"]["delta"],
           "t_end": pb.settings.t_end, "t_transient": pb.settings.t_transient}
    return xr.Dataset(data, coords=coords, attrs={**own, **attrs})


def _uv(name, dims, data, dtype="f8") -> xr.Variable:
    long_name, units = UNCERTAINTY_ATTRS[name]
    return xr.Variable(dims, np.asarray(data, dtype=dtype),
                       {"long_name": long_name, "units": units})


def _index_vars(key: str, sens: dict | None, names: list) -> dict:
    """The Sobol indices of one absorber over ``parameter`` (NaN when undefined)."""
    P = ("parameter",)
    rows = [sens[n] if sens else None for n in names]
    nan2 = [np.nan, np.nan]

    def col(field, empty=np.nan):
        return [empty if r is None else r[field] for r in rows]
    return {f"{key}_first_order": _uv(f"{key}_first_order", P, col("first_order")),
            f"{key}_total_order": _uv(f"{key}_total_order", P, col("total_order")),
            f"{key}_first_order_ci": _uv(f"{key}_first_order_ci", P + ("bound",),
                                         col("first_order_ci", nan2)),
            f"{key}_total_order_ci": _uv(f"{key}_total_order_ci", P + ("bound",),
                                         col("total_order_ci", nan2)),
            f"{key}_index_reliable": _uv(f"{key}_index_reliable", P, col("reliable", 0),
                                         "i1")}


def uncertainty_dataset(result, attrs: dict) -> xr.Dataset:
    """A design with uncertain parts (``studies.uncertainty.UncertaintyResult``): the
    parameter values, worst ratios and regimes at every point, the regime shares, the
    Sobol indices of both absorbers and their statistics. ``attrs`` (provenance) are merged
    over its own (distributions, sampler, notes)."""
    out = result.to_dict()
    names, k, n = result.names, len(result.names), result.n
    blocks = ["A"] * n + ["B"] * n + [f"AB_{x}" for x in names for _ in range(n)]
    X, P, G = ("point",), ("parameter",), ("regime_group",)
    shares = out["vines"]["regime_shares"]
    coords = {"parameter": _uv("parameter", P, names, "U"),
              "regime_group": _uv("regime_group", G, list(shares), "U"),
              "bound": _uv("bound", ("bound",), ["low", "high"], "U"),
              "block": _uv("block", X, blocks, "U")}
    data = {"value": _uv("value", P + X, result.points),
            "vines_worst_ratio": _uv("vines_worst_ratio", X, result.vines_worst),
            "vines_regime": _uv("vines_regime", X, result.vines_regime, "U"),
            "tmd_worst_ratio": _uv("tmd_worst_ratio", X, result.tmd_worst),
            "regime_share": _uv("regime_share", G, list(shares.values()))}
    for key in ("vines", "tmd"):
        data.update(_index_vars(key, out["sensitivity"][key], names))
        for stat in ("nominal", "mean", "q95"):
            data[f"{key}_{stat}"] = _uv(f"{key}_{stat}", (), out[key][stat])
    scalars = {"efficient_probability": out["vines"]["efficient_probability"],
               "vines_better_probability": out["vines_better_probability"],
               "vines_eta": out["design"]["eta"],
               "vines_clearance": out["design"]["clearance_m"],
               "tmd_eta": out["design"]["tmd_eta"]}
    data.update({name: _uv(name, (), v) for name, v in scalars.items()})
    dists = {f"distribution_{p['name']}": ":".join(
        str(p[x]) for x in ("distribution", *[y for y in p if y in ("lo", "hi", "mean", "sd")]))
        + f" ({p['kind']})" for p in out["parameters"]}
    own = {"Conventions": CONVENTIONS, "n_base": n, "n_parameters": k,
           "n_points": out["n_points"], "seed": out["seed"], "sampler": out["sampler"],
           "efficient_regime": "1:1", **dists,
           "sensitivity_notes": "; ".join(out["sensitivity_notes"]) or "none"}
    return xr.Dataset(data, coords=coords, attrs={**own, **attrs})


def atlas_dataset(eta, omega, families: dict, arrays: dict, attrs: dict) -> xr.Dataset:
    """An orbit atlas over (eta, omega): per family (``families``: key -> (walls, periods,
    paper label), in ``atlas.FAMILIES`` order) the found / admissible / stable flags and
    lambda_max (``arrays``: f"{key}:{field}" of shape (eta, omega))."""
    keys = list(families)
    shape = (np.size(eta), np.size(omega))
    D = ("family", "eta", "omega")
    data = {}
    for fld, (long_name, units) in ATLAS_ATTRS.items():
        stack = np.stack([np.asarray(arrays[f"{k}:{fld}"]) for k in keys])
        if stack.shape[1:] != shape:
            raise ValueError(f"atlas field {fld} has shape {stack.shape[1:]}, expected {shape}")
        extra = {} if fld == "lambda_max" else ATLAS_FLAGS
        dtype = "f8" if fld == "lambda_max" else "i1"
        data[fld] = xr.Variable(D, stack.astype(dtype),
                                {"long_name": long_name, "units": units, **extra})
    fam = ("family",)
    per_family = {"paper_label": [families[k][2] for k in keys],
                  "walls": [families[k][0] for k in keys],
                  "periods": np.array([families[k][1] for k in keys], dtype="i2")}
    for name, vals in per_family.items():
        data[name] = xr.Variable(fam, np.asarray(vals), cf(ATLAS_FAMILY_ATTRS, name))
    coords = {**_eta_omega_coords(eta, omega),
              "family": xr.Variable(fam, np.asarray(keys), cf(ATLAS_FAMILY_ATTRS, "family"))}
    own = {"Conventions": CONVENTIONS, "note": ATLAS_NOTE}
    return xr.Dataset(data, coords=coords, attrs={**own, **attrs})


def _sv(name, dims, data, dtype="f8") -> xr.Variable:
    return xr.Variable(dims, np.asarray(data, dtype=dtype), cf(SHOCK_ATTRS, name))


def _padded(values, n: int, fill) -> np.ndarray:
    """``values`` followed by ``fill`` up to length ``n`` (a run that stopped early)."""
    v = np.asarray(values, dtype=float)
    return np.concatenate([v, np.full(n - v.size, fill)])


def shock_dataset(curve: dict, histories: list, history_energies, time_periods,
                  attrs: dict) -> xr.Dataset:
    """A shock study: ``curve`` (``studies.shock.shock`` over an energy range) and
    ``histories`` (``shock`` at each of ``history_energies`` [J]) sampled at
    ``time_periods`` (natural periods of the LO). Times in s; a time not reached (None) is NaN. ``attrs`` (provenance) are
    merged over the study's own (design, structure, window)."""
    c, inp = curve["curve"], curve["inputs"]
    E = ("energy",)
    vin = c["vines"]
    data = {"velocity": _sv("velocity", E, c["velocity_m_s"]),
            **{f"vines_{k}": _sv(f"vines_{k}", E, [_nan(x) for x in vin[k]])
               for k in ("dissipated_fraction", "by_damping", "by_impacts", "t_10", "t_1",
                         "t_reached")},
            "vines_n_impacts": _sv("vines_n_impacts", E, vin["n_impacts"], "i4"),
            "vines_n_sticks": _sv("vines_n_sticks", E, curve["vines"]["n_sticks"], "i4"),
            "vines_status": xr.Variable(E, np.asarray(vin["status"], dtype=str),
                                        cf(SHOCK_ATTRS, "vines_status"))}
    tmd, lo = curve["tmd"], curve["lo_alone"]
    scalars = {"tmd_dissipated_fraction": tmd["dissipated_fraction"],
               "tmd_by_damping": tmd["by_damping"], "tmd_by_absorber": tmd["by_absorber"],
               "tmd_t_10": tmd["t_10"], "tmd_t_1": tmd["t_1"],
               "tmd_frequency_ratio": tmd["design"]["frequency_ratio"],
               "tmd_damping_ratio": tmd["design"]["damping_ratio"],
               "lo_alone_dissipated_fraction": lo["dissipated_fraction"],
               "lo_alone_t_10": lo["t_10"], "lo_alone_t_1": lo["t_1"],
               "activation_energy": curve["activation"]["energy_J"],
               "activation_velocity": curve["activation"]["velocity_m_s"],
               "optimal_energy": curve["optimal"]["energy_J"],
               "optimal_dissipated_fraction": curve["optimal"]["dissipated_fraction"]}
    data.update({k: _sv(k, (), _nan(v)) for k, v in scalars.items()})
    data.update(_shock_histories(histories, np.size(time_periods)))
    data.update(_shock_travel(curve))
    coords = {"energy": _sv("energy", E, c["energy_J"]),
              "history_energy": _sv("history_energy", ("history_energy",),
                                    history_energies),
              "time_periods": _sv("time_periods", ("time_periods",), time_periods)}
    own = {"Conventions": CONVENTIONS, "eta": inp["eta"], "clearance_m": inp["clearance_m"],
           "M_kg": inp["M_kg"], "k_N_per_m": inp["k_N_per_m"], "c_Ns_per_m": inp["c_Ns_per_m"],
           "d": inp["d"], "r": inp["r"], "periods": inp["periods"],
           "omega_band": np.asarray(inp["omega_band"], dtype="f8"),
           "natural_period_s": curve["scales"]["natural_period_s"]}
    return xr.Dataset(data, coords=coords, attrs={**own, **attrs})


def _shock_travel(curve: dict) -> dict:
    """The strokes and the other TMDs of a shock curve (linear: the stroke is the stroke
    per velocity times V0) and the VI NES's dissipated fraction over random ball starts
    (when the curve has them)."""
    E, V = ("energy",), np.asarray(curve["curve"]["velocity_m_s"], dtype=float)
    lo = curve["lo_alone"]
    out = {"vines_stroke": _sv("vines_stroke", (), curve["inputs"]["clearance_m"]),
           "lo_alone_x_max": _sv("lo_alone_x_max", E, lo["x_max_m"] / V.max() * V)}
    for name in ("tmd", "tmd_fastest", "tmd_equal_travel"):
        t = curve.get(name)
        if t is None:
            continue
        out[f"{name}_stroke"] = _sv(f"{name}_stroke", E, t["stroke_per_velocity_s"] * V)
        if name != "tmd":
            for key in ("dissipated_fraction", "t_1"):
                out[f"{name}_{key}"] = _sv(f"{name}_{key}", (), _nan(t[key]))
            for key in ("frequency_ratio", "damping_ratio"):
                out[f"{name}_{key}"] = _sv(f"{name}_{key}", (), t["design"][key])
        out[f"{name}_decay_rate"] = _sv(f"{name}_decay_rate", (),
                                        t["slowest_decay_rate_per_s"])
    st = curve.get("starts")
    if st:
        S, Q = ("start",), ("quantile",)
        out.update(
            ball_position=_sv("ball_position", S, st["ball_position"]),
            ball_velocity_fraction=_sv("ball_velocity_fraction", S,
                                       st["ball_velocity_fraction"]),
            vines_start_dissipated_fraction=_sv("vines_start_dissipated_fraction", E + S,
                                                st["dissipated_fraction"]),
            vines_start_quantile=_sv("vines_start_quantile", E + Q,
                                     st["dissipated_fraction_quantiles"]),
            quantile=_sv("quantile", Q, st["quantiles"]))
    return out


def _shock_histories(histories: list, n: int) -> dict:
    """The decays in time: the VI NES's per history energy (padded after a run that
    stopped), the linear systems' once (their fractions do not depend on E0)."""
    H, T = ("history_energy", "time_periods"), ("time_periods",)
    vin = [h["history"]["vines"] for h in histories]
    out = {"vines_remaining": _sv("vines_remaining", H, [_padded(v["remaining_fraction"], n,
                                                                  np.nan) for v in vin]),
           "vines_history_by_impacts": _sv("vines_history_by_impacts", H,
                                           [_padded(v["by_impacts"], n, np.nan) for v in vin]),
           "vines_history_n_impacts": _sv("vines_history_n_impacts", H,
                                          [_padded(v["n_impacts"], n, -1) for v in vin], "i4")}
    for name in ("tmd", "lo_alone"):
        out[f"{name}_remaining"] = _sv(f"{name}_remaining", T,
                                       histories[0]["history"][name]["remaining_fraction"])
    return out


def _mv(name, dims, data, dtype="f8") -> xr.Variable:
    extra = ATLAS_FLAGS if dtype == "i1" else {}
    return xr.Variable(dims, np.asarray(data, dtype=dtype), cf(MODEL_LADDER_ATTRS, name, **extra))


def _slots(groups, n_slots: int, fill) -> np.ndarray:
    """Rows grouped by an index as a (groups, n_slots) array padded with ``fill`` (float)."""
    out = np.full((len(groups), n_slots), float(fill))
    for i, g in enumerate(groups):
        out[i, :len(g)] = g
    return out


def _by_index(rows: dict, key: str, n: int) -> list:
    return [rows[key][rows["index"] == i] for i in range(n)]


def model_ladder_dataset(panels: list, sigma, sigma_dense, tolerances, bands: list,
                         attrs: dict) -> xr.Dataset:
    """A model ladder: one ``studies.model_ladder.Ladder`` per eta over the grid ``sigma``
    (the slow flow also over ``sigma_dense``); ``bands[k][j]`` = (lo, hi, share) of panel k
    at tolerance j. Rows of fixed points, orbits and branches are padded with NaN (0 for
    the stability flags); the times (``seconds``) are wall-clock measurements."""
    from ..studies.model_ladder import MODELS
    n, nd = np.size(sigma), np.size(sigma_dense)
    grouped = {}
    for key, src, m in (("slowflow", "slowflow", n), ("dense", "dense", nd),
                        ("exact", "exact", n)):
        grouped[key] = [(_by_index(getattr(p, src), "amplitude", m),
                         _by_index(getattr(p, src), "stable", m)) for p in panels]
    width = {k: max([1] + [len(a) for amp, _ in g for a in amp]) for k, g in grouped.items()}

    def stack(key, which, fill):
        return np.stack([_slots(g[which], width[key], fill) for g in grouped[key]])

    K, S, R = ("eta",), ("eta", "sigma"), ("eta", "sigma", "root")
    data = {"F": _mv("F", K, [p.F for p in panels]),
            "xi_min": _mv("xi_min", K, [p.xi_min for p in panels]),
            "omega": _mv("omega", S, [p.omega for p in panels]),
            "omega_dense": _mv("omega_dense", ("eta", "sigma_dense"),
                               [p.dense["grid"] for p in panels]),
            "slowflow_amplitude": _mv("slowflow_amplitude", R, stack("slowflow", 0, np.nan)),
            "slowflow_stable": _mv("slowflow_stable", R, stack("slowflow", 1, False), "i1"),
            "slowflow_error": _mv("slowflow_error", R, np.stack([_slots(
                _by_index({"index": p.slowflow["index"], "e": p.slowflow["nearest_error"]},
                          "e", n), width["slowflow"], np.nan) for p in panels])),
            "dense_amplitude": _mv("dense_amplitude", ("eta", "sigma_dense", "dense_root"),
                                   stack("dense", 0, np.nan)),
            "dense_stable": _mv("dense_stable", ("eta", "sigma_dense", "dense_root"),
                                stack("dense", 1, False), "i1"),
            "exact_amplitude": _mv("exact_amplitude", ("eta", "sigma", "orbit"),
                                   stack("exact", 0, np.nan)),
            "exact_stable": _mv("exact_stable", ("eta", "sigma", "orbit"),
                                stack("exact", 1, False), "i1"),
            "n_slowflow": _mv("n_slowflow", S, [np.bincount(p.slowflow["index"], minlength=n)
                                                for p in panels], "i4"),
            "n_exact": _mv("n_exact", S, [np.bincount(p.exact["index"], minlength=n)
                                          for p in panels], "i4"),
            "error_max": _mv("error_max", S, [p.error_max for p in panels]),
            "simulation_xmax": _mv("simulation_xmax", S,
                                   [p.simulation["xmax"] for p in panels]),
            "simulation_regime": xr.Variable(S, np.asarray([p.simulation["regime"]
                                                            for p in panels], dtype=str),
                                             cf(MODEL_LADDER_ATTRS, "simulation_regime")),
            "seconds": _mv("seconds", ("eta", "model"),
                           [[p.seconds[m] for m in MODELS] for p in panels])}
    data.update(_ladder_curves(panels))
    T = ("eta", "tolerance")
    for j, name in enumerate(("band_lo", "band_hi", "share_within")):
        data[name] = _mv(name, T, [[b[j] for b in bk] for bk in bands])
    coords = {"eta": _mv("eta", K, [p.eta for p in panels]),
              "sigma": _mv("sigma", ("sigma",), sigma),
              "sigma_dense": _mv("sigma_dense", ("sigma_dense",), sigma_dense),
              "tolerance": _mv("tolerance", ("tolerance",), tolerances),
              "model": xr.Variable(("model",), np.asarray(MODELS, dtype=str),
                                   cf(MODEL_LADDER_ATTRS, "model"))}
    return xr.Dataset(data, coords=coords, attrs={"Conventions": CONVENTIONS, **attrs})


def _ladder_curves(panels: list) -> dict:
    """The continued branches: (eta, curve, branch_point) padded with NaN / 0."""
    curves = []
    for p in panels:
        c = p.continuation
        k = int(c["curve"].max()) + 1 if c["curve"].size else 0
        curves.append([{f: c[f][c["curve"] == j] for f in ("omega", "amplitude", "stable")}
                       for j in range(k)])
    n_c = max([1] + [len(cs) for cs in curves])
    n_p = max([1] + [cv["omega"].size for cs in curves for cv in cs])
    out = {f: np.full((len(panels), n_c, n_p), np.nan) for f in ("omega", "amplitude")}
    out["stable"] = np.zeros((len(panels), n_c, n_p), dtype="i1")
    for i, cs in enumerate(curves):
        for j, cv in enumerate(cs):
            for f in out:
                out[f][i, j, :cv[f].size] = cv[f]
    D = ("eta", "curve", "branch_point")
    return {"continuation_omega": _mv("continuation_omega", D, out["omega"]),
            "continuation_amplitude": _mv("continuation_amplitude", D, out["amplitude"]),
            "continuation_stable": _mv("continuation_stable", D, out["stable"], "i1")}


# ------------------------------------------------------------------ design map

#: the design map's 0/1 variables (flag attributes)
_DESIGN_MAP_FLAGS = ("vines_in_domain", "verdict_differs", "verdict_differs_equal_travel")


def design_map_dataset(spec: dict, arrays: dict, summary: dict, attrs: dict) -> xr.Dataset:
    """A design map: ``arrays`` (``studies.design_map.assemble``) over (eta, half_width,
    span), the per-restitution worst ratios over (..., restitution); ``spec`` the map's
    inputs (``MapSpec.to_dict``) and ``summary`` its counts, as attributes."""
    dims = ("eta", "half_width", "span")
    data = {}
    for name, values in arrays.items():
        v = np.asarray(values)
        extra = (DESIGN_MAP_CONFIRM_FLAGS if name == "confirm" else
                 ATLAS_FLAGS if name in _DESIGN_MAP_FLAGS else {})
        d = dims + ("restitution",) if v.ndim == 4 else dims
        data[name] = xr.Variable(d, v, cf(DESIGN_MAP_ATTRS, name, **extra))
    coords = {k: xr.Variable((k,), np.asarray(spec[k], dtype="f8"), cf(DESIGN_MAP_ATTRS, k))
              for k in (*dims, "restitution")}
    own = {"Conventions": CONVENTIONS, "title": "who wins where: VI NES against TMD"}
    for k, v in spec.items():
        if k not in coords:
            own[k] = int(v) if isinstance(v, bool) else v
    own.update({(k if k.startswith("n_") else f"n_{k}"): v for k, v in summary.items()
                if isinstance(v, int)})
    own.update({k: (np.nan if v is None else v) for k, v in summary.items()
                if not isinstance(v, int)})
    return xr.Dataset(data, coords=coords, attrs={**own, **attrs})
