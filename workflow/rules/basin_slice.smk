# basin-slice: the attractor reached from every point of a slice of initial states.


rule basin_slice:
    output:
        dataset("basin_slice"),
    log:
        job_log("basin_slice"),
    benchmark:
        job_benchmark("basin_slice")
    conda:
        "../../environment.yml"
    threads: config["threads"]
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: BASIN_SLICES[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
        script=script_of("basin_slice.py"),
    script:
        "../scripts/basin_slice.py"
