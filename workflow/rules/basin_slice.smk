# basin-slice: the attractor reached from every point of a slice of initial states. The
# states run in chunk jobs of `chunks.basin_slice` states (rule basin_slice_chunk); the
# gather groups their end states into attractors (the census) and writes the dataset.


rule basin_slice_chunk:
    output:
        temp(part_file("basin_slice")),
    log:
        job_log("basin_slice_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("basin_slice_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        part=part_range("basin_slice"),
        args=[],
        spec=lambda w: BASIN_SLICES[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule basin_slice:
    input:
        part_files("basin_slice"),
    output:
        dataset("basin_slice"),
    log:
        job_log("basin_slice"),
    benchmark:
        job_benchmark("basin_slice")
    conda:
        "../../environment.yml"
    threads: job_threads
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
