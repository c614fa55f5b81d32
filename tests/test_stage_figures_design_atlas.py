"""The design, uncertainty and orbit_atlas stages' figures and the atlas stage's independence of the
number of workers: atlas categories and agreement on hand-made atlases, the figure scripts
on tiny datasets, the same atlas with 1 or 2 workers and any rows per task."""
import runpy
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from vines.core.params import D_DEFAULT
from vines.pipeline import stages
from vines.plotting import atlas as A

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ROOT / "workflow" / "scripts" / "figures"
MODEL = {"r": 0.65, "d": D_DEFAULT}


def _atlas(stable, found=None, lam=None):
    """Atlas of families LR/1-sym, LR/1-asym, LLRR/1-sym, LRLR/2 over 2 eta x 3 omega."""
    fams = ["LR/1-sym", "LR/1-asym", "LLRR/1-sym", "LRLR/2"]
    stable = np.asarray(stable, "i1")
    found = stable if found is None else np.asarray(found, "i1")
    lam = np.where(stable == 1, 0.5, np.nan) if lam is None else np.asarray(lam, float)
    D = ("family", "eta", "omega")
    return xr.Dataset({"found": (D, found), "admissible": (D, np.maximum(found, stable)),
                       "stable": (D, stable), "lambda_max": (D, lam),
                       "paper_label": ("family", ["1:1", "1:1", "2:2", "period-2"])},
                      coords={"family": fams, "eta": [0.1, 0.2], "omega": [0.8, 0.9, 1.0]},
                      attrs={"F": 0.2})


def test_atlas_codes_pick_the_most_stable_group_and_mark_coexistence():
    st = np.zeros((4, 2, 3), int)
    st[0, 0, 0] = 1                        # (0.1, 0.8): 1:1 symmetric only
    st[0, 0, 1] = st[2, 0, 1] = 1          # (0.1, 0.9): 1:1 sym and 2:2, 2:2 more stable
    st[3, 1, 2] = 1                        # (0.2, 1.0): period-2
    found = st.copy()
    found[1, 1, 0] = 1                     # (0.2, 0.8): an unstable 1:1 asym found
    lam = np.where(st == 1, 0.5, np.nan)
    lam[2, 0, 1] = 0.3
    codes, coexist = A.atlas_codes(_atlas(st, found, lam))
    g = {k: A.FIRST_GROUP + A.GROUPS.index(k) for k in A.GROUPS}
    assert codes.tolist() == [[g["1:1 symmetric"], g["2:2"], A.NONE_FOUND],
                              [A.NONE_STABLE, A.NONE_FOUND, g["period-2"]]]
    assert coexist.tolist() == [[False, True, False], [False, False, False]]


def test_agreement_counts_only_shared_points_with_atlas_families():
    st = np.zeros((4, 2, 3), int)
    st[1, 0, 0] = 1                        # 1:1 asymmetric stable at (0.1, 0.8)
    st[3, 1, 1] = 1                        # period-2 stable at (0.2, 0.9)
    ds = _atlas(st)
    eta, omega = [0.1, 0.2, 0.3], [0.8, 0.9]
    regime = np.array([["1:1", "2:2"], ["chatter", "period-2"], ["1:1", "1:1"]])
    agr = A.agreement(ds, eta, omega, regime)
    # (0.3, .) is not on the atlas grid, chatter is no family: 3 points, 2 agree
    assert (agr["n"], agr["agree"]) == (3, 2)
    assert agr["misses"] == [(0.1, 0.9, "2:2")]


def _run(script, tmp_path, name, **inputs):
    out = tmp_path / "figures"
    sm = SimpleNamespace(input=SimpleNamespace(**inputs), rule=f"fig_{name}", wildcards={},
                         params=SimpleNamespace(colormap="viridis"),
                         output=SimpleNamespace(pdf=str(out / f"{name}.pdf"),
                                                png=str(out / f"{name}.png")),
                         log=[str(tmp_path / "logs" / f"{name}.log")])
    runpy.run_path(str(SCRIPTS / f"{script}.py"), init_globals={"snakemake": sm})
    return out / f"{name}.png"


def test_atlas_figure_draws_atlas_beside_the_simulation(tmp_path):
    st = np.zeros((4, 2, 3), int)
    st[0] = 1
    path = tmp_path / "atlas_F0.2.nc"
    _atlas(st).to_netcdf(path)
    regime = np.array([["1:1", "2:2", "chatter"], ["no-impact", "irregular", "period-4"]])
    grid = xr.Dataset({"regime": (("eta", "omega", "F"), regime[:, :, None])},
                      coords={"eta": [0.1, 0.2], "omega": [0.8, 0.9, 1.0], "F": [0.2]})
    gpath = tmp_path / "fig12_F0.2.nc"
    grid.to_netcdf(gpath)
    png = _run("atlas", tmp_path, "atlas", atlases=[str(path)], measures=[str(gpath)])
    assert png.read_bytes()[:4] == b"\x89PNG"
    log = (tmp_path / "logs" / "atlas.log").read_text()
    assert "simulation on an atlas family at 2 shared points" in log
    assert "stable and admissible in the atlas at 1;" in log


