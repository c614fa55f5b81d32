"""Stale numba cache files are removed when any vines source changes."""
from vines._numba_cache import STAMP, refresh


def _pkg(tmp_path):
    (tmp_path / "flow.py").write_text("x = 1\n")
    (tmp_path / "maps.py").write_text("y = 2\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()
    for name in ("maps.f-10.py311.nbi", "maps.f-10.py311.1.nbc", "flow.cpython-311.pyc"):
        (cache / name).write_bytes(b"compiled")
    return cache


def test_cache_kept_while_sources_unchanged_and_dropped_after_a_change(tmp_path):
    cache = _pkg(tmp_path)
    refresh(tmp_path)                         # first import: no stamp yet -> clean start
    assert (cache / STAMP).exists()
    (cache / "maps.f-10.py311.nbi").write_bytes(b"compiled")
    assert refresh(tmp_path) is False         # unchanged sources keep the cache
    assert (cache / "maps.f-10.py311.nbi").exists()
    (tmp_path / "flow.py").write_text("x = 3\n")   # an inlined callee changes
    assert refresh(tmp_path) is True
    assert not list(cache.glob("*.nb[ic]"))
    assert (cache / "flow.cpython-311.pyc").exists()   # bytecode is Python's business
    assert refresh(tmp_path) is False
