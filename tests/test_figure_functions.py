"""The figure functions of vines.plotting and the helpers they share (the scripts that call
them are run by test_figures, test_stage_* and the smoke run), the package's import
structure, and the grid cells of core.grids."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from test_import_graph import circles_within, private_imports

import vines.plotting as P
from vines.core.grids import cell_edges, log_cell_edges
from vines.plotting import sections

PLOTTING = Path(P.__file__).resolve().parent


# ------------------------------------------------------------------ core.grids

def test_cell_edges_lie_halfway_with_symmetric_end_cells():
    assert np.array_equal(cell_edges([0.0, 1.0, 3.0]), [-0.5, 0.5, 2.0, 4.0])
    assert np.array_equal(cell_edges([2.0], single=0.5), [1.75, 2.25])
    with pytest.raises(ValueError, match="width"):
        cell_edges([2.0])


def test_log_cell_edges_lie_at_geometric_means():
    assert np.allclose(log_cell_edges([1.0, 100.0]), [0.1, 10.0, 1000.0], rtol=1e-14)
    assert np.allclose(log_cell_edges([10.0], single=0.2), [10 ** 0.9, 10 ** 1.1], rtol=1e-14)


# ------------------------------------------------------------------ sections (Figs 8, 13)

def _plane(axes: dict, fixed: dict, cut: str, marked) -> xr.Dataset:
    """A measures grid over two axes with one fixed value; KE ratio = the first axis's value
    (so each panel's data say where they come from), section_<cut> marking ``marked``."""
    coords = {**{k: np.asarray(v, float) for k, v in axes.items()},
              **{k: np.array([v]) for k, v in fixed.items()}}
    dims = ("eta", "omega", "F")
    shape = tuple(coords[d].size for d in dims)
    first = next(iter(axes))
    ke = np.broadcast_to(coords[first].reshape([-1 if d == first else 1 for d in dims]), shape)
    return xr.Dataset({"ke_ratio": (dims, ke.copy()), "xmax_m": (dims, np.full(shape, 0.01)),
                       f"section_{cut}": (cut, np.isin(coords[cut], marked))},
                      coords=coords)


def _titles(fig):
    return [ax.get_title(loc="left") for ax in fig.axes if ax.get_title(loc="left")]


def test_fig8_sections_have_rows_F_and_columns_W():
    grids = [_plane({"eta": [0.1, 0.2, 0.3], "F": [0.2, 0.3, 0.4]}, {"omega": w}, "F",
                    [0.2, 0.4]) for w in (0.9, 1.1)]
    fig = sections.sections_figure(grids, "F", "eta", "fig7", panel_height=3.2)
    assert _titles(fig) == [r"(a) $F$ = 0.2, $\Omega$ = 0.9", r"(b) $F$ = 0.2, $\Omega$ = 1.1",
                            r"(c) $F$ = 0.4, $\Omega$ = 0.9", r"(d) $F$ = 0.4, $\Omega$ = 1.1"]
    (xmax,) = fig.axes[0].lines
    assert np.array_equal(xmax.get_xdata(), [0.1, 0.2, 0.3])


def test_fig13_sections_have_rows_F_and_columns_eta():
    grids = [_plane({"omega": [0.8, 0.9, 1.0, 1.1], "eta": [0.1, 0.3, 0.5]}, {"F": F}, "eta",
                    [0.1, 0.5]) for F in (0.2, 0.4)]
    fig = sections.sections_figure(grids, "eta", "omega", "fig12", panel_height=3.0)
    assert _titles(fig) == [r"(a) $F$ = 0.2, $\eta$ = 0.1", r"(b) $F$ = 0.2, $\eta$ = 0.5",
                            r"(c) $F$ = 0.4, $\eta$ = 0.1", r"(d) $F$ = 0.4, $\eta$ = 0.5"]
    # panel (a) plots against omega; its KE ratio is the omega of each point
    ke = next(ax for ax in fig.axes if ax is not fig.axes[0]
              and ax.bbox.bounds == fig.axes[0].bbox.bounds).lines[0]
    assert np.array_equal(ke.get_xdata(), [0.8, 0.9, 1.0, 1.1])
    assert np.array_equal(ke.get_ydata(), [0.8, 0.9, 1.0, 1.1])


def test_sections_must_be_marked_alike():
    grids = [_plane({"eta": [0.1, 0.2], "F": [0.2, 0.4]}, {"omega": w}, "F", marked)
             for w, marked in ((0.9, [0.2]), (1.1, [0.4]))]
    with pytest.raises(P.FigureInputError, match="same, non-empty F sections"):
        sections.sections_figure(grids, "F", "eta", "fig7", panel_height=3.2)


# ------------------------------------------------------------------ shared helpers

def test_summary_and_legend_title_the_figure_and_list_one_panel(capsys):
    fig, axes = P.figure(1, 2)
    axes[0, 0].plot([1, 2], [1, 2], label="one")
    axes[0, 0].plot([1, 2], [2, 1], label="two")
    axes[0, 1].plot([1, 2], [1, 1], label="not listed")
    P.draw.summary_and_legend(fig, ["first line", "second line"], axes[0, 0])
    assert fig._suptitle.get_text() == "first line\nsecond line"
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == ["one", "two"]
    assert capsys.readouterr().out.splitlines() == ["first line", "second line"]


def test_plain_log_ticks_label_1_2_5_as_plain_numbers():
    fig, axes = P.figure(1, 1)
    ax = axes[0, 0]
    ax.set_yscale("log")
    ax.set_ylim(0.3, 30)
    P.draw.plain_log_ticks(ax.yaxis)
    fig.canvas.draw()
    shown = [t.get_text() for t in ax.get_yticklabels() if 0.3 <= t.get_position()[1] <= 30]
    assert shown == ["0.5", "1", "2", "5", "10", "20"]


# ------------------------------------------------------------------ import structure

def test_plotting_has_no_import_circle_and_imports_no_private_name():
    assert circles_within("vines.plotting") == []
    assert private_imports("vines.plotting") == []
