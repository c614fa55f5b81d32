# map-solve: 1:1 branches of the impact map continued with stability and events (Figs 6, 15).


rule map_solve:
    output:
        f"{RES}/branches/{{branch}}.nc",
    log:
        f"{RES}/logs/map_solve/{{branch}}.log",
    benchmark:
        f"{RES}/benchmarks/map_solve/{{branch}}.tsv"
    conda:
        "../../environment.yml"
    params:
        spec=lambda w: BRANCHES[w.branch],
        model=MODEL,
        code=CODE,
    script:
        "../scripts/map_solve.py"
