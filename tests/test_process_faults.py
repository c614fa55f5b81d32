"""Faults around a run, each ending in one line with nothing half-written: a killed
warm-up (parent or worker) ends within seconds and leaves no process behind; a second run of
a config while one runs is refused, the first unharmed; a results folder that cannot be
written stops the run before any job."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
import yaml
from conftest import ROOT, SRC
from test_pipeline import SNAKEMAKE, TINY, _copy_workflow, needs_snakemake

from vines.data.netcdf import unwritable_folder

#: the one output of the workflow runs below
TARGET = "results/tiny/timehistory/th.nc"

#: a warm-up task that records its worker's pid, then works for longer than any test waits
SLOW_TASK = '''import os, time
def task(model, simulation):
    open(os.path.join(os.environ["PIDS"], str(os.getpid())), "w").close()
    time.sleep(120)
'''
#: the pipeline's warm-up with two such tasks on two workers, its stamp in a temporary file
WARMUP = ["-c", "import sys, slow_task; from vines.pipeline import warmup as w; "
          "w.STAMP = w.Path(sys.argv.pop(1)); "
          "w.TASKS = {'a': (slow_task.task, ()), 'b': (slow_task.task, ())}; sys.exit(w.main())"]


def _gone(pid: int) -> bool:
    """True once ``pid`` has ended (a zombie that nobody reaps has ended too)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def _wait(condition, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.05)
    return condition()


@pytest.fixture
def warmup(tmp_path):
    """Start the warm-up; (its process, the pids of its two workers once both work)."""
    (tmp_path / "slow_task.py").write_text(SLOW_TASK)
    pids = tmp_path / "pids"
    pids.mkdir()
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(SRC), str(tmp_path)]),
           "PIDS": str(pids), "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    proc = subprocess.Popen([sys.executable, *WARMUP, str(tmp_path / "stamp"), "--model", "{}",
                             "--simulation", "{}", "--jobs", "2"], env=env, cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert _wait(lambda: len(list(pids.iterdir())) == 2, 120), proc.stderr
    workers = [int(p.name) for p in pids.iterdir()]
    yield proc, workers
    for pid in [proc.pid, *workers]:        # never leave a process of a failed test behind
        if not _gone(pid):
            os.kill(pid, signal.SIGKILL)
    proc.wait()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_workers_end_when_the_warmup_is_killed(warmup):
    """SIGKILL of the warm-up (a killed run): its workers end within seconds instead of
    waiting for tasks forever (each held ~490 MB for hours)."""
    proc, workers = warmup
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert _wait(lambda: all(_gone(pid) for pid in workers), 5), workers


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_warmup_fails_fast_in_one_line_when_a_worker_is_killed(warmup):
    proc, workers = warmup
    os.kill(workers[0], signal.SIGKILL)
    stdout, stderr = proc.communicate(timeout=10)
    assert proc.returncode == 1
    lines = stderr.splitlines()
    assert lines[-1].startswith("vines: warm-up stopped: one of its worker processes died")
    assert len(lines) == 2, stderr           # the warm-up's first line, then this one
    assert _wait(lambda: _gone(workers[1]), 5)


# ------------------------------------------------------------------ runs of the workflow

def _smk_cmd(run: Path, *targets) -> list[str]:
    return [SNAKEMAKE, "-c1", "--directory", str(run), "--snakefile", str(run / "Snakefile"),
            *targets, "--configfile", str(run / "cfg.yaml")]


@pytest.fixture
def run(tmp_path):
    """A copy of the workflow with a tiny config (one time history)."""
    _copy_workflow(tmp_path)
    (tmp_path / "cfg.yaml").write_text(yaml.safe_dump(TINY))
    return tmp_path


def _vines_lines(r) -> list[str]:
    out = r.stdout + r.stderr
    assert "Traceback" not in out and "LockException" not in out, out
    return [ln for ln in out.splitlines() if ln.startswith("vines pipeline:")]


