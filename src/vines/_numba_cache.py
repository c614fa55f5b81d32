"""Invalidate vines' numba cache when a source its compiled code depends on changes.

numba keys a cached compiled function on the timestamp of that function's own file only:
functions of maps.py that inline functions of flow.py or _engine.py would keep stale machine
code after an edit (or a ``git pull``) of flow.py. At import, vines compares a hash of the
sources of the subpackages that hold compiled code (``COMPILED_SUBPACKAGES``: the numba
functions live there and use only their functions and constants; an edit of plotting, data,
pipeline or the CLI keeps the cache) with the stamp stored in the package's ``__pycache__`` and
deletes vines' numba cache files (``*.nbi``, ``*.nbc``) in every ``__pycache__`` when they differ; the next call recompiles (a few
seconds once). Read-only installs are left alone.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

STAMP = "numba-sources.sha256"
#: subpackages with numba functions; those functions inline code and constants of these only
COMPILED_SUBPACKAGES = ("core", "orbits")


def sources_hash(pkg_dir: Path) -> str:
    """sha256 over the paths and contents of the sources of ``COMPILED_SUBPACKAGES``."""
    h = hashlib.sha256()
    files = [f for sub in COMPILED_SUBPACKAGES for f in (pkg_dir / sub).rglob("*.py")]
    for f in sorted(files):
        h.update(f.relative_to(pkg_dir).as_posix().encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()


def refresh(pkg_dir=None) -> bool:
    """Delete stale cache files of ``pkg_dir`` (default: this package); True if deleted."""
    pkg_dir = Path(pkg_dir) if pkg_dir is not None else Path(__file__).resolve().parent
    cache = pkg_dir / "__pycache__"
    current = sources_hash(pkg_dir)
    try:
        if (cache / STAMP).read_text() == current:
            return False
    except OSError:
        pass
    removed = False
    for f in list(pkg_dir.rglob("__pycache__/*.nbi")) + list(pkg_dir.rglob("__pycache__/*.nbc")):
        try:
            f.unlink()
            removed = True
        except OSError:
            pass
    try:
        cache.mkdir(exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=cache, prefix=f".{STAMP}.")
        with os.fdopen(fd, "w") as fh:
            fh.write(current)
        os.replace(tmp, cache / STAMP)
    except OSError:
        pass
    return removed
