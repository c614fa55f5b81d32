"""Figure rules get only the `figures` config keys they read: `figures.colormap` goes to the
figures that draw with the colour map, so changing it reruns those and no other figure.

Which figures read the colour map is found here from the sources (the scripts and
vines.plotting, by their syntax trees), independently of the list the rules use
(COLORMAP_FIGURES in workflow/rules/figure_targets.smk). The rerun plan itself is tested on
the smoke run in tests/test_figures.py (test_editing_a_figure_script_reruns_only_its_figures).
"""
import ast
import re
from types import SimpleNamespace

import pytest
from test_figures import SCRIPTS, TH_FIGURES
from test_pipeline import ROOT

import vines.plotting as P

PLOTTING = ROOT / "src" / "vines" / "plotting"
TARGETS = ROOT / "workflow" / "rules" / "figure_targets.smk"
#: the palette's functions that read the configured colour map
READERS = {"colormap", "colormap_name", "sequence"}


def _names(tree) -> set:
    """Every name and attribute name used in a syntax tree."""
    return ({n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
            | {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)})


def _plotting_functions() -> dict:
    """Every function of vines.plotting (outside the palette): name -> the names it uses
    (functions of one name in several modules together)."""
    used = {}
    for f in PLOTTING.glob("*.py"):
        if f.name == "palette.py":
            continue
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.FunctionDef):
                used.setdefault(node.name, set()).update(_names(node) - {node.name})
    return used


def _plotting_readers(direct=False) -> set:
    """Functions of vines.plotting (outside the palette) that read the colour map: directly,
    or (``direct`` False) also through the functions that do (to a fixed point; by name, so
    a reader's name used as a variable elsewhere counts as a call: keep them apart)."""
    used = _plotting_functions()
    readers = {name for name, names in used.items() if names & READERS}
    while not direct:
        more = {name for name, names in used.items() if names & readers} | readers
        if more == readers:
            break
        readers = more
    return readers


def _figures_reading_the_colormap() -> set:
    readers = READERS | _plotting_readers()
    out = set()
    for script in SCRIPTS.glob("*.py"):
        if _names(ast.parse(script.read_text())) & readers:
            out |= set(TH_FIGURES) if script.stem == "timehistory" else {script.stem}
    return out


def _colormap_figures_of_the_rules() -> set:
    m = re.search(r"^COLORMAP_FIGURES = (\(.*?\))$", TARGETS.read_text(), re.M | re.S)
    return set(ast.literal_eval(m.group(1)))


def test_only_contour_maps_and_the_colormap_figures_panels_read_the_colormap():
    # contour maps (Figs 7, 12, robust_tet), the search grid of design, the contours (and
    # the colours of many points) of convergence
    assert _plotting_readers(direct=True) == {"contour_map", "_search_panel", "grid_panels",
                                              "point_colours"}


def test_colormap_param_goes_exactly_to_the_figures_that_read_it():
    readers = _figures_reading_the_colormap()
    assert _colormap_figures_of_the_rules() == readers
    # of the paper's figures, the contour maps of Figs 7 and 12 (Fig 8, 13: sections, lines)
    assert {f for f in readers if re.fullmatch(r"fig[0-9]+", f)} == {"fig7", "fig12"}
    assert {"robust_tet", "design", "convergence"} <= readers


def test_figure_without_the_param_cannot_read_the_colormap():
    # a figure rule without `colormap` that drew with it would not rerun when it changes
    try:
        P.configure(SimpleNamespace(params=SimpleNamespace(code="x")))
        with pytest.raises(RuntimeError, match="COLORMAP_FIGURES"):
            P.palette.colormap()
        with pytest.raises(RuntimeError, match="figures.colormap"):
            P.palette.sequence(3)
        P.configure(SimpleNamespace(params=SimpleNamespace(colormap="jet")))
        assert P.palette.colormap().name == "jet"
    finally:
        P.palette.use_colormap(P.palette.DEFAULT_COLORMAP)