def _start_and_hold_the_lock(run: Path) -> subprocess.Popen:
    """Start a run of ``TARGET``; return once it holds the directory's lock."""
    first = subprocess.Popen(_smk_cmd(run, TARGET), cwd=run, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)
    assert _wait(lambda: list((run / ".snakemake" / "locks").glob("*.lock")), 300)
    return first


@needs_snakemake
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_second_run_of_a_config_is_refused_in_one_line_and_the_first_completes(run):
    """Two runs of the same config at once: the second stops in one line naming the first
    (held still meanwhile, so that it cannot finish first); the first completes, and the
    line's remedy (the same command once it has ended) then works as written."""
    first = _start_and_hold_the_lock(run)
    os.killpg(first.pid, signal.SIGSTOP)
    try:
        second = subprocess.run(_smk_cmd(run, TARGET), cwd=run, capture_output=True,
                                text=True, timeout=300)
    finally:
        os.killpg(first.pid, signal.SIGCONT)
    assert second.returncode == 1
    (line,) = _vines_lines(second)
    assert line.startswith(f"vines pipeline: another Snakemake run is working in {run} "
                           f"(pid {first.pid}); wait for it to end, then run the same "
                           "command again: snakemake ")
    assert first.wait(timeout=600) == 0
    with xr.open_dataset(run / TARGET) as ds:
        assert ds.sizes
    assert not list((run / ".snakemake" / "locks").glob("*.lock"))
    again = subprocess.run(line.split("again: ", 1)[1], shell=True, cwd=run,
                           capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr


@needs_snakemake
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_lock_of_a_killed_run_is_named_with_the_command_that_lifts_it(run):
    first = _start_and_hold_the_lock(run)
    os.killpg(first.pid, signal.SIGKILL)
    first.wait()
    r = subprocess.run(_smk_cmd(run, TARGET), cwd=run, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 1
    (line,) = _vines_lines(r)
    prefix = (f"vines pipeline: {run} is locked by a run that was stopped (killed or lost); "
              "unlock it and run the same command again: ")
    assert line.startswith(prefix)
    remedy = subprocess.run(line[len(prefix):], shell=True, cwd=run, capture_output=True,
                            text=True, timeout=600)
    assert remedy.returncode == 0, remedy.stderr
    with xr.open_dataset(run / TARGET) as ds:
        assert ds.sizes


@needs_snakemake
def test_results_folder_that_cannot_be_written_stops_the_run_in_one_line(run):
    """A file where the results folder should be (what root cannot write through either, unlike
    a folder without write permission: the test runs as root here): one line before any job,
    nothing written."""
    (run / "results").write_text("in the way\n")
    r = subprocess.run(_smk_cmd(run, TARGET), cwd=run, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 1
    (line,) = _vines_lines(r)
    assert line == (f"vines pipeline: cannot write the results folder results/tiny: "
                    f"{run / 'results'} is a file, not a folder; make it writable (or move "
                    "what is in the way), then run the same command again")
    assert (run / "results").read_text() == "in the way\n"
    assert not (run / ".snakemake" / "locks").exists() or not list(
        (run / ".snakemake" / "locks").glob("*.lock"))


def test_unwritable_folder_names_the_folder(tmp_path, monkeypatch):
    """Which folder is in the way: a file on the path, or a folder (itself, an ancestor that
    would hold it, or one inside it) without write permission (os.access: as root only a
    read-only file system says so, hence the stand-in)."""
    (tmp_path / "file").write_text("")
    assert unwritable_folder(tmp_path / "file" / "run") == (
        f"{tmp_path / 'file'} is a file, not a folder")
    assert unwritable_folder(tmp_path / "new" / "run") is None
    (tmp_path / "res" / "run" / "logs").mkdir(parents=True)
    assert unwritable_folder(tmp_path / "res" / "run") is None
    locked = tmp_path / "res" / "run" / "logs"
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode: Path(p) != locked and real(p, mode))
    assert unwritable_folder(tmp_path / "res" / "run") == f"{locked} is not writable"
