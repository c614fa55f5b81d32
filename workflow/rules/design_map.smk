# design_map: who wins where, the best VI NES (slow flow: clearance and restitution
# optimised) against the TMD of the same mass, free and at equal travel, over mass ratio,
# band and amplitude span; the exact solver checks the cells near the frontier and a seeded
# sample (vines.studies.design_map, docs/design.md). The cells run in chunk jobs of about
# `chunks.design_map` cells (rule design_map_chunk, one process each); the gather writes
# the dataset.


rule design_map_chunk:
    output:
        temp(part_file("design_map")),
    log:
        job_log("design_map_chunk", "{name}/{k}"),
    benchmark:
        job_benchmark("design_map_chunk", "{name}/{k}")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(10),
    params:
        part=part_range("design_map"),
        args=[],
        spec=lambda w: DESIGN_MAPS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_MODELS,
        script=script_of("stage_part.py"),
    script:
        "../scripts/stage_part.py"


rule design_map:
    input:
        part_files("design_map"),
    output:
        dataset("design_map"),
    log:
        job_log("design_map"),
    benchmark:
        job_benchmark("design_map")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        spec=lambda w: DESIGN_MAPS[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_MODELS,
        script=script_of("design_map.py"),
    script:
        "../scripts/design_map.py"
