# map-solve: 1:1 branches of the impact map with stability (Figs 6, 15);
# stability-map: abs(lambda_max) and class of the 1:1 orbit on eta-W grids (Fig 16).


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
    script:
        "../scripts/map_solve.py"


rule stability_map:
    output:
        f"{RES}/stability/{{smap}}.nc",
    params:
        spec=lambda w: SMAPS[w.smap],
        model=MODEL,
        code=CODE,
    threads: config["threads"]
    conda:
        "../envs/vines.yaml"
    log:
        f"{RES}/logs/stability_map/{{smap}}.log",
    script:
        "../scripts/stability_map.py"
