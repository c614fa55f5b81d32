"""robust-map: basin fractions of efficient motion and of the stable 1:1 orbit (eta, omega),
gathered from the map's chunk parts."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import read_parts

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.robust_map(dict(sm.params.spec), model=dict(sm.params.model),
                           simulation=dict(sm.params.simulation), code=sm.params.code,
                           title=f"vines robust-TET map {sm.wildcards.name}",
                           parts=read_parts(sm.input))
    write_dataset(ds, sm.output[0])
    print(f"gathered {len(sm.input)} chunks", flush=True)


run_job(sm, main)
