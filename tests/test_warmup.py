"""The numba warm-up before a run's first job (vines.pipeline.warmup): its stamp says warm
only for the sources, numba and CPU it was compiled for. (What the warm-up saves is a time,
measured by benchmarks/bench_pipeline.py on a fresh clone, cold and warm; not a test.)"""
import inspect
import time
from functools import partial

import pytest

import vines._numba_cache as numba_cache
from vines.pipeline import warmup


@pytest.fixture
def stamp(tmp_path, monkeypatch):
    path = tmp_path / "numba-warm.txt"
    monkeypatch.setattr(warmup, "STAMP", path)
    return path


def test_warm_only_for_the_stamped_sources(stamp, monkeypatch):
    assert not warmup.is_warm()                        # no stamp: compile
    stamp.write_text(warmup.warm_stamp())
    assert warmup.is_warm()
    real = numba_cache.sources_hash
    monkeypatch.setattr(numba_cache, "sources_hash", lambda pkg: "0" * 64)   # core/ edited
    assert not warmup.is_warm()
    monkeypatch.setattr(numba_cache, "sources_hash", real)
    stamp.write_text(warmup.warm_stamp().replace(" cpu ", " cpu other-"))    # another CPU
    assert not warmup.is_warm()


def test_warm_run_is_a_no_op(stamp, monkeypatch):
    stamp.write_text(warmup.warm_stamp())
    monkeypatch.setattr(warmup, "warm", lambda *a, **k: pytest.fail("compiled again"))
    assert warmup.main(["--model", "{}", "--simulation", "{}"]) == 0


def _record(path, model, simulation):
    """A warm-up task that records when it started and ended (in ``path``)."""
    start = time.monotonic()
    time.sleep(0.2)
    path.write_text(f"{start} {time.monotonic()}")


def test_tasks_start_after_the_tasks_whose_kernels_they_reuse(tmp_path, monkeypatch):
    """Every stage's kernels have a task, and a task that reuses another's kernels starts
    only once that one has finished (its kernels are then in the cache, not compiled twice),
    on one process and on several."""
    stages_called = " ".join(inspect.getsource(fn) for fn, _ in warmup.TASKS.values())
    for stage in ("compute_chunk", "compute_sweep", "timehistory", "basin_slice",
                  "simulate_exact", "robust_map", "lyapunov", "map_solve", "boundaries",
                  "stability_map", "orbit_atlas"):
        assert stage in stages_called, stage
    assert all(set(after) <= set(warmup.TASKS) for _, after in warmup.TASKS.values())
    for workers in (1, 2):
        files = {k: tmp_path / f"{k}-{workers}" for k in ("a", "b", "c")}
        monkeypatch.setattr(warmup, "TASKS", {"a": (partial(_record, files["a"]), ()),
                                              "b": (partial(_record, files["b"]), ("a",)),
                                              "c": (partial(_record, files["c"]), ())})
        warmup._run_tasks({}, {}, workers)
        times = {k: [float(x) for x in f.read_text().split()] for k, f in files.items()}
        assert times["b"][0] >= times["a"][1]


def test_shooting_task_compiles_what_continuation_calls():
    """The shooting task compiles ``codim1`` for the argument types continuation passes, so
    map_solve and boundaries after it compile no other specialization of it."""
    from vines.core.params import D_DEFAULT
    from vines.orbits.jets import kernels as shooting_kernels
    model = {"r": 0.65, "d": D_DEFAULT}
    simulation = {"t_end": 1000.0, "t_transient": 600.0, "v_stick": 1e-6,
                  "max_impacts": 2_000_000, "root_tol": 1e-13, "periodic_shortcut": True}
    warmup._shooting(model, simulation)
    compiled = list(shooting_kernels.codim1.signatures)
    assert len(compiled) == 1
    warmup._branches(model, simulation)
    assert list(shooting_kernels.codim1.signatures) == compiled
