"""robust-map: basin fractions of efficient motion and of the stable 1:1 orbit (eta, omega)."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.robust_map(dict(sm.params.spec), model=dict(sm.params.model),
                           simulation=dict(sm.params.simulation), code=sm.params.code,
                           title=f"vines robust-TET map {sm.wildcards.name}",
                           n_workers=sm.threads, scheduler=sm.config["dask_scheduler"])
    write_dataset(ds, sm.output[0])


run_job(sm, main)
