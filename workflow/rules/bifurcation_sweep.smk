# bifurcation-sweep: continuation sweeps (last state -> next initial condition), up and
# down in the swept parameter, for every outer value; impacts of the last n_record periods
# stored as a CF contiguous ragged array.


rule bifurcation_sweep:
    output:
        dataset("bifurcation_sweep"),
    log:
        job_log("bifurcation_sweep"),
    benchmark:
        job_benchmark("bifurcation_sweep")
    conda:
        "../../environment.yml"
    threads: job_threads
    resources:
        mem_mb=per_attempt(600),
        runtime=per_attempt(5),
    params:
        spec=lambda w: SWEEPS[w.name],
        model=MODEL,
        periodic_shortcut=SIMULATION["periodic_shortcut"],
        code=CODE,
        script=script_of("bifurcation_sweep.py"),
    script:
        "../scripts/bifurcation_sweep.py"
