# bifurcation-sweep: continuation sweeps (last state -> next initial condition), up and
# down in the swept parameter, for every outer value; impacts of the last n_record periods
# stored as a CF contiguous ragged array.


rule bifurcation_sweep:
    output:
        f"{RES}/sweeps/{{sweep}}.nc",
    log:
        f"{RES}/logs/bifurcation_sweep/{{sweep}}.log",
    benchmark:
        f"{RES}/benchmarks/bifurcation_sweep/{{sweep}}.tsv"
    conda:
        "../../environment.yml"
    threads: config["threads"]
    params:
        spec=lambda w: SWEEPS[w.sweep],
        model=MODEL,
        periodic_shortcut=SIMULATION["periodic_shortcut"],
        code=CODE,
    script:
        "../scripts/bifurcation_sweep.py"
