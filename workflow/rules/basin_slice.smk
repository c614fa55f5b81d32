# basin-slice: the attractor reached from every point of a slice of initial states.


rule basin_slice:
    output:
        f"{RES}/basins/{{bslice}}.nc",
    params:
        spec=lambda w: SLICES[w.bslice],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_ATTRACTORS,
    threads: config["threads"]
    conda:
        "../envs/vines.yaml"
    log:
        f"{RES}/logs/basin_slice/{{bslice}}.log",
    benchmark:
        f"{RES}/benchmarks/basin_slice/{{bslice}}.tsv",
    script:
        "../scripts/basin_slice.py"
