"""timehistory: single runs at the points of one figure, last periods densely sampled."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys

import numpy as np
import xarray as xr

from vines.data.netcdf import COORD_ATTRS, provenance_attrs, write_dataset
from vines.pipeline.stages import compute_timehistory

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    spec, model, simulation = dict(sm.params.spec), dict(sm.params.model), dict(sm.params.simulation)
    pts = [dict(p) for p in spec["points"]]
    r = compute_timehistory(pts, model=model, simulation=simulation,
                            n_periods=spec["n_periods"],
                            samples_per_period=spec["samples_per_period"])
    PS, P, I = ("point", "sample"), ("point",), ("impact",)
    v = {
        "eta": (P, [p["eta"] for p in pts], COORD_ATTRS["eta"]),
        "omega": (P, [p["omega"] for p in pts], COORD_ATTRS["omega"]),
        "F": (P, [p["F"] for p in pts], COORD_ATTRS["F"]),
        "t": (PS, r["t"], {"long_name": "time t = w0 t_dim", "units": "1"}),
        "z_m": (PS, r["z_m"], {"long_name": "LO displacement z_m (units of L)", "units": "1"}),
        "v_m": (PS, r["v_m"], {"long_name": "LO velocity z_m'", "units": "1"}),
        "z_b": (PS, r["z_b"], {"long_name": "ball displacement z_b (units of L)", "units": "1"}),
        "v_b": (PS, r["v_b"], {"long_name": "ball velocity z_b'", "units": "1"}),
        "ke_ratio": (P, r["ke_ratio"], {"long_name": "kinetic energy ratio K_b/(K_m+K_b)", "units": "1"}),
        "xmax": (P, r["xmax"], {"long_name": "max |z_m| over the window (dimensionless)", "units": "1"}),
        "regime": (P, r["regime"], {"long_name": "regime of the post-transient motion", "units": ""}),
        "status": (P, r["status"], {"long_name": "solver status", "units": ""}),
        "row_size": (P, r["row_size"], {"long_name": "number of impacts of each point",
                                        "units": "1", "sample_dimension": "impact"}),
        "impact_t": (I, r["impact_t"], {"long_name": "impact time", "units": "1"}),
        "impact_dw": (I, r["impact_dw"], {"long_name": "relative velocity w' just before impact", "units": "1"}),
        "impact_phase": (I, r["impact_phase"], {"long_name": "impact phase mod(W t + phi, 2 pi)", "units": "rad"}),
        "impact_wall": (I, r["impact_wall"], {"long_name": "wall hit (+1 L, -1 R)", "units": "1"}),
    }
    attrs = provenance_attrs(title=f"vines time histories {sm.wildcards.th}",
                             config_subset={"spec": spec, "model": model, "simulation": simulation},
                             settings={**model, **simulation}, code_version=sm.params.code)
    ds = xr.Dataset({k: xr.Variable(d, np.asarray(a), at) for k, (d, a, at) in v.items()},
                    attrs=attrs)
    write_dataset(ds, sm.output[0])
