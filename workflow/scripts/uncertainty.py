"""uncertainty: the design of one ``uncertainty`` entry with uncertain parts, from the rows
of the entry's chunk parts."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import read_parts

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.uncertainty(dict(sm.params.spec), model=dict(sm.params.model),
                            simulation=dict(sm.params.simulation), code=sm.params.code,
                            title=f"vines uncertainty {sm.wildcards.name}",
                            n_workers=sm.threads, parts=read_parts(sm.input))
    write_dataset(ds, sm.output[0])


run_job(sm, main)
