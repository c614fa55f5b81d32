# convergence: measures against run length and window, against v_stick, and a KE-ratio
# contour against grid resolution (vines.studies.convergence), one dataset per study of the
# `convergence` section; the setting under test is the `simulation` section. The grid
# study's finest grid runs in chunk jobs of about `chunks.convergence` points (whole rows;
# rule convergence_chunk); window and vstick run in their gather job alone.


rule convergence_chunk:
    output:
        temp(part_file("convergence")),
    log:
        job_log("convergence_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("convergence_chunk", "{name}/{k}")
    wildcard_constraints:
        name="grid",
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        part=part_range("convergence"),
        args=lambda w: [w.name],
        spec=lambda w: CONVERGENCE[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_STUDY,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule convergence:
    input:
        part_files("convergence"),
    output:
        dataset("convergence"),
    log:
        job_log("convergence"),
    benchmark:
        job_benchmark("convergence")
    wildcard_constraints:
        name="window|vstick|grid",
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: CONVERGENCE[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_STUDY,
        script=script_of("convergence.py"),
    script:
        "../scripts/convergence.py"
