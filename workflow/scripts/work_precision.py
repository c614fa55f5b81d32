"""work-precision: error and cost of every solver setting on one case.

See vines.studies.workprecision (numbers) and vines.data.studies (dataset).
"""
from vines.data.netcdf import write_dataset
from vines.data.provenance import provenance_attrs
from vines.data.studies import work_precision_dataset
from vines.pipeline.jobs import run_job
from vines.studies.workprecision import work_precision

sm = snakemake  # noqa: F821  (injected by Snakemake)


def main():
    case, settings, model = dict(sm.params.case), dict(sm.params.settings), dict(sm.params.model)
    result = work_precision(case["eta"], case["omega"], case["F"], t_end=case["t_end"],
                            t_transient=case["t_transient"], r=model["r"], d=model["d"],
                            v_stick=sm.params.v_stick, v_sticks=case.get("v_sticks", []),
                            root_tols=settings["root_tols"], rk_methods=settings["rk_methods"],
                            rtols=settings["rtols"], dps=settings["dps"],
                            h_sample=settings["h_sample"], v_visible=settings["v_visible"],
                            min_time=settings["min_time"],
                            progress=lambda line: print(line, flush=True))
    attrs = provenance_attrs(
        title=f"vines work-precision {sm.wildcards.name}",
        config_subset={"case": case, "settings": settings, "model": model,
                       "v_stick": sm.params.v_stick},
        settings=model, code_version=sm.params.code)
    write_dataset(work_precision_dataset(result, attrs), sm.output[0])


run_job(sm, main)
