# work-precision: error against cost of the exact and the RK solvers on the cases of
# `work_precision.cases` (one job per case), measured against the high-precision reference
# (vines.reference.hiprec). The job takes all cores so that no other job disturbs its timings:
# the N of `-c N` (`-c all`: every core of the machine). Commands without a core count
# (`--report`, `--lint`, `--profile profiles/slurm` before it set `cores:`) read no
# `workflow.cores` (it raises there) and give 1 thread; they never run the job locally, and on
# a cluster the profile's `set-threads` replaces this value. A callable: read per job, not
# while the workflow is parsed.


rule work_precision:
    output:
        dataset("work_precision"),
    log:
        job_log("work_precision"),
    benchmark:
        job_benchmark("work_precision")
    conda:
        "../../environment.yml"
    threads: lambda wildcards: workflow.resource_settings.cores or 1
    resources:
        mem_mb=per_attempt(700),
        runtime=per_attempt(5),
    params:
        case=lambda w: WORK_PRECISION["cases"][w.name],
        settings=WORK_PRECISION_SETTINGS,
        model=MODEL,
        v_stick=SIMULATION["v_stick"],
        code=CODE_STUDY,
        script=script_of("work_precision.py"),
    script:
        "../scripts/work_precision.py"
