"""Stale numba cache files are removed when a source of the compiled subpackages changes."""
import re
from pathlib import Path

import vines
from vines._numba_cache import COMPILED_SUBPACKAGES, STAMP, refresh


def _pkg(tmp_path):
    for rel, text in (("core/flow.py", "x = 1\n"), ("orbits/maps.py", "y = 2\n"),
                      ("multimode/kernel.py", "k = 1\n"),
                      ("plotting/draw.py", "z = 3\n"), ("cli/common.py", "c = 4\n")):
        (tmp_path / rel).parent.mkdir(exist_ok=True)
        (tmp_path / rel).write_text(text)
    cache = tmp_path / "orbits" / "__pycache__"
    cache.mkdir()
    for name in ("maps.f-10.py311.nbi", "maps.f-10.py311.1.nbc", "maps.cpython-311.pyc"):
        (cache / name).write_bytes(b"compiled")
    return cache


def test_cache_kept_while_sources_unchanged_and_dropped_after_a_change(tmp_path):
    cache = _pkg(tmp_path)
    refresh(tmp_path)                         # first import: no stamp yet -> clean start
    assert (tmp_path / "__pycache__" / STAMP).exists()
    (cache / "maps.f-10.py311.nbi").write_bytes(b"compiled")
    assert refresh(tmp_path) is False         # unchanged sources keep the cache
    assert (cache / "maps.f-10.py311.nbi").exists()
    (tmp_path / "core" / "flow.py").write_text("x = 3\n")   # an inlined callee changes
    assert refresh(tmp_path) is True
    assert not list(cache.glob("*.nb[ic]"))
    assert (cache / "maps.cpython-311.pyc").exists()   # bytecode is Python's business
    assert refresh(tmp_path) is False


def test_edits_outside_the_compiled_subpackages_keep_the_cache(tmp_path):
    cache = _pkg(tmp_path)
    refresh(tmp_path)
    (cache / "maps.f-10.py311.nbi").write_bytes(b"compiled")
    (tmp_path / "plotting" / "draw.py").write_text("z = 4\n")
    (tmp_path / "cli" / "common.py").write_text("c = 5\n")
    assert refresh(tmp_path) is False
    assert (cache / "maps.f-10.py311.nbi").exists()


def test_every_module_with_numba_code_is_in_a_compiled_subpackage():
    """The stamp covers all compiled code: no numba function outside those subpackages."""
    pkg = Path(vines.__file__).parent
    compiled = [f.relative_to(pkg) for f in pkg.rglob("*.py")
                if re.search(r"@(numba\.|nb\.)?(njit|jit|vectorize|cfunc)\b|numba\.(njit|jit)\(",
                             f.read_text())]
    assert compiled, "no numba functions found: the pattern is wrong"
    outside = [str(f) for f in compiled if f.parts[0] not in COMPILED_SUBPACKAGES]
    assert not outside, f"numba code outside {COMPILED_SUBPACKAGES}: {outside}"



def test_unchanged_sources_are_not_read_again_and_a_touch_keeps_the_cache(tmp_path, monkeypatch):
    """Once stamped, an import only stats the sources (no hashing); a touched file whose
    content is unchanged (a checkout) renews the stamp and keeps the compiled code. Sources
    modified in the last RACY_NS are hashed at every import (``test_cache_kept_...``)."""
    import os

    import vines._numba_cache as nc
    cache = _pkg(tmp_path)
    for f in tmp_path.rglob("*.py"):          # sources older than RACY_NS: fingerprint trusted
        os.utime(f, ns=(f.stat().st_atime_ns, f.stat().st_mtime_ns - 10 * nc.RACY_NS))
    refresh(tmp_path)
    (cache / "maps.f-10.py311.nbi").write_bytes(b"compiled")
    real_hash, hashed = nc.sources_hash, []

    def counting_hash(pkg_dir):
        hashed.append(pkg_dir)
        return real_hash(pkg_dir)

    monkeypatch.setattr(nc, "sources_hash", counting_hash)
    assert refresh(tmp_path) is False and not hashed          # fingerprint matches: no read
    flow = tmp_path / "core" / "flow.py"
    st = flow.stat()
    os.utime(flow, ns=(st.st_atime_ns, st.st_mtime_ns + nc.RACY_NS))  # touch, same content
    assert refresh(tmp_path) is False
    assert len(hashed) == 1 and (cache / "maps.f-10.py311.nbi").exists()
    assert refresh(tmp_path) is False and len(hashed) == 1    # the renewed stamp matches
