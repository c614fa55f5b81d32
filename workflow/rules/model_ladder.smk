# model_ladder: the averaged slow flow beside the exact 1:1 orbits (map solve and
# continuation) and the simulation from rest, amplitude errors and costs
# (vines.studies.model_ladder, docs/performance.md).


rule model_ladder:
    output:
        dataset("model_ladder"),
    log:
        job_log("model_ladder"),
    benchmark:
        job_benchmark("model_ladder")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(500),
        runtime=per_attempt(5),
    params:
        spec=lambda w: MODEL_LADDERS[w.name],
        model=MODEL,
        code=CODE_MODELS,
        script=script_of("model_ladder.py"),
    script:
        "../scripts/model_ladder.py"
