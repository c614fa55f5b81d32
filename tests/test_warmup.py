"""The numba warm-up before a run's first job (vines.pipeline.warmup): its stamp says warm
only for the sources, numba and CPU it was compiled for. (What the warm-up saves is a time,
measured by benchmarks/bench_pipeline.py on a fresh clone, cold and warm; not a test.)"""
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
