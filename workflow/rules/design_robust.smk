# design_robust: a design's LO alone, TMD and VI NES on a host whose natural frequency
# drifts to (1 + delta) w0, and the designs optimised for that drift
# (vines.studies.mistuning, docs/design.md). The search grid's designs on the nominal host
# and on each host of the robust search run in chunk jobs of about `chunks.design_robust`
# runs from rest (rule design_robust_chunk, whole designs); the gather does the compass
# searches, the censuses and the curves over delta from their responses.


rule design_robust_chunk:
    output:
        temp(part_file("design_robust")),
    log:
        job_log("design_robust_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("design_robust_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        part=part_range("design_robust"),
        args=[],
        spec=lambda w: DESIGN_ROBUST[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_DESIGN,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule design_robust:
    input:
        part_files("design_robust"),
    output:
        dataset("design_robust"),
    log:
        job_log("design_robust"),
    benchmark:
        job_benchmark("design_robust")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(15),
    params:
        spec=lambda w: DESIGN_ROBUST[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_DESIGN,
        script=script_of("design_robust.py"),
    script:
        "../scripts/design_robust.py"
