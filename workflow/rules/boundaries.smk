# boundaries: curves of fold, flip, Neimark-Sacker, symmetry-breaking and grazing points of
# 1:1 orbits in the (eta, omega) plane at fixed F (edges of Fig 16's classes; Figs 12, 16).


def _boundaries_map(wildcards):
    """The stability map whose class changes seed the curves (config key stability_map)."""
    name = BOUNDARIES[wildcards.bnd].get("stability_map")
    return [f"{RES}/stability/{name}.nc"] if name else []


rule boundaries:
    input:
        stability=_boundaries_map,
    output:
        f"{RES}/boundaries/{{bnd}}.nc",
    params:
        spec=lambda w: BOUNDARIES[w.bnd],
        model=MODEL,
        code=CODE,
    conda:
        "../envs/vines.yaml"
    log:
        f"{RES}/logs/boundaries/{{bnd}}.log",
    benchmark:
        f"{RES}/benchmarks/boundaries/{{bnd}}.tsv"
    script:
        "../scripts/boundaries.py"
