"""simulate-grid: exact measures at every point of one chunk (dask blocks), one NetCDF."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys

from vines.data.netcdf import grid_dataset, provenance_attrs, write_dataset
from vines.pipeline.stages import compute_chunk

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    p = sm.params
    n = len(p.points["eta"]) * len(p.points["omega"]) * len(p.points["F"])
    print(f"chunk {sm.wildcards.grid}/{sm.wildcards.key}: {n} points, {sm.threads} threads, "
          f"scheduler {sm.config['dask_scheduler'] or 'threads'}", flush=True)
    fields = compute_chunk(p.points, model=dict(p.model), simulation=dict(p.simulation),
                           n_workers=sm.threads, block_size=sm.config["block_size"],
                           scheduler=sm.config["dask_scheduler"], progress=True)
    subset = {"points": p.points, "model": p.model, "simulation": p.simulation}
    attrs = provenance_attrs(title=f"vines grid {sm.wildcards.grid}, chunk {sm.wildcards.key}",
                             config_subset=subset, settings={**p.model, **p.simulation},
                             code_version=p.code)
    write_dataset(grid_dataset(p.points, fields, attrs), sm.output[0])
    print("done", flush=True)
