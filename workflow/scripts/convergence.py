"""convergence: one study of vines.studies.convergence (window, vstick or grid) from its config."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys
import time

from vines.studies import convergence as C
from vines.data.netcdf import provenance_attrs, write_dataset

STUDIES = {"window": C.window_convergence, "vstick": C.vstick_convergence,
           "grid": C.grid_convergence}

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    study = sm.wildcards.study
    spec, model, simulation = dict(sm.params.spec), dict(sm.params.model), dict(sm.params.simulation)
    t0 = time.perf_counter()
    ds = STUDIES[study](**spec, **simulation, **model, n_threads=sm.threads)
    print(f"{study}: {time.perf_counter() - t0:.1f} s", flush=True)
    ds.attrs.update(provenance_attrs(
        title=f"vines convergence {study}",
        config_subset={"spec": spec, "model": model, "simulation": simulation},
        settings={**model, **simulation}, code_version=sm.params.code))
    write_dataset(ds, sm.output[0])
