# stability-map: abs(lambda_max) and class of the 1:1 orbit on eta-omega grids (Fig 16).


rule stability_map:
    output:
        f"{RES}/stability/{{smap}}.nc",
    log:
        f"{RES}/logs/stability_map/{{smap}}.log",
    benchmark:
        f"{RES}/benchmarks/stability_map/{{smap}}.tsv"
    conda:
        "../../environment.yml"
    threads: config["threads"]
    params:
        spec=lambda w: SMAPS[w.smap],
        model=MODEL,
        code=CODE,
    script:
        "../scripts/stability_map.py"
