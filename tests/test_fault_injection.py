"""Random fault injection (tests/fault_injection.py): its checks can fail, and the smoke
pipeline survives random SIGKILL/SIGTERM with the README's remedy (slow; CI runs a short
version through .ci/run, with the smoke run it just made as the reference)."""
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import fault_injection as fi
import numpy as np
import pytest
import xarray as xr

needs_proc = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
needs_snakemake = pytest.mark.skipif(shutil.which("snakemake") is None,
                                     reason="snakemake not installed")


def _write(path: Path, value=1.5, attrs=None, seconds=2.0) -> Path:
    ds = xr.Dataset({"ke_ratio": ("point", np.array([0.25, np.nan, value])),
                     "seconds": ("point", np.full(3, seconds))},
                    attrs={"code_version": "abc", "git_commit": "unknown", **(attrs or {})})
    path.parent.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(path)
    return path


def test_identical_datasets_compare_equal_nan_included(tmp_path):
    a, b = _write(tmp_path / "a.nc"), _write(tmp_path / "b.nc")
    assert fi.compare_dataset(a, b, timed=False) == []


def test_one_ulp_in_a_value_is_a_difference(tmp_path):
    a = _write(tmp_path / "a.nc")
    b = _write(tmp_path / "b.nc", value=np.nextafter(1.5, 2.0))
    assert fi.compare_dataset(a, b, timed=False) == ["variable ke_ratio"]


def test_an_attribute_is_compared_but_not_git_commit(tmp_path):
    a = _write(tmp_path / "a.nc")
    b = _write(tmp_path / "b.nc", attrs={"code_version": "abd", "git_commit": "0123abc"})
    assert fi.compare_dataset(a, b, timed=False) == ["attribute code_version"]


def test_timings_are_left_out_only_in_the_timed_folders(tmp_path):
    a, b = _write(tmp_path / "a.nc"), _write(tmp_path / "b.nc", seconds=3.0)
    assert fi.compare_dataset(a, b, timed=True) == []
    assert fi.compare_dataset(a, b, timed=False) == ["variable seconds"]


def test_a_missing_dataset_and_a_changed_figure_are_findings(tmp_path):
    ref, got = tmp_path / "ref", tmp_path / "got"
    _write(ref / "simulate_grid" / "g" / "chunk_0.nc")
    for res, png in ((ref, b"\x89PNG a"), (got, b"\x89PNG b")):
        (res / "figures").mkdir(parents=True)
        (res / "figures" / "fig2.png").write_bytes(png)
    report = fi.Report(seed=0, faults_asked=0)
    fi.compare_results(ref, got, report)
    assert report.findings == ["figures/fig2.png differs (bytes)",
                               "simulate_grid/g/chunk_0.nc: only in the reference run"]


@needs_proc
def test_a_process_outliving_its_run_is_reported_and_ended():
    proc = subprocess.Popen(["sleep", "60"], start_new_session=True)
    try:
        report = fi.Report(seed=0, faults_asked=0)
        orphans = fi.Orphans(grace=0.5, report=report)
        orphans.add(proc.pid)
        orphans.check(final=True)
        assert len(report.findings) == 1 and "leftover process" in report.findings[0]
        assert "sleep 60" in report.findings[0]
        assert proc.wait(timeout=10) == -signal.SIGKILL     # ended by the check
    finally:
        if proc.poll() is None:
            os.kill(proc.pid, signal.SIGKILL)


@needs_proc
def test_a_process_ending_within_the_grace_is_no_finding():
    proc = subprocess.Popen(["sleep", "0.3"], start_new_session=True)
    report = fi.Report(seed=0, faults_asked=0)
    orphans = fi.Orphans(grace=30, report=report)
    orphans.add(proc.pid)
    t0 = time.monotonic()
    proc.wait()
    orphans.check(final=True)
    assert report.findings == [] and time.monotonic() - t0 < 10


def _faults(tmp_path, seed: int, n: int, warmup: int) -> None:
    args = ["--seed", str(seed), "--faults", str(n), "--warmup-faults", str(warmup),
            "--run-dir", str(tmp_path)]
    rc = fi.main(args)
    assert rc == 0, "findings above (stdout)"


@needs_proc
@needs_snakemake
@pytest.mark.slow
def test_three_random_faults_leave_every_dataset_as_an_uninterrupted_run(tmp_path):
    """The short version (CI runs it through .ci/run); makes its own reference run."""
    _faults(tmp_path, seed=1, n=3, warmup=1)


@needs_proc
@needs_snakemake
@pytest.mark.slow
def test_thirty_random_faults_leave_every_dataset_as_an_uninterrupted_run(tmp_path):
    _faults(tmp_path, seed=2, n=30, warmup=3)


def test_a_truncated_numba_cache_file_is_a_finding(tmp_path):
    pytest.importorskip("numba")
    (tmp_path / "kern.py").write_text(
        "from numba import njit\n\n\n@njit(cache=True)\ndef f(x):\n    return x + 1\n")
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}  # cache beside kern.py
    subprocess.run([sys.executable, "-c", "import kern; kern.f(1)"], cwd=tmp_path, check=True,
                   env=dict(env, PYTHONPATH=str(tmp_path)))
    report = fi.Report(seed=0, faults_asked=0)
    fi.check_cache(tmp_path, report)
    assert report.findings == []                          # a sound cache loads
    nbc = next(tmp_path.rglob("*.nbc"))
    nbc.write_bytes(nbc.read_bytes()[:100])               # what a full disk can leave
    fi.check_cache(tmp_path, report)
    assert len(report.findings) == 1 and "numba cache damaged" in report.findings[0]
