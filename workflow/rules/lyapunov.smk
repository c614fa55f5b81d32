# lyapunov: Lyapunov exponents along a bifurcation sweep (config lyapunov_sweeps; the same
# chain of states as the sweep, the spectrum of each point's run; drawn under Fig 3). Whole
# sweep lines in chunk jobs of about `chunks.lyapunov` points (rule lyapunov_chunk),
# gathered into the entry's dataset.


rule lyapunov_chunk:
    output:
        temp(part_file("lyapunov")),
    log:
        job_log("lyapunov_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("lyapunov_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        part=part_range("lyapunov"),
        args=lambda w: [
            LYAPUNOV_SWEEPS[w.name],
            SWEEPS[LYAPUNOV_SWEEPS[w.name]["sweep"]],
        ],
        model=MODEL,
        periodic_shortcut=SIMULATION["periodic_shortcut"],
        scheduler=config["dask_scheduler"],
        code=CODE_ATTRACTORS,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule lyapunov:
    input:
        part_files("lyapunov"),
    output:
        dataset("lyapunov"),
    log:
        job_log("lyapunov"),
    benchmark:
        job_benchmark("lyapunov")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: LYAPUNOV_SWEEPS[w.name],
        sweep=lambda w: SWEEPS[LYAPUNOV_SWEEPS[w.name]["sweep"]],
        model=MODEL,
        periodic_shortcut=SIMULATION["periodic_shortcut"],
        code=CODE_ATTRACTORS,
        script=script_of("lyapunov.py"),
    script:
        "../scripts/lyapunov.py"
