"""Figure helpers: input checks (``checks``), drawing (``draw``), multi-panel layouts
(``layouts``), the one palette and the colour map (``palette``), impact directions
(``impacts``), the stable 1:1 region of a stability map on other maps and the map's classes
on a raster that follows its interpolated edge (``stable_region``),
the regime of each point of a bifurcation sweep (``sweep_regimes``); and the figures
themselves, one function per figure that takes datasets and returns the figure, in the
modules by subject (``sections``, ``maps``, ``sweeps``, ``bifurcation``, ``stuck_linear``,
``basins``, ``atlas``, ``design``, ``shock``, ``model_ladder``, ``studies``).
Figure scripts use ``import vines.plotting as P`` (and the figure's module): read the
datasets, call the figure's function, ``P.save``.

Figures only *read* the pipeline's datasets (``results/<run>/...``); restyling a figure
never reruns a computation.
"""
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from . import palette
from .checks import (
    CLASS_VALUES,
    FigureInputError,
    basin_slice,
    branch,
    fixed_value,
    grid2d,
    load,
    marked_sections,
    measures,
    require,
    robust_map,
    sorted_by_fixed,
    stability,
    sweep,
    sweep_fixed,
    sweep_points,
    timehistory,
)
from .draw import (
    C_BALL,
    C_BRANCH,
    C_LO,
    CLASSES,
    LABELS,
    SYMBOLS,
    MapStyle,
    bifurcation_dots,
    branch_lines,
    class_handles,
    class_map,
    common_range,
    contour_map,
    eigenvalue_panel,
    figure,
    fmt,
    hatch_cells,
    hatch_region,
    impact_handles,
    impact_phase_panel,
    metres,
    no_impact_handle,
    panel_label,
    save,
    shared_colorbar,
    stable_edge,
    stable_edge_handle,
    th_title,
    time_history,
    twin_measures,
)
from .impacts import impact_direction, point_impacts, pre_impact_velocities
from .layouts import ZOOM_PAD, time_history_figure, zoom_figure, zoom_legend, zoom_range
from .stable_region import (
    class_raster,
    reaches_1to1,
    region_counts,
    stability_margin,
    stable_at,
    stable_orbit_share,
)
from .sweep_regimes import (
    REGIME_ASYM,
    REGIME_CHAOTIC,
    REGIME_QUASIPERIODIC,
    REGIME_SYM,
    REGIMES,
    point_regime,
    regime_grid,
    sweep_regimes,
)

__all__ = [
    # checks
    "CLASS_VALUES", "FigureInputError", "basin_slice", "branch", "fixed_value", "grid2d",
    "load", "marked_sections", "measures", "require", "robust_map", "sorted_by_fixed",
    "stability", "sweep", "sweep_fixed", "sweep_points", "timehistory",
    # draw
    "C_BALL", "C_BRANCH", "C_LO", "CLASSES", "LABELS", "SYMBOLS", "bifurcation_dots",
    "branch_lines", "class_handles", "class_map", "common_range", "contour_map", "MapStyle",
    "eigenvalue_panel", "figure", "fmt", "impact_handles", "impact_phase_panel", "metres",
    "no_impact_handle", "panel_label", "save", "shared_colorbar", "stable_edge", "stable_edge_handle", "hatch_cells", "hatch_region", "th_title",
    "time_history", "twin_measures",
    # impacts
    "impact_direction", "point_impacts", "pre_impact_velocities",
    # palette
    "Line2D", "Patch", "configure", "palette",
    # layouts
    "ZOOM_PAD", "time_history_figure", "zoom_figure", "zoom_legend", "zoom_range",
    # stable_region
    "class_raster", "reaches_1to1", "region_counts", "stability_margin", "stable_at", "stable_orbit_share",
    # sweep_regimes
    "REGIME_ASYM", "REGIME_CHAOTIC", "REGIME_QUASIPERIODIC", "REGIME_SYM", "REGIMES", "point_regime", "regime_grid", "sweep_regimes",
]


def configure(sm) -> None:
    """Settings of a figure job from its rule's params: the colour map of continuous
    quantities (``figures.colormap``), passed only to the figures that draw with it; without
    it reading the colour map is an error (``palette.forbid_colormap``)."""
    name = getattr(getattr(sm, "params", None), "colormap", None)
    if name is None:
        palette.forbid_colormap()
    else:
        palette.use_colormap(name)
