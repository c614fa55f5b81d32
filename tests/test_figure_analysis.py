"""What the figures compute from the datasets before drawing: the regime of sweep points
(Figs 14, 15, fig14_regimes), the stable 1:1 region with interpolated edges (Figs 12, 16),
the impacts of a time history (Figs 4, 5, 9, 10) and the whole-window samples behind them."""
import math

import numpy as np
import pytest
import xarray as xr

import vines.plotting as P
from vines.core.measures import time_histories
from vines.orbits.atlas.stability_map import stability_map
from vines.plotting.sweep_regimes import (
    REGIME_CHATTER,
    REGIME_IRREGULAR,
    REGIME_NONE,
    REGIME_PERIODIC,
    point_regime,
)
from vines.solvers import simulate

N_REC = 10


def _repeat(pattern_dw, pattern_phase, pattern_wall, n_periods=N_REC):
    k = len(pattern_dw)
    return (np.tile(pattern_dw, n_periods), np.tile(pattern_phase, n_periods),
            np.tile(pattern_wall, n_periods).astype("i1")), k


# ------------------------------------------------------------------ regimes of sweep points

def test_regime_of_synthetic_impact_sequences():
    (dw, ph, wl), _ = _repeat([1.5, -1.5], [1.0, 1.0 + math.pi], [1, -1])
    assert point_regime(dw, ph, wl, N_REC) == P.REGIME_SYM
    (dw, ph, wl), _ = _repeat([1.5, -1.5], [1.0, 3.0], [1, -1])
    assert point_regime(dw, ph, wl, N_REC) == P.REGIME_ASYM
    (dw, ph, wl), _ = _repeat([1.2, -0.7, -0.4], [0.5, 2.0, 4.0], [1, -1, -1])   # 2:1
    assert point_regime(dw, ph, wl, N_REC) == REGIME_PERIODIC
    (dw, ph, wl), _ = _repeat([1.5, -1.5, 1.2, -1.2], [1.0, 4.1, 1.1, 4.2], [1, -1, 1, -1],
                              N_REC // 2)                                        # period 2
    assert point_regime(dw, ph, wl, N_REC) == REGIME_PERIODIC
    assert point_regime([], [], [], N_REC) == REGIME_NONE
    walls = np.array([1, 1, 1, 1, -1] * 4, "i1")
    assert point_regime(np.full(20, 1e-3), np.linspace(0, 6, 20), walls, N_REC) == REGIME_CHATTER
    rng = np.random.default_rng(1)
    dw = rng.uniform(0.5, 2.0, 20) * np.tile([1, -1], 10)
    assert point_regime(dw, rng.uniform(0, 6.28, 20), np.tile([1, -1], 10),
                        N_REC) == REGIME_IRREGULAR


def test_regime_tolerance_separates_settled_from_drifting():
    (dw, ph, wl), _ = _repeat([1.5, -1.5], [1.0, 1.0 + math.pi], [1, -1])
    assert point_regime(dw * (1 + 1e-6 * np.arange(dw.size)), ph, wl, N_REC) == P.REGIME_SYM
    assert point_regime(dw * (1 + 1e-3 * np.arange(dw.size)), ph, wl,
                        N_REC) == REGIME_IRREGULAR


@pytest.mark.parametrize("eta,omega,F,cls", [(0.05, 1.0, 0.05, 1), (0.12, 1.1, 0.3077, 2)])
def test_regime_of_simulated_impacts_agrees_with_the_orbit_solver(eta, omega, F, cls):
    # independent: the stability map solves the 1:1 orbits on the impact map and says
    # whether the stable one is symmetric (cls 1) or asymmetric (cls 2)
    res = simulate(eta, omega, F, t_end=3000.0, t_transient=2000.0)
    sel = res.impacts["t"] >= res.t_last - N_REC * 2 * math.pi / omega
    code = point_regime(res.impact_dw[sel], res.impact_phase[sel], res.impacts["wall"][sel],
                        N_REC)
    smap = stability_map(np.array([eta - 0.01, eta]), np.array([omega, omega + 0.001]), F)
    assert int(smap["cls"][1, 0]) == cls
    assert code == {1: P.REGIME_SYM, 2: P.REGIME_ASYM}[cls]


def _sweep_ds(points):
    """A sweep dataset (as bifurcation_sweep writes it) from (eta, omega, direction, dw,
    phase, wall) tuples."""
    rows = [np.asarray(p[3]) for p in points]
    return xr.Dataset(
        {"value": ("point", [p[0] for p in points]),
         "outer_value": ("point", [p[1] for p in points]),
         "direction": ("point", np.array([p[2] for p in points], "i1")),
         "row_size": ("point", np.array([r.size for r in rows], "i4")),
         "dw": ("impact", np.concatenate(rows)),
         "phase": ("impact", np.concatenate([np.asarray(p[4]) for p in points])),
         "wall": ("impact", np.concatenate([np.asarray(p[5], "i1") for p in points]))},
        attrs={"solver_n_record": N_REC})


def test_regime_grid_places_each_point():
    (dw, ph, wl), _ = _repeat([1.5, -1.5], [1.0, 1.0 + math.pi], [1, -1])
    pts = [(e, w, d, dw if e > 0.15 else [], ph if e > 0.15 else [], wl if e > 0.15 else [])
           for d in (1, -1) for w in (0.9, 1.0) for e in (0.1, 0.2, 0.3)]
    xs, ys, grid = P.regime_grid(_sweep_ds(pts), +1)
    assert xs.tolist() == [0.1, 0.2, 0.3] and ys.tolist() == [0.9, 1.0]
    assert grid.tolist() == [[REGIME_NONE, P.REGIME_SYM, P.REGIME_SYM]] * 2


# ------------------------------------------------------------------ stable region

def _map(lam_rows, omega, eta=(0.1, 0.2), cls=None):
    lam = np.repeat(np.asarray(lam_rows, float)[None, :], len(eta), axis=0)   # (eta, omega)
    if cls is None:
        cls = np.where(lam < 1, 1, 3)
    return xr.Dataset({"lambda_max": (("eta", "omega"), np.where(cls == 0, np.nan, lam)),
                       "cls": (("eta", "omega"), np.asarray(cls, "i1"))},
                      coords={"eta": list(eta), "omega": list(omega)}, attrs={"F": 0.2})


def test_stable_edge_is_interpolated_between_rows():
    # the tongue of the issue: |lambda_max| 0.945 at omega 0.5, 1.86 at 0.5067 -> the
    # edge lies at 0.5 + 0.0067 * 0.055 / 0.915 = 0.500403, not half-way (0.50335)
    m = _map([0.945, 1.86, 1.9], [0.5, 0.5067, 0.52])
    edge = 0.5 + 0.0067 * 0.055 / 0.915
    st = P.stable_at(m, [0.15], [0.5, edge - 1e-6, edge + 1e-6, 0.5033])
    assert st[:, 0].tolist() == [True, True, False, False]
    assert not P.stable_at(m, [0.15], [0.49])[0, 0]                # outside the map's range


def test_class_raster_follows_the_interpolated_edge():
    """Fig 16: the row omega = 0.49 lies on the edge of a stable band (|lambda_max| 1 -+ 1e-4
    alternating along eta, stable 0.95 above, unstable 1.2 below): drawn cell by cell every
    other cell of the band's lower half-row is white (a notch). On the raster the band is
    stable from just above 0.49 (edge at 0.49 + 1e-4 / 0.05 * 0.01 at most) in every column,
    unstable below it, and each raster point keeps the class of a neighbouring map point:
    the asymmetric stable cell (class 2) stays black, the map's own points keep theirs."""
    eta = (0.1, 0.2, 0.3, 0.4)
    lam = np.array([[1.2, 1 - 1e-4, 0.95, 1.5], [1.2, 1 + 1e-4, 0.95, 1.5],
                    [1.2, 1 - 1e-4, 0.95, 1.5], [1.2, 1 + 1e-4, 0.95, 1.5]])
    cls = np.where(lam < 1, 1, 3)
    cls[3, 2] = 2
    m = xr.Dataset({"lambda_max": (("eta", "omega"), lam), "cls": (("eta", "omega"), cls.astype("i1"))},
                   coords={"eta": list(eta), "omega": [0.48, 0.49, 0.5, 0.51]})
    er, wr, c = P.class_raster(m, per_eta=4, per_omega=8)
    assert c.shape == (wr.size, er.size) == (32, 16)
    # the band's upper edge: 0.95 at 0.5 -> 1.5 at 0.51 crosses 1 at 0.5 + 0.01 / 11
    above = (wr > 0.49 + 0.0002) & (wr < 0.5 + 0.01 / 11)
    below = (wr < 0.49) | (wr > 0.5 + 0.01 / 11)
    assert above.sum() == 9 and np.all(np.isin(c[above], (1, 2))) and np.all(c[below] == 3)
    assert np.all(c[above][:, er > 0.4] == 2) and np.all(c[above][:, er < 0.3] == 1)
    # at the map's own points (raster points nearest them) the classes are the map's
    at = c[np.argmin(np.abs(wr[:, None] - m["omega"].values), axis=0)][
        :, np.argmin(np.abs(er[:, None] - np.array(eta)), axis=0)]
    near = np.abs(wr[np.argmin(np.abs(wr[:, None] - m["omega"].values), axis=0)] - 0.49) > 1e-3
    assert np.array_equal(at[near], cls.T[near])
    # a stable point between strongly unstable ones (interpolated stable patch 1/1000 of a
    # cell, narrower than a raster point) is not hidden: the points next to it keep its class
    lone = _map([1.5, 0.999, 1.5], [0.4, 0.5, 0.6])
    er, wr, c = P.class_raster(lone, per_eta=4, per_omega=8)
    rows, cols = np.nonzero(c == 1)                     # 2 x 2 raster points per map point
    assert rows.size == 2 * 2 * 2 and np.all(np.abs(wr[rows] - 0.5) < 0.01)
    assert np.all(np.min(np.abs(er[cols, None] - np.array([0.1, 0.2])), axis=1) < 0.02)
    assert np.all((c == 1) | (c == 3))


def test_points_without_an_orbit_are_not_stable():
    m = _map([0.5, 0.5, 0.5], [0.9, 1.0, 1.1], cls=[[1, 0, 1], [1, 0, 1]])
    assert P.stability_margin(m)[1].tolist() == [-1.0, -1.0]
    st = P.stable_at(m, [0.15], [0.9, 0.95, 1.0])[:, 0]
    assert st.tolist() == [True, False, False]                    # 0.5 -> -1 crosses at 1/3


def test_reached_and_counted_only_inside_the_stable_region():
    m = _map([0.5, 0.5, 2.0], [0.9, 1.0, 1.1])
    reg = np.array([["1:1", "no-impact", "1:1"], ["irregular", "1:1", "1:1"]])  # (eta, omega)
    ke = np.array([[0.8, 0.0, 0.9], [0.2, 0.7, 0.6]])
    g = xr.Dataset({"regime": (("eta", "omega", "F"), reg[..., None]),
                    "ke_ratio": (("eta", "omega", "F"), ke[..., None])},
                   coords={"eta": [0.1, 0.2], "omega": [0.9, 1.0, 1.1], "F": [0.2]})
    assert P.reaches_1to1(g).tolist() == [[True, False], [False, True], [True, True]]
    assert P.region_counts(g, m) == {"stable": 4, "reached": 2, "ke_zero": 1}


# ------------------------------------------------------------------ time histories

def test_time_histories_sample_the_whole_window_and_keep_its_impacts():
    sim = {"t_end": 400.0, "t_transient": 200.0}
    pts = [{"eta": 0.05, "omega": 1.0, "F": 0.05}, {"eta": 0.2, "omega": 0.9, "F": 0.4}]
    th = time_histories(pts, model={}, simulation=sim, n_periods=3, samples_per_period=20,
                        window_samples_per_period=8)
    span = 200.0 * 1.0 / (2 * math.pi)                            # periods of the fastest
    assert th["window_t"].shape == (2, math.ceil(span) * 8 + 1)
    assert np.allclose(th["window_t"][:, 0], 200.0) and np.allclose(th["window_t"][:, -1], 400.0)
    assert np.allclose(th["window_z_m"][:, -1], th["z_m"][:, -1])      # same end state
    # 1:1 orbit of Fig 4a: two impacts per period over the whole window, not only the last 3
    n0 = int(th["row_size"][0])
    assert abs(n0 - 2 * span) <= 2
    t0 = th["impact_t"][:n0]
    assert t0.min() >= 200.0 and t0.min() < 200.0 + 2 * math.pi
    none = time_histories(pts[:1], model={}, simulation=sim, n_periods=3,
                          samples_per_period=20, window_samples_per_period=0)
    assert "window_t" not in none


def test_impact_phase_panel_counts_the_window(tmp_path):
    # ball velocity sampled between impacts; v_m- = v_b- + w': point 0: (L) 0.5 + 1 same
    # way, (R) 0.5 - 1 towards, (L) -0.3 + 1 towards; point 1: (L) 0.2 + 0.5, (R) -0.1 - 0.5
    # both the same way
    ds = xr.Dataset({"row_size": ("point", np.array([3, 2], "i4")),
                     "t": (("point", "sample"), [[0.5, 1.5, 2.5], [1.0, 2.0, 3.0]]),
                     "v_b": (("point", "sample"), [[0.5, 0.5, -0.3], [0.2, -0.1, 0.0]]),
                     "impact_t": ("impact", [1.0, 2.0, 3.0, 1.5, 2.5]),
                     "impact_dw": ("impact", [1.0, -1.0, 1.0, 0.5, -0.5]),
                     "impact_phase": ("impact", [0.5, 4.0, 6.0, 1.0, 2.0]),
                     "impact_wall": ("impact", np.array([1, -1, 1, 1, -1], "i1"))},
                    attrs={"solver_r": 0.65})
    assert P.point_impacts(ds, 1)["phase"].tolist() == [1.0, 2.0]
    fig, axes = P.figure(1, 2)
    # wall +1 is the left end (w = +1), -1 the right end; (impacts, of them the same way)
    assert P.impact_phase_panel(axes[0, 0], ds, 0) == {"right end": (1, 0), "left end": (2, 1)}
    assert P.impact_phase_panel(axes[0, 1], ds, 1) == {"right end": (1, 1), "left end": (1, 1)}


def _pixels_of(fig, colour):
    """Mask (rows from the top) of the pixels of ``fig`` drawn in ``colour`` (hex) over
    white, at any opacity of at least 0.3."""
    from matplotlib.colors import to_rgb
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3] / 255.0
    c = np.array(to_rgb(colour))
    k = int(np.argmax(1.0 - c))                       # the channel that shows the colour best
    t = (1.0 - img[..., k]) / (1.0 - c[k])            # opacity if the pixel is c over white
    resid = np.abs(img - (t[..., None] * c + (1.0 - t[..., None])))
    return (t >= 0.3) & np.all(resid <= 0.02, axis=-1)


