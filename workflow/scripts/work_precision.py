"""work-precision: error and cost of every solver setting on one case (Fig workprecision)."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.work_precision(dict(sm.params.case), settings=dict(sm.params.settings),
                               model=dict(sm.params.model), v_stick=sm.params.v_stick,
                               code=sm.params.code,
                               title=f"vines work-precision {sm.wildcards.name}",
                               progress=lambda line: print(line, flush=True))
    write_dataset(ds, sm.output[0])


run_job(sm, main)
