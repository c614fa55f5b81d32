"""map-solve: continue the 1:1 fixed point of the impact map, with stability and events."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.map_solve(dict(sm.params.spec), model=dict(sm.params.model),
                          code=sm.params.code, title=f"vines 1:1 branch {sm.wildcards.name}")
    write_dataset(ds, sm.output[0])


run_job(sm, main)
