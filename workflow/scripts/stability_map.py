"""stability-map: |lambda_max| and class of the 1:1 orbit over an eta-W grid (Fig 16)."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys

import numpy as np
import xarray as xr

from vines.data.netcdf import COORD_ATTRS, provenance_attrs, write_dataset
from vines.pipeline.stages import axis_values
from vines.orbits.stability_map import stability_map

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    spec, model = dict(sm.params.spec), dict(sm.params.model)
    eta, omega = axis_values(spec["eta"]), axis_values(spec["omega"])
    res = stability_map(eta, omega, float(spec["F"]), r=model["r"], d=model["d"],
                        n_threads=sm.threads)
    D = ("eta", "omega")
    for k in ("lambda_max", "cls", "dw_L", "symmetric"):
        if np.shape(res[k]) != (eta.size, omega.size):
            raise ValueError(f"stability_map returned {k} with shape {np.shape(res[k])}, "
                             f"expected (eta, omega) = {(eta.size, omega.size)}")
    data = {
        "lambda_max": (D, res["lambda_max"], {"long_name": "largest |eigenvalue| of the 1:1 orbit", "units": "1"}),
        "cls": (D, np.asarray(res["cls"], dtype="i1"), {
            "long_name": "class of the 1:1 orbit", "units": "1",
            "flag_values": np.array([0, 1, 2, 3], dtype="i1"),
            "flag_meanings": "no_admissible_1to1 symmetric_stable asymmetric_stable unstable"}),
        "dw_L": (D, res["dw_L"], {"long_name": "relative velocity just before the L impact", "units": "1"}),
        "symmetric": (D, np.asarray(res["symmetric"], dtype="i1"), {"long_name": "1 if symmetric", "units": "1"}),
    }
    attrs = provenance_attrs(title=f"vines stability map {sm.wildcards.smap}",
                             config_subset={"spec": spec, "model": model}, settings=model,
                             code_version=sm.params.code)
    attrs["F"] = float(spec["F"])
    ds = xr.Dataset({k: xr.Variable(d, np.asarray(a), at) for k, (d, a, at) in data.items()},
                    coords={"eta": xr.Variable(("eta",), eta, COORD_ATTRS["eta"]),
                            "omega": xr.Variable(("omega",), omega, COORD_ATTRS["omega"])},
                    attrs=attrs)
    write_dataset(ds, sm.output[0])
