# Figure inputs and targets: FIG_INPUTS, REQUESTED_FIGURES, figure_rule, figure_script,
# fig_out, all_figures, paper_targets, all_targets. A figure takes its datasets by name
# from the config sections: grids, sweeps, branches, stability maps, boundaries and time histories named
# `figN` or `figN_<anything>` (see docs/figures.md). A figure whose datasets are not all configured
# (e.g. a test config) is not requested. Included by workflow/rules/figures.smk.


def _named(stage, prefix):
    return [
        dataset(stage, n)
        for n in sorted(STAGE_ENTRIES[stage])
        if n == prefix or n.startswith(f"{prefix}_")
    ]


def _measures(p):
    return _named("extract_measures", p)


def _sweeps(p):
    return _named("bifurcation_sweep", p)


def _branches(p):
    return _named("map_solve", p)


def _smaps(p):
    return _named("stability_map", p)


def _boundaries(p):
    return _named("boundaries", p)


def _th(p):
    return _named("timehistory", p)


def _robust(p):
    return _named("robust_map", p)


def _slices(p):
    return _named("basin_slice", p)


def _designs(p):
    return _named("design", p)


def _atlases(p):
    return _named("orbit_atlas", p)


def _shocks(p):
    return _named("shock", p)


def _family_boundaries():
    """Boundary curves of the families beyond 1:1 (boundaries entries with other walls or
    periods than LR/1), drawn on the atlas."""
    return [
        dataset("boundaries", n)
        for n, b in sorted(BOUNDARIES.items())
        if boundary_family(b).engine.on_atlas
    ]


# figure -> named inputs (lists of dataset files); every list must be non-empty
FIG_INPUTS = {
    "fig2": {"measures": _measures("fig2")},
    "fig3": {"sweep": _sweeps("fig3")},
    # beyond the paper: the leading Lyapunov exponent under the Fig 3 diagrams
    "fig3_lyapunov": {"sweep": _sweeps("fig3"), "lyapunov": _named("lyapunov", "fig3")},
    "fig4": {"th": _th("fig4")},
    "fig5": {"th": _th("fig5")},
    "fig6": {"sweep": _sweeps("fig3"), "branches": _branches("fig6")},
    "fig7": {"measures": _measures("fig7")},
    "fig8": {"measures": _measures("fig7")},
    "fig9": {"th": _th("fig9")},
    "fig10": {"th": _th("fig10")},
    "fig11": {"measures": _measures("fig11"), "th": _th("fig11")},
    "fig12": {
        "measures": _measures("fig12"),
        "stability": _smaps("fig16"),
        "boundaries": _boundaries("fig16"),
    },
    "fig13": {"measures": _measures("fig12")},
    "fig14": {"sweeps": _sweeps("fig14")},
    # companion of Fig 14 (not in the paper); irregular split by the exponents
    "fig14_regimes": {
        "sweeps": _sweeps("fig14"),
        "lyapunov": _named("lyapunov", "fig14"),
    },
    "fig15": {"sweep": _sweeps("fig15"), "branches": _branches("fig15")},
    "fig16": {"stability": _smaps("fig16"), "boundaries": _boundaries("fig16")},
    # beyond the paper: coexisting attractors (robust-TET maps beside Fig 12, basin slices)
    "robust_tet": {
        "robust": _robust("robust"),
        "measures": _measures("fig12"),
        "stability": _smaps("fig16"),
        "boundaries": _boundaries("fig16"),
    },
    "basin_slices": {"slices": _slices("basin")},
    # beyond the paper: absorber design against the TMD, the periodic-orbit atlas
    "design": {"designs": _designs("design")},
    "design_robust": {
        "robust": [dataset("design_robust", n) for n in sorted(DESIGN_ROBUST)]
    },
    "uncertainty": {"studies": _named("uncertainty", "uncertainty")},
    "atlas": {"atlases": _atlases("atlas"), "measures": _measures("fig12")},
    # beyond the paper: free decay after a shock against the TMD
    "shock": {"shocks": _shocks("shock")},
    # beyond the paper: the slow flow against the exact model, amplitudes and costs
    "model_ladder": {"ladders": _named("model_ladder", "model_ladder")},
    # beyond the paper: who wins where, VI NES against TMD over the design space
    "design_map": {"maps": _named("design_map", "design_map")},
    # beyond the paper: the solver studies
    "workprecision": {
        "cases": [dataset("work_precision", c) for c in WORK_PRECISION["cases"]]
    },
    "convergence": {
        s: dataset("convergence", s) if s in CONVERGENCE else ""
        for s in ("window", "vstick", "grid")
    },
}
# figure -> inputs drawn when configured (may be empty; the figure is requested without them)
FIG_OPTIONAL_INPUTS = {"atlas": {"boundaries": _family_boundaries()}}
# figures that draw with the configured colour map (`figures.colormap`: plotting.contour_map,
# palette.colormap, palette.sequence), the only ones it is passed to as a param, so that
# changing it reruns them and no other figure (tests/test_figure_params.py)
COLORMAP_FIGURES = ("fig7", "fig12", "robust_tet", "design", "convergence")


