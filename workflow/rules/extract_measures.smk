# extract-measures: merge a grid's chunks into one dataset over (eta, omega, F) and add the
# derived fields (metres, stuck-linear reference amplitude, masks, section markers).


rule extract_measures:
    input:
        chunk_files,
    output:
        dataset("extract_measures"),
    log:
        job_log("extract_measures"),
    benchmark:
        job_benchmark("extract_measures")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(400),
        runtime=per_attempt(5),
    params:
        axes=lambda w: {d: v.tolist() for d, v in AXES[w.name].items()},
        sections=lambda w: GRIDS[w.name]["sections"],
        model=MODEL,
        code=CODE,
        script=script_of("extract_measures.py"),
    script:
        "../scripts/extract_measures.py"
