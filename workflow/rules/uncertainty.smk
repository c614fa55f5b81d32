# uncertainty: a design with uncertain parts (host frequency, clearance, mass, restitution):
# worst ratios of the VI NES and the TMD over Sobol samples, regimes and Sobol indices
# (vines.studies.uncertainty, docs/design.md). The sample points run in chunk jobs of about
# `chunks.uncertainty` runs from rest (rule uncertainty_chunk, whole points); the gather
# builds the design again and the statistics from their rows.


rule uncertainty_chunk:
    output:
        temp(part_file("uncertainty")),
    log:
        job_log("uncertainty_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("uncertainty_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        part=part_range("uncertainty"),
        args=[],
        spec=lambda w: UNCERTAINTY[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_DESIGN,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule uncertainty:
    input:
        part_files("uncertainty"),
    output:
        dataset("uncertainty"),
    log:
        job_log("uncertainty"),
    benchmark:
        job_benchmark("uncertainty")
    conda:
        "../../environment.yml"
    threads: job_threads
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
