"""extract-measures: merge the chunks of one grid and add derived fields."""
import _checkout  # noqa: F401  (this checkout's vines first)
import sys

from vines.data.netcdf import (derive_measures, grid_dataset, merge_chunks, provenance_attrs,
                      read_dataset, write_dataset)

sm = snakemake  # noqa: F821  (injected by Snakemake)
with open(sm.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    p = sm.params
    fields = merge_chunks((read_dataset(f) for f in sm.input), p.axes)
    first = read_dataset(sm.input[0])
    subset = {"axes": p.axes, "sections": p.sections, "model": p.model,
              "chunks_config_sha256": sorted(read_dataset(f).attrs["config_sha256"]
                                             for f in sm.input)}
    attrs = provenance_attrs(title=f"vines measures, grid {sm.wildcards.grid}",
                             config_subset=subset,
                             settings={k[len("solver_"):]: v for k, v in first.attrs.items()
                                       if k.startswith("solver_")},
                             code_version=p.code)
    ds = derive_measures(grid_dataset(p.axes, fields, attrs), r=p.model["r"], d=p.model["d"],
                         sections=dict(p.sections))
    write_dataset(ds, sm.output[0])
    print(f"merged {len(sm.input)} chunks", flush=True)
