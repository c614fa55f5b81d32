# boundaries: curves of fold, flip, Neimark-Sacker, symmetry-breaking and grazing points of
# 1:1 orbits in the (eta, omega) plane at fixed F (edges of Fig 16's classes; Figs 12, 16).


rule boundaries:
    input:
        stability=boundaries_seed_map,
    output:
        dataset("boundaries"),
    log:
        job_log("boundaries"),
    benchmark:
        job_benchmark("boundaries")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: BOUNDARIES[w.name],
        model=MODEL,
        code=CODE,
        script=script_of("boundaries.py"),
    script:
        "../scripts/boundaries.py"
