"""bifurcation-sweep: continuation sweeps up and down, impacts as a CF ragged array."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.bifurcation_sweep(dict(sm.params.spec), model=dict(sm.params.model),
                                  periodic_shortcut=sm.params.periodic_shortcut,
                                  code=sm.params.code,
                                  title=f"vines bifurcation sweep {sm.wildcards.name}",
                                  n_workers=sm.threads, scheduler=sm.config["dask_scheduler"])
    write_dataset(ds, sm.output[0])
    print(f"{ds.sizes['point']} points, {ds.sizes['impact']} impacts", flush=True)


run_job(sm, main)
