# timehistory: single runs at the points a figure shows (Figs 4, 5, 9, 10, 11c-e); only the
# last periods are stored, densely sampled from the exact trajectory, with their impacts.


rule timehistory:
    output:
        dataset("timehistory"),
    log:
        job_log("timehistory"),
    benchmark:
        job_benchmark("timehistory")
    conda:
        "../../environment.yml"
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: TIMEHISTORIES[w.name],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE,
        script=script_of("timehistory.py"),
    script:
        "../scripts/timehistory.py"
