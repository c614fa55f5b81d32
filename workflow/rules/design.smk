# design: the VI NES (eta, L) for a band and base amplitudes against the LO alone and the
# optimal TMD of the same mass (vines.design, docs/design.md). The search grid's designs run
# in chunk jobs of about `chunks.design` runs (rule design_chunk); the gather does the
# compass search and the census from their responses and writes the dataset.


rule design_chunk:
    output:
        temp(part_file("design")),
    log:
        job_log("design_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("design_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        part=part_range("design"),
        args=[],
        spec=lambda w: DESIGNS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_DESIGN,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule design:
    input:
        part_files("design"),
    output:
        dataset("design"),
    log:
        job_log("design"),
    benchmark:
        job_benchmark("design")
    conda:
        "../../environment.yml"
    threads: job_threads
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
