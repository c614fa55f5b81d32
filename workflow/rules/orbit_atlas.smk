# orbit-atlas: which periodic families (1:1, 2:2, 2:1, 3:2, 3:3, period-2) are admissible
# and stable over an eta-W grid at one F (vines.orbits.atlas, docs/bifurcation.md).


rule orbit_atlas:
    output:
        dataset("orbit_atlas"),
    log:
        job_log("orbit_atlas"),
    benchmark:
        job_benchmark("orbit_atlas")
    conda:
        "../../environment.yml"
    threads: config["threads"]
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(8),
    params:
        grid=lambda w: atlas_grid(config, w.name),
        sim_t_end=lambda w: ORBIT_ATLASES[w.name]["sim_t_end"],
        model=MODEL,
        code=CODE,
        script=script_of("orbit_atlas.py"),
    script:
        "../scripts/orbit_atlas.py"
