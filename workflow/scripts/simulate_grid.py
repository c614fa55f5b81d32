"""simulate-grid: exact measures at every point of one chunk (dask blocks), one NetCDF."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    p, wc = sm.params, sm.wildcards
    n = len(p.points["eta"]) * len(p.points["omega"]) * len(p.points["F"])
    print(f"chunk {wc.grid}/{wc.key}: {n} points, {sm.threads} threads, "
          f"scheduler {sm.config['dask_scheduler'] or 'threads'}", flush=True)
    ds = stages.simulate_grid(dict(p.points), model=dict(p.model),
                              simulation=dict(p.simulation), code=p.code,
                              title=f"vines grid {wc.grid}, chunk {wc.key}",
                              n_workers=sm.threads, block_size=sm.config["block_size"],
                              scheduler=sm.config["dask_scheduler"])
    write_dataset(ds, sm.output[0])
    print("done", flush=True)


run_job(sm, main)
