# design_robust: a design's LO alone, TMD and VI NES on a host whose natural frequency
# drifts to (1 + delta) w0, and the designs optimised for that drift
# (vines.studies.mistuning, docs/design.md).


rule design_robust:
    output:
        dataset("design_robust"),
    log:
        job_log("design_robust"),
    benchmark:
        job_benchmark("design_robust")
    conda:
        "../../environment.yml"
    threads: config["threads"]
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
