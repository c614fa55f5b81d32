# map-solve: 1:1 branches of the impact map continued with stability and events (Figs 6, 15).


rule map_solve:
    output:
        f"{RES}/branches/{{branch}}.nc",
    params:
        spec=lambda w: BRANCHES[w.branch],
        model=MODEL,
        code=CODE,
    conda:
        "../envs/vines.yaml"
    log:
        f"{RES}/logs/map_solve/{{branch}}.log",
    benchmark:
        f"{RES}/benchmarks/map_solve/{{branch}}.tsv",
    script:
        "../scripts/map_solve.py"