def test_impact_markers_on_the_panel_edge_are_drawn_whole():
    """Fig 4: an impact at phase 2 pi (and |w'_i| = 0) sits on the panel's edge; its marker
    is drawn whole, half of it outside the axes, not cut by them."""
    import matplotlib.pyplot as plt
    ds = xr.Dataset({"row_size": ("point", np.array([2], "i4")),
                     "t": (("point", "sample"), [[0.5, 1.5, 2.5]]),
                     "v_b": (("point", "sample"), [[0.5, 0.5, 0.5]]),
                     "impact_t": ("impact", [1.0, 2.0]),
                     "impact_dw": ("impact", [-1.0, 0.0]),
                     "impact_phase": ("impact", [2 * np.pi - 1e-12, 2.0]),
                     "impact_wall": ("impact", np.array([-1, -1], "i1"))},
                    attrs={"solver_r": 0.65})
    fig, axes = P.figure(1, 1, width=3.0, height=2.5)
    ax = axes[0, 0]
    P.impact_phase_panel(ax, ds, 0)
    box = ax.get_window_extent()
    # the first impact: moving towards each other (v_m = 0.5 - 1); the second the same way
    _, cols = np.nonzero(_pixels_of(fig, P.palette.C_TOWARDS))
    assert np.any(cols > box.x1 + 1), "marker at phase 2 pi cut at the right edge"
    rows, _ = np.nonzero(_pixels_of(fig, P.palette.C_SAME_WAY))
    y_up = fig.bbox.height - rows                       # pixel rows counted from below
    assert np.any(y_up < box.y0 - 1), "marker at |w'_i| = 0 cut at the bottom edge"
    plt.close(fig)


