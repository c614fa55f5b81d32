"""design_map: the map of one ``design_maps`` entry (who wins where: VI NES against TMD),
gathered from the cells of the entry's chunk parts."""
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import read_parts

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    ds = stages.design_map(dict(sm.params.spec), model=dict(sm.params.model),
                           simulation=dict(sm.params.simulation), code=sm.params.code,
                           title=f"vines design map {sm.wildcards.name}",
                           parts=read_parts(sm.input))
    write_dataset(ds, sm.output[0])


run_job(sm, main)
