# stability-map: abs(lambda_max) and class of the 1:1 orbit on eta-omega grids (Fig 16).


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
    benchmark:
        f"{RES}/benchmarks/stability_map/{{smap}}.tsv",
    script:
        "../scripts/stability_map.py"
