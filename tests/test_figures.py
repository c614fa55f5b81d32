"""Figures: input checks of vines.plotting.draw and the figure rules' rerun plans.

Input checks run on tiny synthetic datasets. The dry-run test works on a copy of the
workflow in tmp_path with a copy of the smoke run's datasets (results/smoke, made by
`snakemake -c2 --configfile config/smoke.yaml`); it never touches results/.
"""
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from test_pipeline import ROOT, _copy_workflow, _planned, _smk, needs_snakemake
from vines.plotting import draw as P
from vines.data.netcdf import COORD_ATTRS

SMOKE = ROOT / "results" / "smoke"


def _grid(tmp_path, eta=(0.05, 0.1, 0.15), ke=None, drop=None, name="g.nc"):
    eta = np.asarray(eta, float)
    ke = np.linspace(0.1, 0.5, eta.size) if ke is None else np.asarray(ke, float)
    shape = (eta.size, 1, 1)
    ds = xr.Dataset(
        {"ke_ratio": (("eta", "omega", "F"), ke.reshape(shape), {"units": "1"}),
         "xmax_m": (("eta", "omega", "F"), np.full(shape, 0.01), {"units": "m"})},
        coords={"eta": ("eta", eta, COORD_ATTRS["eta"]),
                "omega": ("omega", [1.0], COORD_ATTRS["omega"]),
                "F": ("F", [0.05], COORD_ATTRS["F"])})
    if drop:
        ds = ds.drop_vars(drop)
    path = tmp_path / name
    ds.to_netcdf(path)
    return path


def test_good_grid_passes(tmp_path):
    ds = P.measures(_grid(tmp_path), axes=("eta",), fixed=("omega", "F"))
    assert P.fixed_value(ds, "F") == 0.05


def test_nan_value_fails_clearly(tmp_path):
    path = _grid(tmp_path, ke=[0.1, np.nan, 0.3])
    with pytest.raises(P.FigureInputError, match=r"g\.nc: variable 'ke_ratio' has 1 "
                                                 r"non-finite value"):
        P.measures(path, axes=("eta",), fixed=("omega", "F"))


def test_missing_coordinate_fails_clearly(tmp_path):
    path = _grid(tmp_path, drop="F")
    with pytest.raises(P.FigureInputError, match="expected coordinate 'F' is missing"):
        P.measures(path, axes=("eta",), fixed=("omega",))


def test_too_few_points_and_missing_file_fail_clearly(tmp_path):
    with pytest.raises(P.FigureInputError, match="coordinate 'eta' has 1 values"):
        P.measures(_grid(tmp_path, eta=[0.1], ke=[0.2]), axes=("eta",), fixed=("F",))
    with pytest.raises(P.FigureInputError, match="does not exist"):
        P.measures(tmp_path / "nope.nc", axes=("eta",), fixed=("F",))


def test_stability_map_allows_nan_only_without_a_1to1_orbit(tmp_path):
    lam = np.array([[0.5, np.nan], [2.0, 0.9]])
    for cls, ok in (([[1, 0], [3, 2]], True), ([[1, 3], [3, 2]], False)):
        ds = xr.Dataset({"lambda_max": (("eta", "omega"), lam),
                         "cls": (("eta", "omega"), np.array(cls, np.int8))},
                        coords={"eta": [0.1, 0.2], "omega": [0.9, 1.0]}, attrs={"F": 0.2})
        path = tmp_path / f"s{ok}.nc"
        ds.to_netcdf(path)
        if ok:
            P.stability(path)
        else:
            with pytest.raises(P.FigureInputError, match="lambda_max"):
                P.stability(path)


def test_save_is_atomic_and_writes_both_files(tmp_path):
    fig, axes = P.figure(1, 1)
    axes[0, 0].plot([0, 1], [0, 1])
    P.save(fig, tmp_path / "f.pdf", tmp_path / "f.png")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.pdf", "f.png"]
    assert (tmp_path / "f.png").read_bytes()[:4] == b"\x89PNG"


@needs_snakemake
@pytest.mark.skipif(not (SMOKE / "measures").is_dir(), reason="no smoke datasets")
def test_editing_one_figure_script_reruns_only_that_figure(tmp_path):
    _copy_workflow(tmp_path)
    dst = tmp_path / "results" / "smoke"
    for sub in ("grid", "measures", "stability"):       # copy2: mtimes kept
        shutil.copytree(SMOKE / sub, dst / sub)
    smoke = ["--configfile", str(tmp_path / "config" / "smoke.yaml")]
    figs = [f"results/smoke/figures/{f}.{e}" for f in ("fig2", "fig16") for e in ("pdf", "png")]
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == {"fig2": 1, "fig16": 1}
    _smk(tmp_path, *figs, *smoke)
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == {}
    script = tmp_path / "workflow" / "scripts" / "figures" / "fig16.py"
    script.write_text(script.read_text() + "\n# restyled\n")
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == {"fig16": 1}


@needs_snakemake
@pytest.mark.skipif(not (SMOKE / "measures").is_dir(), reason="no smoke datasets")
def test_figure_rule_fails_clearly_on_bad_input(tmp_path):
    _copy_workflow(tmp_path)
    dst = tmp_path / "results" / "smoke"
    for sub in ("grid", "measures"):
        shutil.copytree(SMOKE / sub, dst / sub)
    bad = dst / "measures" / "fig2_F0.1.nc"
    with xr.open_dataset(bad) as ds:
        ds = ds.load()
    ds["ke_ratio"][1] = np.nan
    ds.to_netcdf(bad)
    r = _smk(tmp_path, "results/smoke/figures/fig2.png",
             "--configfile", str(tmp_path / "config" / "smoke.yaml"), check=False)
    assert r.returncode != 0
    assert "vines figures: fig2: bad input:" in r.stderr + r.stdout
    assert "'ke_ratio' has 1 non-finite value" in r.stderr + r.stdout
    assert not (dst / "figures" / "fig2.png").exists()
