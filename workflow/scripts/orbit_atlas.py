"""orbit-atlas: periodic families admissible and stable over an eta-W grid at one F,
gathered from the atlas's chunk parts."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import read_parts

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.orbit_atlas(dict(sm.params.grid), sim_t_end=float(sm.params.sim_t_end),
                            model=dict(sm.params.model), code=sm.params.code,
                            title=f"vines orbit atlas {sm.wildcards.name}",
                            parts=read_parts(sm.input))
    write_dataset(ds, sm.output[0])
    print(f"gathered {len(sm.input)} chunks", flush=True)


run_job(sm, main)