def figure_params(fig):
    """The keys of config `figures` the figure reads (its rule's params besides code)."""
    if fig in COLORMAP_FIGURES:
        return {"colormap": config["figures"]["colormap"]}
    return {}


REQUESTED_FIGURES = [f for f, ins in FIG_INPUTS.items() if all(ins.values())]
_missing = [f for f in FIG_INPUTS if f not in REQUESTED_FIGURES]
if _missing and REQUESTED_FIGURES:
    print(
        f"vines pipeline: warning: figures {', '.join(_missing)} are not requested "
        "(their datasets are not configured)",
        file=sys.stderr,
    )


#: figures drawn by the shared time-history script
TIMEHISTORY_FIGURES = ("fig4", "fig5", "fig9", "fig10")


def figure_rule(fig):
    """Rule name of a figure: figN, fig_<study>."""
    return fig if fig.startswith("fig") else f"fig_{fig}"


def figure_script(fig):
    """Script (workflow/scripts/figures/<name>.py) of a figure."""
    return "timehistory" if fig in TIMEHISTORY_FIGURES else fig


def fig_out(name):
    return {
        "pdf": f"{RES}/figures/{name}.pdf",
        "png": report(
            f"{RES}/figures/{name}.png",
            caption=f"../report/{name}.rst",
            category="Figures",
            labels={"figure": name},
        ),
    }


def all_figures(figs=None):
    """PDF and PNG of ``figs`` (default: every requested figure)."""
    figs = REQUESTED_FIGURES if figs is None else figs
    return [f"{RES}/figures/{f}.{ext}" for f in figs for ext in ("pdf", "png")]


def is_paper_figure(fig):
    """Figures 2-16 of the paper (figN); the others are companions beyond the paper."""
    return re.fullmatch(r"fig[0-9]+", fig) is not None


def paper_targets():
    """Rule `paper`: the paper's figures and every dataset of the stages behind them."""
    return all_datasets(PAPER_STAGES) + all_figures(
        [f for f in REQUESTED_FIGURES if is_paper_figure(f)]
    )


def all_targets():
    """Rule `all`: every configured dataset and figure."""
    return all_datasets() + all_figures()


# The rules are defined in a function called in a loop: a rule's script path is evaluated
# again when its job runs, so it must bind the figure of its own call (a bare loop variable
# would give every rule the last figure's script).
def figure_rule_for(fig):

    rule:
        name:
            figure_rule(fig)
        input:
            **FIG_INPUTS[fig],
            **FIG_OPTIONAL_INPUTS.get(fig, {}),
        output:
            **fig_out(fig),
        log:
            f"{RES}/logs/figures/{fig}.log",
        conda:
            "../../environment.yml"
        params:
            **figure_params(fig),
            code=CODE_FIGURES,
            script=script_of(f"figures/{figure_script(fig)}.py"),
        script:
            f"../scripts/figures/{figure_script(fig)}.py"
