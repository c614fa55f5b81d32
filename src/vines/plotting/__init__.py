"""Figure helpers: input checks (``checks``), drawing (``draw``), multi-panel layouts
(``layouts``). Figure scripts use ``import vines.plotting as P``.

Figures only *read* the pipeline's datasets (``results/<run>/...``); restyling a figure
never reruns a computation.
"""
from .checks import (CLASS_VALUES, FigureInputError, branch, fixed_value, grid2d, load,
                     marked_sections, measures, require, sorted_by_fixed, stability, sweep,
                     sweep_points, timehistory)
from .draw import (C_BALL, C_BRANCH, C_LO, CLASSES, LABELS, SYMBOLS, bifurcation_dots,
                   branch_lines, contour_map, eigenvalue_panel, figure, fmt, metres,
                   panel_label, save, th_title, time_history, twin_measures)
from .layouts import ZOOM_PAD, time_history_figure, zoom_figure, zoom_range

__all__ = [
    # checks
    "CLASS_VALUES", "FigureInputError", "branch", "fixed_value", "grid2d", "load",
    "marked_sections", "measures", "require", "sorted_by_fixed", "stability", "sweep",
    "sweep_points", "timehistory",
    # draw
    "C_BALL", "C_BRANCH", "C_LO", "CLASSES", "LABELS", "SYMBOLS", "bifurcation_dots",
    "branch_lines", "contour_map", "eigenvalue_panel", "figure", "fmt", "metres",
    "panel_label", "save", "th_title", "time_history", "twin_measures",
    # layouts
    "ZOOM_PAD", "time_history_figure", "zoom_figure", "zoom_range",
]
