# Figures: one rule per figure, each with its own script, go here. `rule all` (in the
# top-level Snakefile: Snakemake ignores `default_target` set in an included file) requests
# all_targets(): for now every dataset the figures need; add the figure files to it.


def all_targets():
    return all_datasets()
