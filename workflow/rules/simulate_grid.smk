# simulate-grid: one job per chunk (a sub-grid of at most chunk_size points), named by the
# sha256 of its parameter values: extending a grid reuses the chunks already computed.
# Only the chunk's own values and the settings are params, so editing another grid, or
# another part of this one, does not rerun it. No time series are stored.


rule simulate_grid:
    output:
        dataset("simulate_grid", "{grid}/chunk_{key}"),
    log:
        job_log("simulate_grid", "{grid}/{key}"),
    benchmark:
        job_benchmark("simulate_grid", "{grid}/{key}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        points=lambda w: CHUNKS[w.grid][w.key],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE,
        script=script_of("simulate_grid.py"),
    script:
        "../scripts/simulate_grid.py"