def test_stable_orbit_share_is_drawn_only_where_the_orbit_is_stable():
    """The robust-TET map's census row at omega = 0.5 samples the narrow stable tongue
    (|lambda_max| 0.945 at 0.5, 1.86 at 0.5067: edge at 0.500403); drawn finer than the
    census grid, its value covers the tongue and not the half cell above it, where no stable
    1:1 orbit exists and the fraction is 0."""
    m = _map([1.5, 0.945, 1.86, 1.9, 1.9], [0.46, 0.5, 0.5067, 0.55, 0.6],
             eta=(0.05, 0.1, 0.15, 0.2))
    frac = np.array([[0.8, 0.6], [0.0, 0.0]])             # (omega 0.5, 0.55) x (eta 0.1, 0.15)
    er, wr, zr, kept = P.stable_orbit_share([0.1, 0.15], [0.5, 0.55], frac, m, per_cell=40)
    assert kept == 0
    assert er.min() > 0.075 and er.max() < 0.175 and wr.min() > 0.475 and wr.max() < 0.575
    edge = 0.5 + 0.0067 * 0.055 / 0.915
    # the lower edge: 1.5 at 0.46 -> 0.945 at 0.5 crosses 1 at 0.46 + 0.04 * 0.5 / 0.555
    low = 0.46 + 0.04 * 0.5 / 0.555
    inside = (wr > low) & (wr < edge)
    assert inside.any() and (~inside & (wr < 0.525)).any()
    col = er < 0.125                                       # the eta = 0.1 cells
    assert np.all(zr[inside][:, col] == 0.8) and np.all(zr[inside][:, ~col] == 0.6)
    assert np.all(zr[~inside] == 0.0)
    # a positive fraction where the map has no stable point anywhere in the cell is kept
    frac2 = np.array([[0.8, 0.6], [0.3, 0.0]])
    _, wr2, zr2, kept2 = P.stable_orbit_share([0.1, 0.15], [0.5, 0.55], frac2, m, per_cell=40)
    assert kept2 == 1
    upper = wr2 > 0.525
    assert np.all(zr2[upper][:, col] == 0.3) and np.all(zr2[upper][:, ~col] == 0.0)
    # a census point on the map's edge (eta 0.2): its cell's outer half (to 0.225) takes
    # the edge's class, not the census value; a point off the map (0.25) is kept
    er3, wr3, zr3, _ = P.stable_orbit_share([0.15, 0.2, 0.25], [0.5, 0.55],
                                            np.array([[0.5] * 3, [0.0] * 3]), m, per_cell=40)
    beyond = (er3 > 0.2) & (er3 < 0.225)
    assert np.all(zr3[~inside][:, beyond] == 0.0) and np.all(zr3[inside][:, beyond] == 0.5)
    assert np.all(zr3[:, er3 > 0.225] == np.repeat([0.5, 0.0], 40)[:, None])


