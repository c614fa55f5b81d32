"""stability-map: |lambda_max| and class of the 1:1 orbit over an eta-omega grid (Fig 16)."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.stability_map(dict(sm.params.spec), model=dict(sm.params.model),
                              code=sm.params.code,
                              title=f"vines stability map {sm.wildcards.name}",
                              n_workers=sm.threads)
    write_dataset(ds, sm.output[0])


run_job(sm, main)
