"""vines.progress: loops report to the reporter of their context (none by default), only
the outermost task shows, a cancelled reporter stops loops and their pending pool work,
and a reporter changes no number."""
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import pytest

from vines import progress


class Recorder(progress.Reporter):
    """Every call shown to it, in order."""

    def __init__(self):
        super().__init__()
        self.calls = []

    def show_start(self, t):
        self.calls.append(("start", t.desc, t.total, t.unit))

    def show_advance(self, t):
        self.calls.append(("advance", t.desc, t.count))

    def show_end(self, t):
        self.calls.append(("end", t.desc, t.count))


def test_without_a_reporter_loops_run_unchanged():
    assert progress.current() is None
    assert list(progress.track(iter(range(5)), 5, "x")) == [0, 1, 2, 3, 4]
    with progress.task(3, "y"):
        progress.advance()
        progress.check()


def test_only_the_outermost_task_shows():
    rec = Recorder()
    with progress.reporting(rec):
        for _ in progress.track(range(2), 2, "outer", "points"):
            for _ in progress.track(range(3), 3, "inner"):   # silent, counted apart
                pass
    assert rec.calls == [("start", "outer", 2, "points"), ("advance", "outer", 1),
                         ("advance", "outer", 2), ("end", "outer", 2)]
    assert rec.tasks == [] and progress.current() is None


def test_the_reporter_is_local_to_its_context():
    seen = []
    with progress.reporting(Recorder()):
        t = threading.Thread(target=lambda: seen.append(progress.current()))
        t.start()
        t.join()
        assert progress.current() is not None
    assert seen == [None]         # a new thread (e.g. a pool's worker) reports nothing


def test_cancel_stops_a_loop_between_items():
    rec = Recorder()
    done = []
    with progress.reporting(rec), pytest.raises(progress.Cancelled):
        for i in progress.track(range(100), 100, "loop"):
            done.append(i)
            if i == 4:
                rec.cancel()
    assert done == [0, 1, 2, 3, 4]
    assert isinstance(progress.Cancelled(), KeyboardInterrupt)


def test_cancel_drops_the_pending_work_of_a_pool():
    rec, ran = progress.Reporter(), []

    def work(i):
        ran.append(i)
        time.sleep(0.01)
        return i

    with (progress.reporting(rec), pytest.raises(progress.Cancelled),
          ThreadPoolExecutor(max_workers=2) as ex):
        for i in progress.track(ex.map(work, range(400)), 400, "pool"):
            if i == 3:
                rec.cancel()
    # at most the items already running or queued ahead when the cancel came
    assert len(ran) < 50


def test_line_reporter_writes_every_tenth():
    lines = []
    with progress.reporting(progress.LineReporter(lines.append)):
        for _ in progress.track(range(256), 256, "census", "states"):
            pass
    assert lines[0] == "census: started (256 states)"
    assert "census 128/256 states (50 %)" in lines
    assert [ln.split("(")[-1] for ln in lines[1:-1]] == [f"{p} %)" for p in
                                                         (10, 20, 30, 40, 50, 60, 70, 80, 90)]
    assert lines[-1].startswith("census: 256 states in ")


def test_line_reporter_quiet_for_short_tasks():
    lines = []
    with progress.reporting(progress.LineReporter(lines.append, quiet_s=60.0)):
        for _ in progress.track(range(10), 10, "quick"):
            pass
    assert lines == []


def test_a_reporter_changes_no_census_number():
    from vines.attractors import census
    kw = dict(n=6, seed=3, t_end=400.0, t_transient=200.0, n_threads=2)
    plain = census(0.13, 1.0, 0.1, **kw).to_dict()
    rec = Recorder()
    with progress.reporting(rec):
        reported = census(0.13, 1.0, 0.1, **kw).to_dict()
    assert reported == plain
    assert rec.calls[0] == ("start", "census", 6, "states") and rec.calls[-1][0] == "end"