# ------------------------------------------------------------------ zoom insets (Figs 6, 15)

def _panel(y_top):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    x = np.linspace(0.0, 1.0, 400)
    ax.scatter(np.repeat(x, 20), np.tile(np.linspace(-2.0, y_top, 20), 400), s=1)
    ax.set_xlim(0.0, 1.0)
    ax.set_ylim(-2.5, 2.5)
    return fig, ax


def test_inset_covers_no_drawn_point():
    """An inset goes where nothing is drawn (with room for its tick labels); when the data
    fill the panel, the panel gains headroom above them for it and the data stay whole."""
    import matplotlib.pyplot as plt

    from vines.plotting import bifurcation as B
    for y_top in (0.0, 2.4):                  # room in the upper half / none anywhere
        fig, ax = _panel(y_top)
        box = B._inset_box(ax)
        assert B._covered(B._drawn_points(ax), box) == 0
        lo, hi = ax.get_ylim()
        assert lo == -2.5 and (hi == 2.5) == (y_top == 0.0)
        assert len(B._drawn_points(ax)) == 8000           # every point still inside
        plt.close(fig)


def _zoom_data():
    """A branch dataset (row 0: symmetric branch over eta in [-1, 2], |w'| = 1 + eta^2,
    stable on [0.3, 0.7]: zoom window [0.06, 0.94]; row 1: a small asymmetric branch on
    [0.25, 0.3]) and a sweep whose impacts fill |w'| <= 2.5 outside [0.2, 0.75] and sit on
    the branch inside it, like Fig 6 (a)."""
    e0, e1 = np.linspace(-1.0, 2.0, 301), np.linspace(0.25, 0.3, 11)
    eta = np.concatenate([e0, e1])
    dw = np.concatenate([1 + e0 ** 2, 1.3 + 8 * (0.3 - e1)])
    stable = np.concatenate([(e0 >= 0.3) & (e0 <= 0.7), e1 > 0.28])
    n = eta.size
    br = xr.Dataset({"dw_L": ("point", -dw), "dw_R": ("point", dw),
                     "admissible": ("point", np.ones(n, bool)), "stable": ("point", stable),
                     "lambda_max": ("point", np.where(stable, 0.5, 1.5)),
                     "abs_eigenvalues": (("point", "k"), np.full((n, 4), 0.5)),
                     "row_size": ("row", np.array([e0.size, e1.size], "i4"))},
                    coords={"eta": ("point", eta), "F": ("point", np.full(n, 0.1)),
                            "omega": ("point", np.ones(n))})
    val = np.round(np.arange(0.0, 1.0001, 0.01), 10)
    rows = [np.linspace(-2.5, 2.5, 20) if (v < 0.2 or v > 0.75) else
            np.array([-1.0, 1.0]) * (1 + v ** 2) for v in val]
    sw = xr.Dataset({"value": ("point", val), "outer_value": ("point", np.full(val.size, 0.1)),
                     "row_size": ("point", np.array([r.size for r in rows], "i4")),
                     "dw": ("impact", np.concatenate(rows))}, attrs={"outer_parameter": "F"})
    return br, sw


