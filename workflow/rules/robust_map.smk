# robust-map: basin fractions of efficient motion and of the stable 1:1 orbit over eta-omega
# grids (an attractor census per point; beside Fig 12). The points are computed in chunk jobs
# of `chunks.robust_map` points (rule robust_map_chunk), gathered into the map's dataset.


rule robust_map_chunk:
    output:
        temp(part_file("robust_map")),
    log:
        job_log("robust_map_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("robust_map_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(800),
        runtime=per_attempt(10),
    params:
        part=part_range("robust_map"),
        args=[],
        spec=lambda w: ROBUST_MAPS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        scheduler=config["dask_scheduler"],
        code=CODE_ATTRACTORS,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule robust_map:
    input:
        part_files("robust_map"),
    output:
        dataset("robust_map"),
    log:
        job_log("robust_map"),
    benchmark:
        job_benchmark("robust_map")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(800),
        runtime=per_attempt(5),
    params:
        spec=lambda w: ROBUST_MAPS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
        script=script_of("robust_map.py"),
    script:
        "../scripts/robust_map.py"
