# lyapunov: Lyapunov exponents along a bifurcation sweep (config lyapunov_sweeps; the same
# chain of states as the sweep, the spectrum of each point's run; drawn under Fig 3).


rule lyapunov:
    output:
        dataset("lyapunov"),
    log:
        job_log("lyapunov"),
    benchmark:
        job_benchmark("lyapunov")
    conda:
        "../../environment.yml"
    threads: config["threads"]
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