def test_zoom_panel_fits_its_data_and_the_inset_reads():
    """Fig 6 (a): the y range is that of the impacts and branches inside the zoom window
    (|w'| <= 2.5), not of the branch beyond it (up to 5) nor headroom for the inset; the
    inset sits where nothing is drawn and its tick labels do not touch."""
    import matplotlib.pyplot as plt

    from vines.plotting import bifurcation as B
    br, sw = _zoom_data()
    fig = P.zoom_figure(sw, B.continued_branches([br]), outer_dim="F")
    B.draw_switched(fig, [br], sw, "F")
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    assert -2.5 - 0.3 <= lo <= -2.5 and 2.5 <= hi <= 2.5 + 0.3, (lo, hi)
    (ins,) = ax.child_axes
    fig.canvas.draw()
    box = ins.get_window_extent().transformed(ax.transAxes.inverted())
    x, y = P.sweep_points(sw, 0.1)
    fx, fy = (ax.transData + ax.transAxes.inverted()).transform(np.c_[x, y]).T
    assert not np.any((fx >= box.x0) & (fx <= box.x1) & (fy >= box.y0) & (fy <= box.y1))
    for labels in (ins.get_xticklabels(), ins.get_yticklabels()):
        ext = sorted((t.get_window_extent() for t in labels if t.get_text()),
                     key=lambda b: (b.x0, b.y0))
        assert len(ext) >= 2
        for a, b in zip(ext[:-1], ext[1:], strict=True):
            assert not a.overlaps(b.expanded(1.1, 1.1)), "inset tick labels touch"
    plt.close(fig)
