# basin-slice: the attractor reached from every point of a slice of initial states.


rule basin_slice:
    output:
        f"{RES}/basins/{{bslice}}.nc",
    log:
        f"{RES}/logs/basin_slice/{{bslice}}.log",
    benchmark:
        f"{RES}/benchmarks/basin_slice/{{bslice}}.tsv"
    conda:
        "../../environment.yml"
    threads: config["threads"]
    params:
        spec=lambda w: SLICES[w.bslice],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
    script:
        "../scripts/basin_slice.py"
