# uncertainty: a design with uncertain parts (host frequency, clearance, mass, restitution):
# worst ratios of the VI NES and the TMD over Sobol samples, regimes and Sobol indices
# (vines.studies.uncertainty, docs/design.md).


rule uncertainty:
    output:
        dataset("uncertainty"),
    log:
        job_log("uncertainty"),
    benchmark:
        job_benchmark("uncertainty")
    conda:
        "../../environment.yml"
    threads: config["threads"]
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(13),
    params:
        spec=lambda w: UNCERTAINTY[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_DESIGN,
        script=script_of("uncertainty.py"),
    script:
        "../scripts/uncertainty.py"
