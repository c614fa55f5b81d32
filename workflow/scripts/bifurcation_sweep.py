"""bifurcation-sweep: continuation sweeps up and down, impacts as a CF ragged array."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys

from vines.data.netcdf import COORD_ATTRS, provenance_attrs, ragged_dataset, write_dataset
from vines.pipeline.stages import compute_sweep

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    spec, model = dict(sm.params.spec), dict(sm.params.model)
    r = compute_sweep(spec, model=model, n_workers=sm.threads,
                      scheduler=sm.config["dask_scheduler"], progress=True)
    par, out = spec["param"], spec["outer"]
    inst = {
        "value": (r["value"], f"swept parameter {par}: " + COORD_ATTRS[par]["long_name"], "1"),
        "outer_value": (r["outer_value"], f"outer parameter {out}: "
                        + COORD_ATTRS[out]["long_name"], "1"),
        "direction": (r["direction"], "sweep direction (+1 up, -1 down)", "1"),
        "line": (r["line"], "index of the sweep line (outer value, direction)", "1"),
        "phi": (r["phi"], "forcing phase at the start of the point", "rad"),
        "status": (r["status"], "solver status of the point", ""),
    }
    samples = {
        "dw": (r["dw"], "relative velocity w' = z_m' - z_b' just before impact", "1"),
        "phase": (r["phase"], "impact phase mod(W t + phi, 2 pi)", "rad"),
        "wall": (r["wall"], "wall hit (+1 left end L, -1 right end R)", "1"),
    }
    attrs = provenance_attrs(title=f"vines bifurcation sweep {sm.wildcards.sweep}",
                             config_subset={"spec": spec, "model": model},
                             settings={**model, **{k: spec[k] for k in
                                                   ("t_settle", "t_step", "n_record", "v_stick")}},
                             code_version=sm.params.code)
    attrs.update(swept_parameter=par, outer_parameter=out,
                 fixed=", ".join(f"{k}={v!r}" for k, v in sorted(spec["fixed"].items())))
    ds = ragged_dataset(inst, samples, r["row_size"], instance_dim="point",
                        sample_dim="impact", attrs=attrs)
    write_dataset(ds, sm.output[0])
    print(f"{ds.sizes['point']} points, {ds.sizes['impact']} impacts", flush=True)
