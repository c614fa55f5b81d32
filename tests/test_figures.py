"""Figures: vines.plotting (input checks, drawing, layouts), the figure scripts run through the
shared job runner, and the figure rules' rerun plans.

Input checks and scripts run on tiny synthetic datasets. The Snakemake tests work on a copy
of the workflow in tmp_path with a copy of the smoke run's datasets (results/smoke, made by
`snakemake -c2 --configfile config/smoke.yaml`, or the directory named by VINES_SMOKE); they
never touch results/.
"""
import importlib.util
import os
import runpy
import shutil
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from test_pipeline import BEYOND_PAPER, ROOT, _copy_workflow, _planned, _smk, needs_snakemake

import vines.plotting as P
from vines.data.schema import COORD_ATTRS, STABILITY_CLASS_FLAGS

SMOKE = Path(os.environ.get("VINES_SMOKE", ROOT / "results" / "smoke"))
SCRIPTS = ROOT / "workflow" / "scripts" / "figures"
TH_FIGURES = ("fig4", "fig5", "fig9", "fig10")


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


def _timehistories(tmp_path, n_points=2, n_samples=50, bad=False, name="th.nc"):
    t = np.linspace(0.0, 20.0, n_samples)
    rows = np.stack([t] * n_points)
    zb = np.stack([np.sin(t + k) for k in range(n_points)])
    if bad:
        zb[0, 3] = np.nan
    ds = xr.Dataset(
        {"t": (("point", "sample"), rows), "z_m": (("point", "sample"), 0.2 * np.sin(rows)),
         "v_m": (("point", "sample"), 0.2 * np.cos(rows)), "z_b": (("point", "sample"), zb),
         "v_b": (("point", "sample"), np.cos(rows)),
         "row_size": (("point",), np.full(n_points, 2, np.int32)),
         "impact_t": (("impact",), np.tile([5.0, 8.0], n_points)),
         "impact_dw": (("impact",), np.tile([1.0, -1.0], n_points)),
         "impact_phase": (("impact",), np.tile([1.0, 4.0], n_points)),
         "impact_wall": (("impact",), np.tile(np.array([1, -1], "i1"), n_points)),
         "eta": (("point",), np.linspace(0.05, 0.1, n_points)),
         "omega": (("point",), np.ones(n_points)), "F": (("point",), np.full(n_points, 0.05))},
        attrs={"solver_r": 0.65})
    path = tmp_path / name
    ds.to_netcdf(path)
    return path


# ------------------------------------------------------------------ the package's layout

def test_public_names_come_from_their_modules():
    from vines.plotting import checks, draw, layouts
    assert P.FigureInputError is checks.FigureInputError
    assert P.measures is checks.measures and P.sweep_points is checks.sweep_points
    assert P.contour_map is draw.contour_map and P.save is draw.save
    assert P.time_history_figure is layouts.time_history_figure
    assert P.zoom_figure is layouts.zoom_figure
    assert all(hasattr(P, name) for name in P.__all__)


def test_stability_classes_match_the_dataset_flags():
    flags = [int(v) for v in STABILITY_CLASS_FLAGS["flag_values"]]
    assert list(P.CLASS_VALUES) == flags == sorted(P.CLASSES)


# ------------------------------------------------------------------ input checks

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


def test_sweep_points_select_outer_value_and_last_impacts(tmp_path):
    ds = xr.Dataset({"value": ("point", [0.1, 0.2, 0.1]),
                     "outer_value": ("point", [1.0, 1.0, 2.0]),
                     "direction": ("point", [1, 1, 1]),
                     "row_size": ("point", [3, 0, 2]),
                     "dw": ("impact", [1.0, 2.0, 3.0, 4.0, 5.0])})
    path = tmp_path / "sw.nc"
    ds.to_netcdf(path)
    sw = P.sweep(path)
    x, y = P.sweep_points(sw)
    assert x.tolist() == [0.1, 0.1, 0.1, 0.1, 0.1] and y.tolist() == [1, 2, 3, 4, 5]
    x, y = P.sweep_points(sw, 1.0, max_per_point=2)
    assert x.tolist() == [0.1, 0.1] and y.tolist() == [2.0, 3.0]
    with pytest.raises(P.FigureInputError, match="no sweep at outer value 3"):
        P.sweep_points(sw, 3.0)


