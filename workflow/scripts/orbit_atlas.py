"""orbit-atlas: periodic families admissible and stable over an eta-W grid at one F."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.orbit_atlas(dict(sm.params.grid), sim_t_end=float(sm.params.sim_t_end),
                            model=dict(sm.params.model), code=sm.params.code,
                            title=f"vines orbit atlas {sm.wildcards.name}",
                            n_workers=sm.threads)
    write_dataset(ds, sm.output[0])


run_job(sm, main)
