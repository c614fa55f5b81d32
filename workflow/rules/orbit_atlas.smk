# orbit-atlas: which periodic families (1:1, 2:2, 2:1, 3:2, 3:3, period-2) are admissible
# and stable over an eta-W grid at one F (vines.orbits.atlas.atlas, docs/bifurcation.md). Whole
# eta rows (each swept in W) in chunk jobs of about `chunks.orbit_atlas` points (rule
# orbit_atlas_chunk), gathered into the atlas's dataset.


rule orbit_atlas_chunk:
    output:
        temp(part_file("orbit_atlas")),
    log:
        job_log("orbit_atlas_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("orbit_atlas_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        part=part_range("orbit_atlas"),
        args=[],
        grid=lambda w: atlas_grid(config, w.name),
        sim_t_end=lambda w: float(ORBIT_ATLASES[w.name]["sim_t_end"]),
        model=MODEL,
        scheduler=config["dask_scheduler"],
        code=CODE,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule orbit_atlas:
    input:
        part_files("orbit_atlas"),
    output:
        dataset("orbit_atlas"),
    log:
        job_log("orbit_atlas"),
    benchmark:
        job_benchmark("orbit_atlas")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        grid=lambda w: atlas_grid(config, w.name),
        sim_t_end=lambda w: ORBIT_ATLASES[w.name]["sim_t_end"],
        model=MODEL,
        code=CODE,
        script=script_of("orbit_atlas.py"),
    script:
        "../scripts/orbit_atlas.py"
