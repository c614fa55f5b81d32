# stability-map: abs(lambda_max) and class of the 1:1 orbit on eta-omega grids (Fig 16).


rule stability_map:
    output:
        dataset("stability_map"),
    log:
        job_log("stability_map"),
    benchmark:
        job_benchmark("stability_map")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        spec=lambda w: STABILITY_MAPS[w.name],
        model=MODEL,
        code=CODE,
        script=script_of("stability_map.py"),
    script:
        "../scripts/stability_map.py"
