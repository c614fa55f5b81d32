# design: the VI NES (eta, L) for a band and base amplitudes against the LO alone and the
# optimal TMD of the same mass (vines.design, docs/design.md).


rule design:
    output:
        dataset("design"),
    log:
        job_log("design"),
    benchmark:
        job_benchmark("design")
    conda:
        "../../environment.yml"
    threads: config["threads"]
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        spec=lambda w: DESIGNS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_DESIGN,
        script=script_of("design.py"),
    script:
        "../scripts/design.py"
