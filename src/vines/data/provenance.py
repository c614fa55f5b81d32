"""Provenance of datasets: which code, config and libraries made them (no timestamps).

Global attributes record the vines version, the git commit of the sources (``-dirty`` when
tracked files were edited), the code version (sha256 of the sources the numbers depend on),
the sha256 of the config subset that produced the file (and the subset itself), the solver
settings and the versions of the libraries that computed it. Nothing here depends on the
time or the host, so rerunning a job rewrites a byte-identical file.
"""
from __future__ import annotations

import hashlib
import json
import subprocess
from pathlib import Path

import numpy as np

from .schema import CONVENTIONS


def config_sha256(subset) -> str:
    """sha256 of a JSON-able config subset (keys sorted, floats in repr form)."""
    blob = json.dumps(subset, sort_keys=True, separators=(",", ":"), default=_json_default)
    return hashlib.sha256(blob.encode()).hexdigest()


def _json_default(x):
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(f"not JSON-serialisable: {type(x).__name__}")


def git_commit(path=None) -> str:
    """Commit of the git checkout holding ``path`` (default: the running vines sources),
    or 'unknown' outside a checkout.

    A checkout with uncommitted changes to any tracked file (sources, workflow, config) gets
    a ``-dirty`` suffix.
    """
    where = Path(path) if path is not None else Path(__file__).resolve().parents[1]
    try:
        head = subprocess.run(["git", "-C", str(where), "rev-parse", "HEAD"], check=True,
                              capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(where), "status", "--porcelain",
                                "--untracked-files=no"], check=True,
                               capture_output=True, text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


#: libraries whose versions every dataset records (``library_versions``)
LIBRARIES = ("numpy", "scipy", "numba", "xarray", "netCDF4", "mpmath")


def library_versions() -> dict:
    """{'python': ..., 'numpy': ..., ...}: the versions that computed a dataset."""
    import importlib
    import platform
    out = {"python": platform.python_version()}
    for name in LIBRARIES:
        try:
            out[name] = importlib.import_module(name).__version__
        except ImportError:
            out[name] = "not installed"
    return out


def provenance_attrs(*, title: str, config_subset, settings: dict | None = None,
                     code_version: str = "", commit: str | None = None) -> dict:
    """Global attributes: CF conventions and provenance (deterministic: no timestamps)."""
    from .. import __version__
    versions = library_versions()
    attrs = {
        "Conventions": CONVENTIONS,
        "title": title,
        "source": f"vines {__version__}",
        "history": f"computed by vines {__version__} (code version {code_version or 'n/a'}) "
                   "from the config subset in the attribute 'config'",
        "vines_version": __version__,
        "git_commit": git_commit() if commit is None else commit,
        "code_version": code_version,
        "config_sha256": config_sha256(config_subset),
        "config": json.dumps(config_subset, sort_keys=True, default=_json_default),
        "library_versions": ", ".join(f"{k} {v}" for k, v in versions.items()),
    }
    for k, v in sorted((settings or {}).items()):
        attrs[f"solver_{k}"] = _attr_value(v)
    return attrs


def _attr_value(v):
    if v is None:
        return "none"
    if isinstance(v, bool):
        return int(v)
    if isinstance(v, (int, float, str, np.generic)):
        return v
    return json.dumps(v, sort_keys=True, default=_json_default)
