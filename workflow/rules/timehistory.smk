# timehistory: single runs at the points a figure shows (Figs 4, 5, 9, 10, 11c-e); only the
# last periods are stored, densely sampled from the exact trajectory, with their impacts.


rule timehistory:
    output:
        f"{RES}/timehistories/{{th}}.nc",
    log:
        f"{RES}/logs/timehistory/{{th}}.log",
    benchmark:
        f"{RES}/benchmarks/timehistory/{{th}}.tsv"
    conda:
        "../../environment.yml"
    params:
        spec=lambda w: THIST[w.th],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE,
    script:
        "../scripts/timehistory.py"
