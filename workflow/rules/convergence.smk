# convergence: measures against run length and window, against v_stick, and a KE-ratio
# contour against grid resolution (vines.studies.convergence), one job per study of the
# `convergence` section; the setting under test is the `simulation` section.


rule convergence:
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
    threads: config["threads"]
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
