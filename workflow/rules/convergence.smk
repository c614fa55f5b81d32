# convergence: measures against run length and window, against v_stick, and a KE-ratio
# contour against grid resolution (vines.studies.convergence), one job per study of the
# `convergence` section; the setting under test is the `simulation` section.


rule convergence:
    output:
        f"{RES}/convergence/{{study}}.nc",
    log:
        f"{RES}/logs/convergence/{{study}}.log",
    benchmark:
        f"{RES}/benchmarks/convergence/{{study}}.tsv"
    wildcard_constraints:
        study="window|vstick|grid",
    conda:
        "../../environment.yml"
    threads: config["threads"]
    params:
        spec=lambda w: CONV[w.study],
        model=MODEL,
        simulation=SIMULATION,
        code=CODE_STUDY,
    script:
        "../scripts/convergence.py"