def _curves(path, F, family, types):
    """A boundaries dataset at F: one straight curve of each type in ``types``."""
    n = len(types)
    eta = np.concatenate([np.linspace(0.1, 0.2, 3)] * n)
    omega = np.concatenate([np.linspace(0.8, 0.8 + 0.05 * k, 3) for k in range(n)])
    xr.Dataset({"curve_type": ("curve", list(types)), "family": ("curve", [family] * n),
                "row_size": ("curve", np.full(n, 3, np.int32))},
               coords={"eta": ("point", eta), "omega": ("point", omega)},
               attrs={"F": F}).to_netcdf(path)
    return str(path)


def test_atlas_figure_draws_family_boundaries_at_their_F(tmp_path):
    """Boundary curves of a family beyond 1:1 go on the atlas panel of their F only."""
    st = np.zeros((4, 2, 3), int)
    st[2] = 1
    path = tmp_path / "atlas_F0.2.nc"
    _atlas(st).to_netcdf(path)
    curves = [_curves(tmp_path / "llrr_F0.2.nc", 0.2, "LLRR/1-sym", ("fold", "grazing")),
              _curves(tmp_path / "lrlr_F0.4.nc", 0.4, "LRLR/2", ("flip",))]
    png = _run("atlas", tmp_path, "atlas", atlases=[str(path)], measures=[],
               boundaries=curves)
    assert png.read_bytes()[:4] == b"\x89PNG"
    log = (tmp_path / "logs" / "atlas.log").read_text()
    assert "F = 0.2: boundary curves drawn on the atlas (type, family): fold LLRR/1-sym, " \
           "grazing LLRR/1-sym" in log
    assert "LRLR/2" not in log


def test_design_figure_from_a_tiny_design(tmp_path):
    from vines.data.netcdf import write_dataset
    spec = {"omega_band": [0.9, 1.1], "n_omega": 3, "amplitudes_m": [0.003, 0.006],
            "eta_max": 0.1, "n_eta": 1, "n_clearance": 2, "census_n": 2, "t_end": 200.0,
            "t_transient": 100.0}
    ds = stages.design(spec, model=MODEL, simulation={"v_stick": 1e-6, "max_impacts": 10**6,
                       "root_tol": 1e-13}, code="test", title="t")
    # the chosen design is never worse than the best grid design; attractors >= from rest
    assert float(ds["vines_worst_ratio"]) <= float(ds["search_worst_ratio"].min()) + 1e-12
    assert np.all(ds["vines_ratio_any_attractor"].values >= ds["vines_ratio"].values)
    # strokes: the TMD's at the largest amplitude, the VI NES's +-L; one eta: on the edge
    from vines.plotting.design import _edge_note
    assert float(ds["tmd_stroke"]) == pytest.approx(0.006 * float(ds["tmd_worst_travel"]))
    assert float(ds["vines_stroke"]) == float(ds["vines_clearance"])
    assert r"\eta_{\max}" in _edge_note(ds)
    path = write_dataset(ds, tmp_path / "design_x.nc")
    png = _run("design", tmp_path, "design", designs=[str(path)])
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_uncertainty_stage_and_figure_from_a_tiny_entry(tmp_path):
    """The stage's dataset holds the study's numbers (CF-complete: written), the nominal
    design's from rest, and its figure draws."""
    from vines.data.netcdf import write_dataset
    spec = {"design": {"omega_band": [0.9, 1.1], "n_omega": 3, "amplitudes_m": [0.003],
                       "eta": 0.1, "clearance_m": 0.0424, "census_n": 64, "t_end": 200.0,
                       "t_transient": 100.0},
            "parameters": {"frequency": ["uniform", -0.05, 0.05], "r": ["uniform", 0.6, 0.6]},
            "samples": 2, "seed": 0}
    ds = stages.uncertainty(spec, model=MODEL, simulation={"v_stick": 1e-6, "max_impacts":
                            10**6, "root_tol": 1e-13}, code="test", title="t")
    assert ds.sizes == {"parameter": 2, "point": 8, "regime_group": 5, "bound": 2}
    assert list(ds["block"].values[:2]) == ["A", "A"] and ds["block"].values[-1] == "AB_r"
    assert np.all(ds["value"].sel(parameter="r").values == 0.6)
    assert float(ds["regime_share"].sum()) == pytest.approx(1.0)
    assert float(ds["tmd_first_order"].sel(parameter="r")) == 0.0     # r: no effect on it
    path = write_dataset(ds, tmp_path / "uncertainty_x.nc")
    png = _run("uncertainty", tmp_path, "uncertainty", studies=[str(path)])
    assert png.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("n_workers,rows", [(2, 1), (1, 2)])