def test_save_is_atomic_and_writes_both_files(tmp_path):
    fig, axes = P.figure(1, 1)
    axes[0, 0].plot([0, 1], [0, 1])
    P.save(fig, tmp_path / "f.pdf", tmp_path / "f.png")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.pdf", "f.png"]
    assert (tmp_path / "f.png").read_bytes()[:4] == b"\x89PNG"


def test_save_removes_the_temporaries_of_a_killed_write(tmp_path):
    """A write killed by SIGKILL leaves its temporary (.f.png.<random>.png): the next save of
    that figure removes it; another figure's temporaries are not touched."""
    stale = [tmp_path / ".f.png.k1l2e3d4.png", tmp_path / ".f.pdf.abcdefgh.pdf"]
    other = tmp_path / ".f1.png.k1l2e3d4.png"
    for p in (*stale, other):
        p.write_bytes(b"half a figure")
    fig, axes = P.figure(1, 1)
    P.save(fig, tmp_path / "f.pdf", tmp_path / "f.png")
    assert sorted(p.name for p in tmp_path.iterdir()) == [other.name, "f.pdf", "f.png"]


# ------------------------------------------------------------------ figure scripts

def _run_script(name, tmp_path, **inputs):
    """Run a figure script as Snakemake would (``snakemake`` injected), return its log."""
    out = tmp_path / "figures"
    sm = SimpleNamespace(input=SimpleNamespace(**inputs), rule="fig4", wildcards={},
                         output=SimpleNamespace(pdf=str(out / "fig4.pdf"),
                                                png=str(out / "fig4.png")),
                         log=[str(tmp_path / "logs" / "fig4.log")])
    runpy.run_path(str(SCRIPTS / f"{name}.py"), init_globals={"snakemake": sm})
    return Path(sm.log[0])


def test_time_history_script_draws_one_row_per_point(tmp_path):
    _run_script("timehistory", tmp_path, th=[str(_timehistories(tmp_path, n_points=3))])
    png = tmp_path / "figures" / "fig4.png"
    assert png.read_bytes()[:4] == b"\x89PNG" and (tmp_path / "figures" / "fig4.pdf").is_file()
    fig = P.time_history_figure(P.timehistory(_timehistories(tmp_path, n_points=3)))
    assert len(fig.axes) == 9 and fig.axes[0].get_title(loc="left").startswith("(a) $\\eta$")


