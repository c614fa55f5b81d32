"""Parameter axes of the config and the split of a grid into chunks keyed by their values."""
from __future__ import annotations

import hashlib

import numpy as np

from ..core.params import PARAM_NAMES


class ConfigError(ValueError):
    """Invalid pipeline config; ``str(err)`` names the key path."""

    def __init__(self, key: str, message: str):
        self.key = key
        super().__init__(f"invalid config key '{key}': {message}")


def axis_values(spec, key: str = "axis") -> np.ndarray:
    """1-D float axis from a number, a list, {values: [...]} or {start, stop, num[, include]}.

    ``include`` adds exact values (e.g. F = 0.3077) to a linspace; the result is sorted and
    unique.
    """
    if isinstance(spec, (int, float)) and not isinstance(spec, bool):
        vals = np.array([float(spec)])
    elif isinstance(spec, list):
        vals = _distinct(spec, key)
    elif isinstance(spec, dict):
        if "values" in spec:
            vals = _distinct(spec["values"], f"{key}.values")
        else:
            vals = np.linspace(float(spec["start"]), float(spec["stop"]), int(spec["num"]))
        if spec.get("include"):
            vals = _include(vals, _distinct(spec["include"], f"{key}.include"))
    else:
        raise ConfigError(key, f"cannot read an axis from {spec!r}")
    vals = np.unique(vals)
    if vals.size == 0 or not np.all(np.isfinite(vals)):
        raise ConfigError(key, "axis must hold at least one finite value")
    return vals


def _include(vals: np.ndarray, extra: np.ndarray) -> np.ndarray:
    """``vals`` with the exact values ``extra`` added; a value of ``vals`` that an extra one
    equals to round-off (linspace(0.01, 1, 100) holds 0.09999999999999999, not 0.1) is
    replaced by it, not kept beside it as a second, near-duplicate grid row."""
    scale = float(np.max(np.abs(np.concatenate([vals, extra])), initial=1.0))
    near = np.abs(vals[:, None] - extra[None, :]) <= 1e-12 * scale
    return np.concatenate([vals[~near.any(axis=1)], extra])


def _distinct(values, key: str) -> np.ndarray:
    """The listed values as floats; a value listed twice is a ConfigError (a typo, and a
    duplicate point would be computed twice)."""
    vals = np.asarray(values, dtype=float)
    uniq, counts = np.unique(vals, return_counts=True)
    if np.any(counts > 1):
        raise ConfigError(key, f"values listed more than once: {uniq[counts > 1].tolist()}")
    return vals


def grid_axes(grid: dict, key: str = "grid") -> dict:
    """Axes of a grid config: swept ``axes`` and ``fixed`` values -> {dim: 1-D array}."""
    axes = {}
    for d in PARAM_NAMES:
        in_axes, in_fixed = d in grid.get("axes", {}), d in grid.get("fixed", {})
        if in_axes == in_fixed:
            raise ConfigError(f"{key}.{'axes' if in_fixed else 'fixed'}.{d}",
                              f"{d} must be given exactly once, in axes or in fixed")
        spec = grid["axes"][d] if in_axes else float(grid["fixed"][d])
        axes[d] = axis_values(spec, key=f"{key}.axes.{d}")
        if d in ("eta", "omega") and axes[d][0] <= 0 or axes[d][0] < 0:
            raise ConfigError(f"{key}.axes.{d}", f"{d} must be positive")
    return axes


def grid_chunks(axes: dict, chunk_size: int) -> list[dict]:
    """Cut the grid into sub-grids (cartesian products) of at most ``chunk_size`` points.

    Cuts go along the slowest axis in (eta, omega, F) order that has several values: groups
    of whole "rows" (all values of the faster axes), or, if one row alone is too big, the
    row is cut recursively along the next axis. Appending values to the slowest axis, or
    refining nothing but adding another grid, leaves existing chunks (and their files)
    unchanged.
    """
    chunk_size = max(1, int(chunk_size))
    out: list[dict] = []

    def rec(prefix: dict, rest: list):
        n = int(np.prod([axes[d].size for d in rest])) if rest else 1
        if n <= chunk_size:
            out.append({**prefix, **{d: axes[d].tolist() for d in rest}})
            return
        d, faster = rest[0], rest[1:]
        row = int(np.prod([axes[x].size for x in faster])) if faster else 1
        vals = axes[d].tolist()
        if row <= chunk_size:
            k = max(1, chunk_size // row)
            for i in range(0, len(vals), k):
                out.append({**prefix, d: vals[i:i + k], **{x: axes[x].tolist() for x in faster}})
        else:
            for v in vals:
                rec({**prefix, d: [v]}, faster)

    rec({}, list(PARAM_NAMES))
    return [{d: c[d] for d in PARAM_NAMES} for c in out]


def chunk_key(chunk: dict) -> str:
    """Name of a chunk: sha256 (16 hex digits) of its parameter values (exact float64)."""
    h = hashlib.sha256()
    for d in PARAM_NAMES:
        a = np.ascontiguousarray(np.asarray(chunk[d], dtype="<f8"))
        h.update(d.encode() + b":" + str(a.size).encode() + b":" + a.tobytes())
    return h.hexdigest()[:16]


def chunk_map(axes: dict, chunk_size: int) -> dict:
    """{chunk_key: chunk} in grid order."""
    return {chunk_key(c): c for c in grid_chunks(axes, chunk_size)}
