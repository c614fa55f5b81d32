"""shock: the free decay of one ``shocks`` entry, VI NES against the TMD and the LO alone."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.shock(dict(sm.params.spec), model=dict(sm.params.model), code=sm.params.code,
                      title=f"vines shock {sm.wildcards.name}")
    write_dataset(ds, sm.output[0])


run_job(sm, main)