def _fig14_sweep(tmp_path, F):
    """An eta sweep at two W: every point a symmetric 1:1 orbit (4 periods recorded, two
    impacts each, half a period apart, alternate walls) but one without impacts."""
    eta, W = np.tile([0.1, 0.2, 0.3], 2), np.repeat([0.9, 1.1], 3)
    n = np.array([8, 8, 0, 8, 8, 8], "i4")
    k = int(n.sum())
    ds = xr.Dataset({"value": ("point", eta), "outer_value": ("point", W),
                     "direction": ("point", np.ones(6, "i1")), "row_size": ("point", n),
                     "dw": ("impact", np.tile([1.0, -1.0], k // 2)),
                     "phase": ("impact", np.tile([1.0, 1.0 + np.pi], k // 2)),
                     "wall": ("impact", np.tile(np.array([-1, 1], "i1"), k // 2))},
                    attrs={"swept_parameter": "eta", "outer_parameter": "omega",
                           "fixed": f"F={F}", "solver_n_record": 4})
    path = tmp_path / f"fig14_F{F}.nc"
    ds.to_netcdf(path)
    return str(path)


def test_fig14_legend_lists_the_regimes_drawn(tmp_path, monkeypatch):
    """A scatter of impacts never shows a point without impacts: Fig 14's legend lists the
    regimes it draws, not 'no impact'."""
    saved = []
    monkeypatch.setattr(P, "save", lambda fig, *a, **k: saved.append(fig))
    _run_script("fig14", tmp_path, sweeps=[_fig14_sweep(tmp_path, 0.2), _fig14_sweep(tmp_path, 0.4)])
    (fig,) = saved
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == ["1:1 symmetric"]
    assert len(fig.axes) == 2


def test_same_data_render_to_identical_bytes(tmp_path):
    # no creation date (or other run-dependent metadata) in the PDF and PNG files
    th = [str(_timehistories(tmp_path, n_points=2))]
    files = []
    for k in range(2):
        run = tmp_path / f"render{k}"
        run.mkdir()
        _run_script("timehistory", run, th=th)
        files.append([(run / "figures" / f"fig4.{ext}").read_bytes() for ext in ("pdf", "png")])
    assert files[0] == files[1]
    pdf, png = files[0]
    assert b"/CreationDate" not in pdf and b"/ModDate" not in pdf
    assert b"tIME" not in png and b"Creation Time" not in png


def test_bad_input_fails_with_one_line_in_log_and_console(tmp_path, capfd):
    with pytest.raises(SystemExit) as ei:
        _run_script("timehistory", tmp_path, th=[str(_timehistories(tmp_path, bad=True))])
    assert ei.value.code == 1
    line = "vines fig4: FigureInputError: "
    log = (tmp_path / "logs" / "fig4.log").read_text().splitlines()
    assert log[-1].startswith(line) and "variable 'z_b' has 1 non-finite value" in log[-1]
    console = [ln for ln in capfd.readouterr().err.splitlines() if ln.startswith(line)]
    assert len(console) == 1 and "(log: " in console[0]
    assert not (tmp_path / "figures").exists()


def test_figure_scripts_share_one_preamble():
    for script in sorted(SCRIPTS.glob("*.py")):
        text = script.read_text()
        assert "sys.path" not in text, script.name
        assert "import vines.plotting as P\n" in text, script.name
        assert "    P.configure(sm)\n" in text, script.name      # colour map from the rule
        assert text.rstrip().splitlines()[-1].startswith(
            "run_job(snakemake, lambda: main(snakemake))"), script.name
    for fig in TH_FIGURES:
        assert not (SCRIPTS / f"{fig}.py").exists()


# ------------------------------------------------------------------ rules and reruns

def _copy_datasets(tmp_path, subdirs):
    """Copy smoke datasets into the workflow copy, newer than its scripts and in DAG order
    (the copies must not look outdated: only figure jobs are to be planned). The times lie
    in the past: a future one would be newer than the figures drawn from it within seconds
    on a fast machine, which Snakemake refuses as clock skew."""
    dst = tmp_path / "results" / "smoke"
    base = time.time() - len(subdirs) - 1
    for k, sub in enumerate(subdirs):
        shutil.copytree(SMOKE / sub, dst / sub)
        for f in (dst / sub).rglob("*.nc"):
            os.utime(f, (base + k, base + k))
    return dst


@needs_snakemake
@pytest.mark.skipif(not (SMOKE / "extract_measures").is_dir(), reason="no smoke datasets")
def test_editing_a_figure_script_reruns_only_its_figures(tmp_path):
    _copy_workflow(tmp_path, with_src_copy=True)
    _copy_datasets(tmp_path, ("simulate_grid", "extract_measures", "stability_map",
                                    "boundaries", "timehistory"))
    smoke = ["--configfile", str(tmp_path / "config" / "smoke.yaml")]
    names = ("fig2", "fig12", "fig16") + TH_FIGURES
    figs = [f"results/smoke/figures/{f}.{e}" for f in names for e in ("pdf", "png")]
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == dict.fromkeys(names, 1)
    _smk(tmp_path, *figs, *smoke)
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == {}
    for name, rerun in (("workflow/scripts/figures/fig16.py", ("fig16",)),
                        ("workflow/scripts/figures/timehistory.py", TH_FIGURES),
                        ("src/vines/plotting/draw.py", names)):
        f = tmp_path / name
        text, st = f.read_text(), f.stat()
        f.write_text(text + "\n# restyled\n")
        assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == dict.fromkeys(rerun, 1), name
        f.write_text(text)
        os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))   # as before the edit
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == {}
    # another colour map (a param of the figures that draw with it) reruns those figures only
    cfg = tmp_path / "config" / "smoke.yaml"
    cfg.write_text(cfg.read_text().replace("colormap: viridis", "colormap: jet"))
    assert _planned(_smk(tmp_path, "-n", *figs, *smoke)) == {"fig12": 1}


@needs_snakemake
@pytest.mark.skipif(not (SMOKE / "extract_measures").is_dir(), reason="no smoke datasets")
def test_figure_rule_fails_clearly_on_bad_input(tmp_path):
    _copy_workflow(tmp_path)
    dst = _copy_datasets(tmp_path, ("simulate_grid", "extract_measures"))
    bad = dst / "extract_measures" / "fig2_F0.1.nc"
    with xr.open_dataset(bad) as ds:
        ds = ds.load()
    ds["ke_ratio"][1] = np.nan
    ds.to_netcdf(bad)
    r = _smk(tmp_path, "results/smoke/figures/fig2.png",
             "--configfile", str(tmp_path / "config" / "smoke.yaml"), check=False)
    assert r.returncode != 0
    line = "vines fig2: FigureInputError: results/smoke/extract_measures/fig2_F0.1.nc: variable "
    assert line + "'ke_ratio' has 1 non-finite value" in r.stderr + r.stdout
    log = (dst / "logs" / "figures" / "fig2.log").read_text()
    assert log.splitlines()[-1].startswith(line)
    assert not (dst / "figures" / "fig2.png").exists()


def test_every_figure_has_a_caption_stating_start_and_window():
    # each figure's report caption says how its runs started and what they measured
    report = ROOT / "workflow" / "report"
    names = [s.stem for s in SCRIPTS.glob("*.py") if s.stem != "timehistory"] + list(TH_FIGURES)
    for name in names:
        text = (report / f"{name}.rst").read_text()
        starts = ("from rest", "no initial condition", "initial velocity")   # shock: an impulse
        assert any(w in text for w in starts), name
        assert any(w in text for w in ("window", "periods recorded", "forcing periods")), name


@pytest.mark.skipif(not all((SMOKE / s).is_dir() for s in ("extract_measures", *BEYOND_PAPER)),
                    reason="no complete smoke run (snakemake -c2 all --configfile "
                           "config/smoke.yaml)")
def test_docs_numbers_are_generated_from_the_datasets():
    # docs/figure_numbers.py measures every section on a run's datasets (here the smoke run)
    spec = importlib.util.spec_from_file_location("figure_numbers",
                                                  ROOT / "docs" / "figure_numbers.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    rows = mod.measure(SMOKE)
    assert list(rows) == [s.title for s in mod.SECTIONS]
    assert not any(r[0].startswith(("not available", "not in this run")) for r in rows.values())
    text = mod.render("head", rows)
    assert text.startswith(mod.BEGIN) and text.endswith(mod.END)
    before = mod.DOC.read_text()
    assert mod.main([str(SMOKE), "--check"]) in (0, 1)
    assert mod.DOC.read_text() == before                       # --check never writes


def test_colormap_choices_are_one_list():
    # figures.colormap: the schema's choices are the palette's, the default not jet
    from vines.pipeline.config import load_schema
    key = load_schema()["properties"]["figures"]["properties"]["colormap"]
    assert tuple(key["enum"]) == P.palette.COLORMAPS
    assert key["default"] == P.palette.DEFAULT_COLORMAP != "jet"
    with pytest.raises(ValueError, match="figures.colormap"):
        P.palette.use_colormap("rainbow")
    P.configure(SimpleNamespace(params=SimpleNamespace(colormap="jet")))
    assert P.palette.colormap().name == "jet"
    P.configure(SimpleNamespace(params=SimpleNamespace(colormap="viridis")))
    assert P.palette.colormap_name() == P.palette.DEFAULT_COLORMAP
    # no colour map named in the figure code outside the palette
    for f in list(SCRIPTS.glob("*.py")) + list((ROOT / "src" / "vines" / "plotting").glob("*.py")):
        if f.name != "palette.py":
            assert not any(f'"{c}"' in f.read_text() for c in ("jet", "viridis", "Greys",
                                                               "plasma", "tab10", "tab20")), f
