"""extract-measures: merge the chunks of one grid and add derived fields."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    p = sm.params
    ds = stages.extract_measures(list(sm.input), axes=p.axes, sections=dict(p.sections),
                                 model=dict(p.model), code=p.code,
                                 title=f"vines measures, grid {sm.wildcards.name}")
    write_dataset(ds, sm.output[0])
    print(f"merged {len(sm.input)} chunks", flush=True)


run_job(sm, main)
