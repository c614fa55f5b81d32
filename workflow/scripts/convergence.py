"""convergence: one study of vines.studies.convergence (window, vstick or grid) from its config."""
import time

from vines.data.netcdf import write_dataset
from vines.data.provenance import provenance_attrs
from vines.data.studies import convergence_dataset
from vines.pipeline.jobs import run_job
from vines.studies.convergence import STUDIES

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    study = sm.wildcards.name
    spec, model = dict(sm.params.spec), dict(sm.params.model)
    simulation = dict(sm.params.simulation)
    t0 = time.perf_counter()
    result = STUDIES[study](**spec, **simulation, **model, n_threads=sm.threads)
    print(f"{study}: {time.perf_counter() - t0:.1f} s", flush=True)
    attrs = provenance_attrs(
        title=f"vines convergence {study}",
        config_subset={"spec": spec, "model": model, "simulation": simulation},
        settings={**model, **simulation}, code_version=sm.params.code)
    write_dataset(convergence_dataset(study, result, attrs), sm.output[0])


run_job(sm, main)
