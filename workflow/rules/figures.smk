# Figures: one rule per figure, generated below, each reading only datasets and writing
# results/<run>/figures/<fig>.pdf and .png. A figure rule depends on its datasets, its
# script (Snakemake tracks script changes) and the code version of vines.plotting only, so
# restyling a figure reruns figures and never a computation. Figs 4, 5, 9, 10 share one
# script (timehistory.py, the figure given by its input and output); every other figure has
# its own (workflow/scripts/figures/<fig>.py). Captions for `snakemake --report` are in
# workflow/report/<fig>.rst. Inputs per figure and all_targets(): figure_targets.smk.
# `rule paper` (the default target) and `rule all` are in the top-level Snakefile (Snakemake
# ignores `default_target` set in an included file): paper_targets(), all_targets().


include: "figure_targets.smk"


rule figures:
    input:
        all_figures(),


# One rule per figure (``figure_rule_for`` in figure_targets.smk binds each its own script).
for _fig in FIG_INPUTS:
    figure_rule_for(_fig)