def test_atlas_stage_same_numbers_whatever_workers_and_rows(n_workers, rows):
    grid = {"eta": [0.1, 0.3, 0.5], "omega": {"start": 0.8, "stop": 1.2, "num": 4}, "F": 0.3077}
    kw = dict(sim_t_end=100.0, model=MODEL, code="t", title="t")
    one = stages.orbit_atlas(grid, n_workers=1, rows_per_task=1, **kw)
    other = stages.orbit_atlas(grid, n_workers=n_workers, rows_per_task=rows, **kw)
    for k in ("found", "admissible", "stable", "lambda_max"):
        np.testing.assert_array_equal(one[k].values, other[k].values)
    assert one["stable"].values.any()      # the test compares something


def test_atlas_legend_lists_exactly_the_classes_drawn_in_their_colours():
    g = {k: A.FIRST_GROUP + A.GROUPS.index(k) for k in A.GROUPS}
    sim = {lab: c for c, (lab, _) in A.sim_classes().items()}
    drawn_atlas = np.array([g["1:1 asymmetric"], A.NONE_STABLE, g["2:2"]])
    drawn_sim = np.array([sim["1:1"], sim["chatter"], sim["3:2"]])
    entries = dict(A.legend_entries(drawn_atlas, drawn_sim))
    atlas_col = {lab: col for lab, col in A.atlas_classes().values()}
    assert entries == {
        "1:1 symmetric (simulation: 1:1 of either symmetry)": atlas_col["1:1 symmetric"],
        "1:1 asymmetric": atlas_col["1:1 asymmetric"], "2:2": atlas_col["2:2"],
        "3:2": atlas_col["3:2"],
        "atlas: orbits found, none stable and admissible": atlas_col[
            "orbits found, none stable and admissible"],
        "simulation: chatter": A.sim_classes()[sim["chatter"]][1]}
    # a simulated family is drawn in its group's colour, a simulated 1:1 in the symmetric's
    for lab in ("2:2", "2:1", "3:2", "3:3", "period-2"):
        assert A.sim_classes()[sim[lab]][1] == atlas_col[lab]
    assert A.sim_classes()[sim["1:1"]][1] == atlas_col["1:1 symmetric"]


#: Machado, Oliveira & Fernandes (2009) dichromacy matrices (severity 1) on linear sRGB
CVD = {"protan": [[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                  [-0.003882, -0.048116, 1.051998]],
       "deutan": [[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                  [-0.011820, 0.042940, 0.968881]],
       "tritan": [[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602],
                  [0.004733, 0.691367, 0.303900]]}


def _lab(colour, vision):
    """CIELAB (D65) of a matplotlib colour as seen with ``vision`` (normal or a CVD key)."""
    from matplotlib.colors import to_rgb
    c = np.asarray(to_rgb(colour))
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    if vision != "normal":
        lin = np.clip(np.asarray(CVD[vision]) @ lin, 0, 1)
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722],
                    [0.0193, 0.1192, 0.9505]]) @ lin / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def _min_distance(colours):
    import itertools
    return min(float(np.linalg.norm(_lab(a, v) - _lab(b, v)))
               for a, b in itertools.combinations(colours, 2)
               for v in ("normal", *CVD))


#: smallest CIE76 colour difference asked of two classes of one figure: a pure red and green
#: (the classic deutan confusion) come out at 12 under simulated deuteranopia
MIN_DELTA_E = 15.0


def test_atlas_colours_stay_apart_for_colour_blind_readers():
    """Every two classes of the atlas figure (both panels share one legend) differ by at
    least MIN_DELTA_E in normal vision and under the three simulated dichromacies, except
    the two light greys of 'nothing' (no orbit found / no impact), which never share a
    panel and differ by lightness; so do the regime colours of the regime figures."""
    assert _min_distance(["#FF0000", "#00A000"]) < MIN_DELTA_E        # the check can fail
    from vines.plotting import palette
    atlas = {c for lab, c in A.atlas_classes().values()}
    sim = {c for lab, c in A.sim_classes().values() if lab != "no-impact"}
    assert _min_distance(sorted(atlas | sim)) >= MIN_DELTA_E
    assert _min_distance([c for _, c in palette.REGIMES_SPLIT.values()]) >= MIN_DELTA_E
    # the black 1:1 asymmetric class and chatter are far apart (chatter was near-black)
    black, chatter = palette.FAMILY_GROUPS["1:1 asymmetric"], palette.SIM_OTHER["chatter"]
    assert _min_distance([black, chatter]) > 40
