"""boundaries: curves of codimension-one points of 1:1 orbits in (eta, omega) at fixed F."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.boundaries(dict(sm.params.spec), model=dict(sm.params.model),
                           code=sm.params.code, title=f"vines boundary curves {sm.wildcards.name}",
                           stability_path=sm.input.stability[0] if sm.input.stability else None)
    write_dataset(ds, sm.output[0])


run_job(sm, main)
