"""The one palette of every figure: the colour map of continuous quantities (config key
``figures.colormap``), the regime and stability-class colours, the impact-direction
colours, the greys of "no impact" and "no data", and a categorical list for figures that
tell items apart (attractors, points of a study).

Categorical colours are the Okabe-Ito set (distinct for the common colour-vision
deficiencies, and apart in grey by lightness where two of them meet on a map), and for the
orbit atlas, which tells more classes apart than that set has colours, three of the
colour-blind-safe "muted" scheme (tests/test_stage_figures_design_atlas.py checks every pair of the atlas
figure's colours under simulated protan-, deutan- and tritanopia). Colour map
names appear here only: figure code asks ``colormap()`` for the configured one.
"""
from __future__ import annotations

#: colour maps accepted by ``figures.colormap`` (perceptually uniform ones, and the paper's
#: ``jet``, which invents edges and is unreadable in grey: kept only to compare with the paper)
COLORMAPS = ("viridis", "cividis", "plasma", "inferno", "magma", "jet")
DEFAULT_COLORMAP = "viridis"
#: neutral grey scale of background maps under coloured lines (convergence figure)
GREY_COLORMAP = "Greys"

#: Okabe-Ito colours by name
OKABE_ITO = {"orange": "#E69F00", "sky blue": "#56B4E9", "bluish green": "#009E73",
             "yellow": "#F0E442", "blue": "#0072B2", "vermillion": "#D55E00",
             "reddish purple": "#CC79A7", "black": "#000000"}
#: categorical colours in order of use (attractors of a basin slice, points of a study)
CATEGORICAL = [OKABE_ITO[k] for k in ("blue", "orange", "bluish green", "vermillion",
                                      "reddish purple", "sky blue", "yellow", "black")]

#: "no impact" cells of a KE-ratio map (a class of their own, not KE ratio 0)
NO_IMPACT = "0.72"
#: cells without data (outside a computed grid): left blank in this colour
NO_DATA = "white"

#: regime codes of vines.plotting.sweep_regimes -> (label, colour); the 1:1 colours are
#: those of the stability classes (Fig 16)
REGIMES = {0: ("no impact", "0.85"), 1: ("1:1 symmetric", OKABE_ITO["orange"]),
           2: ("1:1 asymmetric", OKABE_ITO["black"]),
           3: ("other periodic", OKABE_ITO["bluish green"]),
           4: ("irregular", OKABE_ITO["sky blue"]),
           5: ("chatter", OKABE_ITO["reddish purple"])}
#: REGIMES with "irregular" split by the leading Lyapunov exponent (``sweep_regimes``):
#: irregular stays for the points whose lambda_1 is below 0 beyond its interval
REGIMES_SPLIT = {**REGIMES, 4: (r"irregular, $\lambda_1$ < 0", OKABE_ITO["sky blue"]),
                 6: (r"chaotic ($\lambda_1$ > 0)", OKABE_ITO["vermillion"]),
                 7: (r"quasi-periodic ($\lambda_1$ = 0)", OKABE_ITO["blue"])}
#: regimes of the census's asymptotic view beyond the window's labels (``regime_asymptotic``
#: of the basin slices) -> (legend label, colour); quasi-periodic as in REGIMES_SPLIT
CENSUS_REGIMES = {"quasi-periodic": ("quasi-periodic (torus)", REGIMES_SPLIT[7][1])}
#: stability classes (value of ``cls`` in the stability maps) -> (label, colour); the
#: paper's orange / black / white, grey where it leaves points without a 1:1 orbit white
CLASSES = {0: ("no admissible 1:1", "0.6"), 1: ("symmetric stable 1:1", OKABE_ITO["orange"]),
           2: ("asymmetric stable 1:1", OKABE_ITO["black"]), 3: ("unstable 1:1", "white")}

#: LO / cavity ends and ball (the paper's blue and red)
C_LO, C_BALL = OKABE_ITO["blue"], OKABE_ITO["vermillion"]
#: symmetric and asymmetric 1:1 branches of the zoom figures (Figs 6, 15)
C_SYMMETRIC, C_ASYMMETRIC = OKABE_ITO["vermillion"], OKABE_ITO["blue"]
#: impacts by direction of motion just before impact: LO and ball moving towards each
#: other (v_m v_b < 0) or the same way (v_m v_b > 0)
C_TOWARDS, C_SAME_WAY = OKABE_ITO["blue"], OKABE_ITO["orange"]

_current = [DEFAULT_COLORMAP]


def use_colormap(name: str) -> None:
    """Set the colour map of continuous quantities (a figure script passes its rule's
    ``figures.colormap`` param)."""
    if name not in COLORMAPS:
        raise ValueError(f"figures.colormap = {name!r}: allowed {', '.join(COLORMAPS)}")
    _current[0] = name


def forbid_colormap() -> None:
    """For a figure whose rule passes no ``figures.colormap`` (it would not rerun when the
    key changes): reading the colour map is then an error."""
    _current[0] = None


def colormap_name() -> str:
    if _current[0] is None:
        raise RuntimeError("this figure reads figures.colormap but its rule does not pass it:"
                           " add the figure to COLORMAP_FIGURES in "
                           "workflow/rules/figure_targets.smk")
    return _current[0]


def colormap(n: int | None = None):
    """The configured colour map (``n`` discrete colours when given)."""
    import matplotlib
    cmap = matplotlib.colormaps[colormap_name()]
    return cmap.resampled(n) if n else cmap


def sequence(n: int) -> list:
    """``n`` ordered colours along the configured map (light end avoided), for ordered
    series such as grid resolutions."""
    cmap = colormap()
    return [cmap(0.85 * k / max(1, n - 1)) for k in range(n)]


#: three colours of the colour-blind-safe "muted" qualitative scheme, for the atlas's periodic
#: families beyond the Okabe-Ito colours the regimes take
TOL_MUTED = {"green": "#117733", "indigo": "#332288", "purple": "#AA4499"}

#: orbit atlas: groups of periodic families (the paper's wording, 1:1 split by symmetry)
#: -> colour; the 1:1 colours are those of the regimes and stability classes (Fig 16), the
#: other families take colours no regime of ``REGIMES`` uses (the simulation panel beside
#: the atlas draws the regimes in their ``REGIMES`` colours)
FAMILY_GROUPS = {"1:1 symmetric": REGIMES[1][1], "1:1 asymmetric": REGIMES[2][1],
                 "2:2": TOL_MUTED["green"], "2:1": TOL_MUTED["indigo"], "3:2": TOL_MUTED["purple"],
                 "3:3": OKABE_ITO["yellow"], "period-2": OKABE_ITO["vermillion"]}
#: atlas points without a stable admissible family: none found / only unstable found
ATLAS_NONE_FOUND, ATLAS_NONE_STABLE = "white", "0.35"
#: simulated regimes beside the atlas that no atlas family describes: the regime colours
SIM_OTHER = {"no-impact": REGIMES[0][1], "other periodic": REGIMES[3][1],
             "irregular": REGIMES[4][1], "chatter": REGIMES[5][1]}
