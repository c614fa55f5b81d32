# vines: reproduce the study. `snakemake -c2` draws the paper's figures (config/config.yaml),
# `snakemake -c2 all` everything; `--configfile config/smoke.yaml`: the same DAG on tiny grids.
# Stages live in workflow/rules/, thin scripts in workflow/scripts/, computations in vines.
from snakemake.utils import min_version

# Snakemake 8 APIs: workflow.config_settings, storage-free local rules, executor plugins
min_version("8.0")

# --configfile FILE replaces config/config.yaml (Snakemake would otherwise merge the two
# recursively, keeping the full study's grids next to the smoke grids).
if not workflow.config_settings.configfiles:

    configfile: "config/config.yaml"


include: "workflow/rules/common.smk"
include: "workflow/rules/warmup.smk"
include: "workflow/rules/simulate_grid.smk"
include: "workflow/rules/extract_measures.smk"
include: "workflow/rules/bifurcation_sweep.smk"
include: "workflow/rules/lyapunov.smk"
include: "workflow/rules/map_solve.smk"
include: "workflow/rules/stability_map.smk"
include: "workflow/rules/boundaries.smk"
include: "workflow/rules/timehistory.smk"
include: "workflow/rules/robust_map.smk"
include: "workflow/rules/basin_slice.smk"
include: "workflow/rules/work_precision.smk"
include: "workflow/rules/convergence.smk"
include: "workflow/rules/design.smk"
include: "workflow/rules/design_robust.smk"
include: "workflow/rules/uncertainty.smk"
include: "workflow/rules/orbit_atlas.smk"
include: "workflow/rules/shock.smk"
include: "workflow/rules/model_ladder.smk"
include: "workflow/rules/design_map.smk"
include: "workflow/rules/figures.smk"


# `snakemake -c2` (rule `paper`): the paper's Figures 2-16 and the datasets of their stages.
# `snakemake -c2 all`: also the stages beyond the paper (Lyapunov exponents, attractor
# censuses, solver studies, design, orbit atlas, shock, model ladder) and their figures.
rule paper:
    default_target: True
    input:
        paper_targets(),


rule all:
    input:
        all_targets(),
