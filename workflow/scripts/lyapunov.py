"""lyapunov: Lyapunov exponents along the points of one bifurcation sweep entry, gathered
from the entry's chunk parts."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import read_parts

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.lyapunov(dict(sm.params.spec), dict(sm.params.sweep),
                         model=dict(sm.params.model), code=sm.params.code,
                         periodic_shortcut=bool(sm.params.periodic_shortcut),
                         title=f"vines Lyapunov exponents along sweep {sm.wildcards.name}",
                         parts=read_parts(sm.input))
    write_dataset(ds, sm.output[0])
    print(f"gathered {len(sm.input)} chunks", flush=True)


run_job(sm, main)
