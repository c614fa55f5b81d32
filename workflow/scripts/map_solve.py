"""map-solve: continue the 1:1 fixed point of the impact map, with stability and events."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys

import numpy as np
import xarray as xr

from vines.orbits.continuation import continue_branch
from vines.data.netcdf import COORD_ATTRS, provenance_attrs, write_dataset

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    spec, model = dict(sm.params.spec), dict(sm.params.model)
    fixed = {k: float(v) for k, v in spec["fixed"].items()}
    br = continue_branch(spec["param"], spec["start"], spec["stop"], spec["step"], fixed,
                         r=model["r"], d=model["d"])
    par = spec["param"]
    D = ("point",)
    data = {
        "eta": (D, br.eta, COORD_ATTRS["eta"]),
        "omega": (D, br.omega, COORD_ATTRS["omega"]),
        "F": (D, br.F, COORD_ATTRS["F"]),
        "lambda_max": (D, br.lambda_max, {"long_name": "largest |eigenvalue| of the 1:1 map", "units": "1"}),
        "abs_eigenvalues": (("point", "eig"), np.asarray(br.abs_eigenvalues).reshape(-1, 4),
                            {"long_name": "|eigenvalues| of J_P2 J_P1, decreasing", "units": "1"}),
        "stable": (D, np.asarray(br.stable, dtype="i1"), {"long_name": "1 if all |lambda| < 1", "units": "1"}),
        "symmetric": (D, np.asarray(br.symmetric, dtype="i1"), {"long_name": "1 if symmetric 1:1 orbit", "units": "1"}),
        "admissible": (D, np.asarray(br.admissible, dtype="i1"), {"long_name": "1 if admissible (no earlier contact)", "units": "1"}),
        "dw_L": (D, br.dw_L, {"long_name": "relative velocity just before the L impact", "units": "1"}),
        "dw_R": (D, br.dw_R, {"long_name": "relative velocity just before the R impact", "units": "1"}),
        "phase_L": (D, br.phase_L, {"long_name": "phase of the L impact", "units": "rad"}),
        "phase_R": (D, br.phase_R, {"long_name": "phase of the R impact", "units": "rad"}),
    }
    etype = [e["type"] for e in br.events]
    eat = [float(e["at"]) for e in br.events]
    data["event_type"] = (("event",), np.asarray(etype, dtype="U32"),
                          {"long_name": "bifurcation / admissibility event type", "units": ""})
    data["event_at"] = (("event",), np.asarray(eat, dtype=float),
                        {"long_name": f"{par} value of the event", "units": "1"})
    attrs = provenance_attrs(title=f"vines 1:1 branch {sm.wildcards.branch}",
                             config_subset={"spec": spec, "model": model}, settings=model,
                             code_version=sm.params.code)
    attrs.update(continued_parameter=par, stopped=str(br.stopped))
    ds = xr.Dataset({k: xr.Variable(d, np.asarray(a), at) for k, (d, a, at) in data.items()},
                    attrs=attrs)
    write_dataset(ds, sm.output[0])
