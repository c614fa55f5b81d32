# robust-map: basin fractions of efficient motion and of the stable 1:1 orbit over eta-omega
# grids (an attractor census per point; beside Fig 12).


rule robust_map:
    output:
        dataset("robust_map"),
    log:
        job_log("robust_map"),
    benchmark:
        job_benchmark("robust_map")
    conda:
        "../../environment.yml"
    threads: config["threads"]
    resources:
        mem_mb=per_attempt(800),
        runtime=per_attempt(31),
    params:
        spec=lambda w: ROBUST_MAPS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
        script=script_of("robust_map.py"),
    script:
        "../scripts/robust_map.py"
