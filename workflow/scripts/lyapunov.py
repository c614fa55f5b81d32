"""lyapunov: Lyapunov exponents along the points of one bifurcation sweep entry."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.lyapunov(dict(sm.params.spec), dict(sm.params.sweep),
                         model=dict(sm.params.model), code=sm.params.code,
                         periodic_shortcut=bool(sm.params.periodic_shortcut),
                         title=f"vines Lyapunov exponents along sweep {sm.wildcards.name}",
                         n_workers=sm.threads, scheduler=sm.config["dask_scheduler"])
    write_dataset(ds, sm.output[0])


run_job(sm, main)
