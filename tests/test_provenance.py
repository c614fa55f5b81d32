"""Provenance that cannot lie: jobs run their own checkout's vines, datasets say which code
and libraries made them, merged datasets do not depend on the chunking."""
import os
import shutil
import subprocess
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from test_pipeline import TINY, _copy_workflow, _smk, needs_snakemake

from vines.core.params import D_DEFAULT
from vines.data.netcdf import read_dataset, write_dataset
from vines.data.provenance import LIBRARIES, git_commit
from vines.pipeline import stages
from vines.pipeline.axes import grid_chunks
from vines.pipeline.codeversion import COMPUTE, code_version
from vines.pipeline.jobs import check_code_version, run_job

ROOT = Path(__file__).resolve().parents[1]
MODEL = {"r": 0.65, "d": D_DEFAULT}
SIM = {"t_end": 120.0, "t_transient": 60.0}


def _measures(tmp_path, chunk_size, tag):
    axes = {"eta": [0.05, 0.1, 0.2], "omega": [1.0], "F": [0.05, 0.1]}
    paths = []
    for i, c in enumerate(grid_chunks({k: np.asarray(v) for k, v in axes.items()}, chunk_size)):
        ds = stages.simulate_grid(c, model=MODEL, simulation=SIM, code="x", title="t")
        paths.append(write_dataset(ds, tmp_path / f"{tag}_{i}.nc"))
    return stages.extract_measures(paths, axes=axes, sections={}, model=MODEL, code="x",
                                   title="m")


def test_merged_measures_do_not_depend_on_the_chunk_size(tmp_path):
    a, b = _measures(tmp_path, 1, "a"), _measures(tmp_path, 6, "b")
    assert a.attrs == b.attrs
    for k in a.variables:
        np.testing.assert_array_equal(a[k].values, b[k].values)


def test_datasets_record_code_and_library_versions(tmp_path):
    ds = _measures(tmp_path, 6, "c")
    for name in ("python",) + LIBRARIES:
        assert f"{name} " in ds.attrs["library_versions"]
    assert ds.attrs["code_version"] == "x" and ds.attrs["history"]


def test_git_commit_marks_an_edited_checkout_dirty(tmp_path):
    if shutil.which("git") is None:
        pytest.skip("git not installed")
    repo = tmp_path / "repo"
    (repo / "src").mkdir(parents=True)
    f = repo / "src" / "a.py"
    f.write_text("x = 1\n")
    env = {**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t",
           "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t"}
    for cmd in (["init", "-q"], ["add", "."], ["commit", "-qm", "c"]):
        subprocess.run(["git", "-C", str(repo)] + cmd, check=True, env=env)
    clean = git_commit(repo / "src")
    assert len(clean) == 40
    f.write_text("x = 2\n")
    assert git_commit(repo / "src") == clean + "-dirty"


def test_a_job_refuses_code_it_was_not_planned_with(tmp_path, capsys):
    check_code_version(code_version(COMPUTE))          # the running code: accepted
    sm = SimpleNamespace(log=[str(tmp_path / "job.log")], params=SimpleNamespace(code="0" * 16),
                         rule="simulate_grid", wildcards={})
    ran = []
    with pytest.raises(SystemExit) as exc:
        run_job(sm, lambda: ran.append(1))
    assert exc.value.code == 1 and not ran
    log = (tmp_path / "job.log").read_text()
    assert "code version 0000000000000000" in log and "Traceback" in log


@needs_snakemake
def test_jobs_run_their_own_checkout_not_another_on_pythonpath(tmp_path):
    """Checkout B runs while another copy (A, edited) is first on PYTHONPATH, as an
    installed copy would be: B's sources run and B's code version is recorded."""
    other = tmp_path / "other_src"
    shutil.copytree(ROOT / "src", other, ignore=shutil.ignore_patterns("*.egg-info", "__pycache__"))
    (other / "vines" / "core" / "flow.py").write_text(
        (other / "vines" / "core" / "flow.py").read_text() + "\nraise ImportError('wrong copy')\n")
    b = tmp_path / "b"
    b.mkdir()
    _copy_workflow(b, with_src_copy=True)
    cfg = {k: TINY[k] for k in ("run", "simulation", "timehistories")}
    saved = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join([str(other)] + ([saved] if saved else []))
    try:
        _smk(b, cfg=cfg)
    finally:
        if saved is None:
            del os.environ["PYTHONPATH"]
        else:
            os.environ["PYTHONPATH"] = saved
    ds = read_dataset(b / "results" / "tiny" / "timehistory" / "th.nc")
    assert ds.attrs["code_version"] == code_version(COMPUTE, b / "src" / "vines")


def test_write_dataset_writes_dask_backed_and_in_memory_data_alike(tmp_path):
    """The plain-lock writer must not drop lazily computed (dask) variables."""
    import dask.array as da
    import xarray as xr
    cf = {"long_name": "a value", "units": "1"}
    values = np.linspace(0.0, 1.0, 10)
    lazy = xr.Dataset({"a": ("x", da.from_array(values, chunks=3), cf)},
                      coords={"x": ("x", np.arange(10), cf)})
    eager = lazy.compute()
    write_dataset(lazy, tmp_path / "lazy.nc")
    write_dataset(eager, tmp_path / "eager.nc")
    np.testing.assert_array_equal(read_dataset(tmp_path / "lazy.nc")["a"].values, values)
    assert (tmp_path / "lazy.nc").read_bytes() == (tmp_path / "eager.nc").read_bytes()
