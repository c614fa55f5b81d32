"""convergence: one study of vines.studies.convergence (window, vstick or grid) from its config
(the grid study from the runs of its chunk parts)."""
import time

from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import read_parts

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    study = sm.wildcards.name
    t0 = time.perf_counter()
    ds = stages.convergence(study, dict(sm.params.spec), model=dict(sm.params.model),
                            simulation=dict(sm.params.simulation), code=sm.params.code,
                            title=f"vines convergence {study}", n_workers=sm.threads,
                            parts=read_parts(sm.input))
    print(f"{study}: {time.perf_counter() - t0:.1f} s", flush=True)
    write_dataset(ds, sm.output[0])


run_job(sm, main)
