# vines: reproduce the study. `snakemake -c2` runs the full study (config/config.yaml);
# `snakemake -c2 --configfile config/smoke.yaml` the same DAG on tiny grids.
# Stages live in workflow/rules/, thin scripts in workflow/scripts/, computations in vines.

# --configfile FILE replaces config/config.yaml (Snakemake would otherwise merge the two
# recursively, keeping the full study's grids next to the smoke grids).
if not workflow.config_settings.configfiles:

    configfile: "config/config.yaml"


include: "workflow/rules/common.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/measures.smk"
include: "workflow/rules/sweeps.smk"
include: "workflow/rules/maps.smk"
include: "workflow/rules/timehistory.smk"
include: "workflow/rules/workprecision.smk"
include: "workflow/rules/convergence.smk"
include: "workflow/rules/figures.smk"


rule all:
    default_target: True
    input:
        all_targets(),
