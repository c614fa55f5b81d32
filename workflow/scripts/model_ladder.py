"""model_ladder: one ``model_ladders`` entry, the slow flow beside the exact models."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.model_ladder(dict(sm.params.spec), model=dict(sm.params.model),
                             code=sm.params.code, title=f"vines model ladder {sm.wildcards.name}")
    write_dataset(ds, sm.output[0])


run_job(sm, main)
