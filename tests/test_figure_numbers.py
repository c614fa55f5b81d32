"""docs/figure_numbers.py: its argument parser, the refusal of a path that is not a run, the
--check differences and the figures whose stage is not in the run.

The logic runs on small fake runs (one number per dataset, sections of the test's own); the
last test runs the real sections on the smoke run (results/smoke or VINES_SMOKE), skipped
without one.
"""
import importlib.util
import shutil
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr
from test_figures import SMOKE
from test_pipeline import BEYOND_PAPER, ROOT

SCRIPT = ROOT / "docs" / "figure_numbers.py"
COMMIT = "0123456789abcdef0123456789abcdef01234567"
DOC = "intro\n\n<!-- numbers:begin -->\nold\n<!-- numbers:end -->\n\nrows after\n"


@pytest.fixture(scope="module")
def fn():
    spec = importlib.util.spec_from_file_location("figure_numbers", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _dataset(path, value, commit=COMMIT):
    path.parent.mkdir(parents=True, exist_ok=True)
    xr.Dataset({"v": ((), value)}, attrs={"vines_version": "0.1.0", "git_commit": commit,
                                          "config_sha256": "ab" * 32,
                                          "solver_t_end": 700.0,
                                          "solver_t_transient": 400.0}).to_netcdf(path)


def _value(res, prefix):
    with xr.open_dataset(next((res / "stage_a").glob(f"{prefix}*.nc"))) as ds:
        return [f"value {float(ds['v']):.2f}"]


@pytest.fixture
def fake(fn, tmp_path, monkeypatch):
    """A run with stage_a only; sections A (stage_a) and B (stage_b, not in the run)."""
    run = tmp_path / "run"
    _dataset(run / "stage_a" / "a_1.nc", 1.5)
    monkeypatch.setattr(fn, "SECTIONS", (
        fn.Section("A", lambda r: _value(r, "a"), (("stage_a", "a"),)),
        fn.Section("B", lambda r: ["b"], (("stage_b", "b"),))))
    doc = tmp_path / "figures.md"
    doc.write_text(DOC)
    return run, doc


def _cli(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True, timeout=120)


def test_help_prints_usage_and_writes_nothing(tmp_path):
    doc = ROOT / "docs" / "figures.md"
    before = doc.read_text()
    r = _cli("--help")
    assert r.returncode == 0 and "--check" in r.stdout and "RUN" in r.stdout
    assert doc.read_text() == before
    assert "--help" not in before


@pytest.mark.parametrize("what", ["missing", "not_a_run"])
def test_a_path_that_is_not_a_run_is_refused_without_writing(tmp_path, what):
    doc = tmp_path / "figures.md"
    doc.write_text(DOC)
    run = tmp_path / "run"
    if what == "not_a_run":
        run.mkdir()
        xr.Dataset({"v": ((), 1.0)}).to_netcdf(run / "x.nc")         # no stage folder
        (run / "stage").mkdir()
        xr.Dataset({"v": ((), 1.0)}).to_netcdf(run / "stage" / "y.nc")   # no provenance
    for args in ((run,), (run, "--check"), ("--check", run)):
        r = _cli(*args, "--doc", doc)
        assert r.returncode == 2, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and str(run) in r.stderr
        assert "Traceback" not in r.stderr
    assert doc.read_text() == DOC


def test_regenerate_states_commit_and_marks_stages_not_in_the_run(fn, fake, capsys):
    run, doc = fake
    assert fn.main([str(run), "--doc", str(doc)]) == 0
    text = doc.read_text()
    assert text.startswith("intro\n\n<!-- numbers:begin -->") and text.endswith("rows after\n")
    assert "**A**\n\n- value 1.50\n" in text
    assert "**B**\n\n- not in this run\n" in text
    assert f"commit `{COMMIT}`" in text and "t_end = 700, t_transient = 400" in text
    assert "run `run`" in text and str(run.parent) not in text     # no path of this machine
    assert "not in this run (" in capsys.readouterr().out


@pytest.mark.parametrize("order", ["check_first", "run_first"])
def test_check_passes_when_equal_and_prints_each_difference(fn, fake, capsys, order):
    run, doc = fake
    fn.main([str(run), "--doc", str(doc)])
    written = doc.read_text()
    args = (["--check", str(run)] if order == "check_first" else [str(run), "--check"])
    capsys.readouterr()
    assert fn.main(args + ["--doc", str(doc)]) == 0
    assert "numbers agree" in capsys.readouterr().out
    _dataset(run / "stage_a" / "a_1.nc", 2.25)
    assert fn.main(args + ["--doc", str(doc)]) == 1
    out = capsys.readouterr().out
    assert "A:\n  old: value 1.50\n  new: value 2.25" in out
    assert doc.read_text() == written                               # --check never writes


def test_stage_not_in_the_run_is_no_difference(fn, fake, capsys):
    # the file holds B's numbers (from a run with stage_b); a run without it checks clean
    run, doc = fake
    _dataset(run.parent / "full" / "stage_a" / "a_1.nc", 1.5)
    _dataset(run.parent / "full" / "stage_b" / "b_1.nc", 1.0)
    fn.main([str(run.parent / "full"), "--doc", str(doc)])
    assert "**B**\n\n- b\n" in doc.read_text()
    capsys.readouterr()
    assert fn.main(["--check", str(run), "--doc", str(doc)]) == 0
    out = capsys.readouterr().out
    assert "not in this run" in out and ": B" in out and "old: b" not in out
    # a section the file lacks entirely counts as a difference
    doc.write_text(DOC)
    assert fn.main(["--check", str(run), "--doc", str(doc)]) == 1
    assert "A:\n  old: (no line)\n  new: value 1.50" in capsys.readouterr().out


def test_datasets_of_several_commits_are_each_named(fn, fake):
    run, doc = fake
    _dataset(run / "stage_a" / "a_2.nc", 1.0, commit="f" * 40 + "-dirty")
    fn.main([str(run), "--doc", str(doc)])
    text = doc.read_text()
    assert f"`{COMMIT}` (1 datasets)" in text and f"`{'f' * 40}-dirty` (1 datasets)" in text


@pytest.mark.skipif(not all((SMOKE / s).is_dir() for s in ("extract_measures", *BEYOND_PAPER)),
                    reason="no complete smoke run (snakemake -c2 all --configfile "
                           "config/smoke.yaml)")
def test_smoke_paper_part_checks_clean_against_the_full_run(fn, tmp_path, capsys):
    doc = tmp_path / "figures.md"
    shutil.copy(ROOT / "docs" / "figures.md", doc)
    assert fn.main([str(SMOKE), "--doc", str(doc)]) == 0
    text = doc.read_text()
    block = text[text.index(fn.BEGIN):text.index(fn.END)]
    assert "not available" not in block and "not in this run" not in block
    with xr.open_dataset(SMOKE / "timehistory" / "fig4.nc") as ds:
        assert f"commit `{ds.attrs['git_commit']}`" in text
    # the same run without the stages beyond the paper: their figures are skipped
    paper = tmp_path / "smoke"
    paper.mkdir()
    for stage in SMOKE.iterdir():
        if stage.name not in ("lyapunov", "robust_map") and stage.is_dir():
            (paper / stage.name).symlink_to(stage)
    capsys.readouterr()
    assert fn.main(["--check", str(paper), "--doc", str(doc)]) == 0
    out = capsys.readouterr().out
    assert "not in this run" in out and "fig3_lyapunov, robust_tet" in out
    assert np.all([f"**{s.title}**" in block for s in fn.SECTIONS])
