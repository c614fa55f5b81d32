# shock: free decay after an impulse, the VI NES (exact solver) against the equal-mass TMD
# and the LO alone (vines.studies.shock, docs/design.md).


rule shock:
    output:
        dataset("shock"),
    log:
        job_log("shock"),
    benchmark:
        job_benchmark("shock")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        spec=lambda w: SHOCKS[w.name],
        model=MODEL,
        code=CODE_STUDY,
        script=script_of("shock.py"),
    script:
        "../scripts/shock.py"
