"""Faults of the processes around a run: a killed warm-up (parent or worker) ends within
seconds, with one line, and leaves no process behind."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import ROOT, SRC

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
