# work-precision: error against cost of the exact and the RK solvers on the cases of
# `work_precision.cases` (one job per case), measured against the high-precision reference
# (vines.reference.hiprec). The job takes all cores so that no other job disturbs its timings.


rule work_precision:
    output:
        f"{RES}/workprecision/{{case}}.nc",
    params:
        case=lambda w: WPREC["cases"][w.case],
        settings=WPREC_SETTINGS,
        model=MODEL,
        v_stick=SIMULATION["v_stick"],
        code=CODE_STUDY,
    threads: workflow.cores
    conda:
        "../envs/vines.yaml"
    log:
        f"{RES}/logs/work_precision/{{case}}.log",
    script:
        "../scripts/work_precision.py"
