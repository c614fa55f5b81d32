# Figures: one rule and one script per figure (workflow/scripts/figures/figNN.py), reading
# only datasets and writing results/<run>/figures/figNN.pdf and .png. A figure rule depends
# on its datasets and its script only (Snakemake tracks script changes), so restyling a
# figure reruns that figure and never a computation. Captions for `snakemake --report`
# are in workflow/report/figNN.rst. Inputs per figure and all_targets(): figure_targets.smk.
# `rule all` (in the top-level Snakefile: Snakemake ignores `default_target` set in an
# included file) requests all_targets(): every dataset and every figure.


include: "figure_targets.smk"


rule figures:
    input:
        all_figures(),


rule fig2:
    input:
        **FIG_INPUTS["fig2"],
    output:
        **fig_out("fig2"),
    log:
        f"{RES}/logs/figures/fig2.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig2.py"


rule fig3:
    input:
        **FIG_INPUTS["fig3"],
    output:
        **fig_out("fig3"),
    log:
        f"{RES}/logs/figures/fig3.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig3.py"


rule fig4:
    input:
        **FIG_INPUTS["fig4"],
    output:
        **fig_out("fig4"),
    log:
        f"{RES}/logs/figures/fig4.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig4.py"


rule fig5:
    input:
        **FIG_INPUTS["fig5"],
    output:
        **fig_out("fig5"),
    log:
        f"{RES}/logs/figures/fig5.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig5.py"


rule fig6:
    input:
        **FIG_INPUTS["fig6"],
    output:
        **fig_out("fig6"),
    log:
        f"{RES}/logs/figures/fig6.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig6.py"


rule fig7:
    input:
        **FIG_INPUTS["fig7"],
    output:
        **fig_out("fig7"),
    log:
        f"{RES}/logs/figures/fig7.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig7.py"


rule fig8:
    input:
        **FIG_INPUTS["fig8"],
    output:
        **fig_out("fig8"),
    log:
        f"{RES}/logs/figures/fig8.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig8.py"


rule fig9:
    input:
        **FIG_INPUTS["fig9"],
    output:
        **fig_out("fig9"),
    log:
        f"{RES}/logs/figures/fig9.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig9.py"


rule fig10:
    input:
        **FIG_INPUTS["fig10"],
    output:
        **fig_out("fig10"),
    log:
        f"{RES}/logs/figures/fig10.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig10.py"


rule fig11:
    input:
        **FIG_INPUTS["fig11"],
    output:
        **fig_out("fig11"),
    log:
        f"{RES}/logs/figures/fig11.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig11.py"


rule fig12:
    input:
        **FIG_INPUTS["fig12"],
    output:
        **fig_out("fig12"),
    log:
        f"{RES}/logs/figures/fig12.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig12.py"


rule fig13:
    input:
        **FIG_INPUTS["fig13"],
    output:
        **fig_out("fig13"),
    log:
        f"{RES}/logs/figures/fig13.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig13.py"


rule fig14:
    input:
        **FIG_INPUTS["fig14"],
    output:
        **fig_out("fig14"),
    log:
        f"{RES}/logs/figures/fig14.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig14.py"


rule fig15:
    input:
        **FIG_INPUTS["fig15"],
    output:
        **fig_out("fig15"),
    log:
        f"{RES}/logs/figures/fig15.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig15.py"


rule fig16:
    input:
        **FIG_INPUTS["fig16"],
    output:
        **fig_out("fig16"),
    log:
        f"{RES}/logs/figures/fig16.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/fig16.py"


rule fig_workprecision:
    input:
        **FIG_INPUTS["workprecision"],
    output:
        **fig_out("workprecision"),
    log:
        f"{RES}/logs/figures/workprecision.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/workprecision.py"


rule fig_convergence:
    input:
        **FIG_INPUTS["convergence"],
    output:
        **fig_out("convergence"),
    log:
        f"{RES}/logs/figures/convergence.log",
    conda:
        "../envs/vines.yaml"
    script:
        "../scripts/figures/convergence.py"
