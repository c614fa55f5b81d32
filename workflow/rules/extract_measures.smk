# extract-measures: merge a grid's chunks into one dataset over (eta, omega, F) and add the
# derived fields (metres, stuck-linear reference amplitude, masks, section markers).


rule extract_measures:
    input:
        chunk_files,
    output:
        f"{RES}/measures/{{grid}}.nc",
    log:
        f"{RES}/logs/extract_measures/{{grid}}.log",
    benchmark:
        f"{RES}/benchmarks/extract_measures/{{grid}}.tsv"
    conda:
        "../../environment.yml"
    params:
        axes=lambda w: {d: v.tolist() for d, v in AXES[w.grid].items()},
        sections=lambda w: GRIDS[w.grid]["sections"],
        model=MODEL,
        code=CODE,
    script:
        "../scripts/extract_measures.py"
