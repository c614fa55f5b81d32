# robust-map: basin fractions of efficient motion and of the stable 1:1 orbit over eta-omega
# grids (an attractor census per point; beside Fig 12).


rule robust_map:
    output:
        f"{RES}/robust/{{rmap}}.nc",
    log:
        f"{RES}/logs/robust_map/{{rmap}}.log",
    benchmark:
        f"{RES}/benchmarks/robust_map/{{rmap}}.tsv"
    conda:
        "../../environment.yml"
    threads: config["threads"]
    params:
        spec=lambda w: ROBUST[w.rmap],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
    script:
        "../scripts/robust_map.py"
