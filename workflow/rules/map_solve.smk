# map-solve: 1:1 branches of the impact map continued with stability and events (Figs 6, 15).


rule map_solve:
    output:
        dataset("map_solve"),
    log:
        job_log("map_solve"),
    benchmark:
        job_benchmark("map_solve")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: BRANCHES[w.name],
        model=MODEL,
        code=CODE,
        script=script_of("map_solve.py"),
    script:
        "../scripts/map_solve.py"
