"""Invalidate vines' numba cache when a source its compiled code depends on changes.

numba keys a cached compiled function on the timestamp of that function's own file only:
functions of maps.py that inline functions of flow.py or _engine.py would keep stale machine
code after an edit (or a ``git pull``) of flow.py. So vines keeps a stamp in the package's
``__pycache__``: a sha256 of the sources of the subpackages that hold compiled code
(``COMPILED_SUBPACKAGES``: the numba functions live there and use only their functions and
constants; an edit of plotting, data, pipeline or the CLI keeps the cache) and a cheap
fingerprint of the same files (paths, sizes, modification times: ``os.stat`` only).

At import, ``refresh`` compares the fingerprint (well under a millisecond): equal, nothing
else is done, so the check runs once per install or code change, not once per import.
Only when it differs (an edit, a checkout, a new install) are the sources hashed; if the
hash differs too, vines' numba cache files (``*.nbi``, ``*.nbc``) in every ``__pycache__``
are deleted and the next call recompiles (a few seconds once); a touched but unchanged
file only renews the stamp. A fingerprint is trusted only once every source is older than
two seconds (a file rewritten within the clock's granularity keeps its time stamp). Read-only
installs are left alone.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
import time
from pathlib import Path

STAMP = "numba-sources.sha256"
#: subpackages with numba functions; those functions inline code and constants of these only
COMPILED_SUBPACKAGES = ("core", "orbits", "multimode")
#: sources modified less than this long ago [ns] are hashed at every import until older
RACY_NS = 2_000_000_000


def kernel_sources(pkg_dir: Path) -> list[str]:
    """Paths (relative to ``pkg_dir``, sorted) of the .py files of COMPILED_SUBPACKAGES."""
    out = []
    todo = list(COMPILED_SUBPACKAGES)
    while todo:
        rel = todo.pop()
        with os.scandir(os.path.join(pkg_dir, rel)) as entries:
            for e in entries:
                if e.name.endswith(".py") and e.is_file():
                    out.append(f"{rel}/{e.name}")
                elif e.name != "__pycache__" and e.is_dir():
                    todo.append(f"{rel}/{e.name}")
    return sorted(out)


def sources_hash(pkg_dir: Path) -> str:
    """sha256 over the paths and contents of the sources of ``COMPILED_SUBPACKAGES``."""
    h = hashlib.sha256()
    for rel in kernel_sources(pkg_dir):
        h.update(rel.encode() + b"\0" + (pkg_dir / rel).read_bytes() + b"\0")
    return h.hexdigest()


def sources_fingerprint(pkg_dir: Path) -> tuple[str, int]:
    """(sha256 over the paths, inodes, sizes and modification times of the same sources,
    the newest modification time in ns)."""
    parts, newest = [], 0
    for rel in kernel_sources(pkg_dir):
        st = os.stat(os.path.join(pkg_dir, rel))
        parts.append(f"{rel}\0{st.st_ino}\0{st.st_size}\0{st.st_mtime_ns}")
        newest = max(newest, st.st_mtime_ns)
    return hashlib.sha256("\n".join(parts).encode()).hexdigest(), newest


def _read_stamp(path: Path) -> tuple[str, str]:
    """(sources hash, fingerprint) of the stamp; empty strings if absent or unreadable."""
    try:
        lines = path.read_text().split()
    except OSError:
        return "", ""
    return (lines + ["", ""])[0], (lines + ["", ""])[1]


def _write_stamp(cache: Path, digest: str, fingerprint: str) -> None:
    try:
        cache.mkdir(exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=cache, prefix=f".{STAMP}.")
        with os.fdopen(fd, "w") as fh:
            fh.write(f"{digest}\n{fingerprint}\n")
        os.replace(tmp, cache / STAMP)
    except OSError:
        pass


def refresh(pkg_dir=None) -> bool:
    """Delete stale cache files of ``pkg_dir`` (default: this package); True if deleted."""
    pkg_dir = Path(pkg_dir) if pkg_dir is not None else Path(__file__).resolve().parent
    cache = pkg_dir / "__pycache__"
    stored_hash, stored_fingerprint = _read_stamp(cache / STAMP)
    fingerprint, newest = sources_fingerprint(pkg_dir)
    if fingerprint == stored_fingerprint:
        return False
    if newest > time.time_ns() - RACY_NS:
        # a file modified this recently may change again within the clock's granularity
        # without changing its time stamp: do not trust the fingerprint yet (as git does)
        fingerprint = "-"
    current = sources_hash(pkg_dir)
    removed = False
    if current != stored_hash:
        for f in list(pkg_dir.rglob("__pycache__/*.nbi")) + list(pkg_dir.rglob("__pycache__/*.nbc")):
            try:
                f.unlink()
                removed = True
            except OSError:
                pass
    _write_stamp(cache, current, fingerprint)
    return removed
