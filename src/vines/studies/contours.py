"""Contour geometry for the grid-resolution study: nested axes, level lines, areas, distances.

Pure numpy (and contourpy for the level lines): arrays in, arrays or numbers out. Lines are
lists of (k, 2) arrays of (x, y) vertices.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike


def nested_axis(lo: float, hi: float, n_fine: int, n: int) -> np.ndarray:
    """The n-point axis nested in linspace(lo, hi, n_fine): every (n_fine-1)/(n-1)-th value."""
    if n < 2 or (n_fine - 1) % (n - 1):
        raise ValueError(f"a grid of {n} points per axis is not nested in one of {n_fine}: "
                         f"(n_fine - 1) must be a multiple of (n - 1)")
    return np.linspace(lo, hi, n_fine)[::(n_fine - 1) // (n - 1)]


def contour_lines(x: ArrayLike, y: ArrayLike, z: ArrayLike, level: float) -> list[np.ndarray]:
    """Lines of z = level (z shape (len(y), len(x))) as (k, 2) arrays of (x, y) vertices."""
    import contourpy
    gen = contourpy.contour_generator(np.asarray(x, float), np.asarray(y, float),
                                      np.ma.masked_invalid(np.asarray(z, float)),
                                      name="serial", line_type="Separate")
    return [ln for ln in gen.lines(float(level)) if len(ln) >= 2]


def line_length(lines: list[np.ndarray]) -> float:
    """Total length of polylines."""
    return float(sum(np.hypot(*np.diff(p, axis=0).T).sum() for p in lines))


def area_above(x: ArrayLike, y: ArrayLike, z: ArrayLike, level: float) -> float:
    """Area of {z > level} in (x, y) units, from the filled contour (holes subtracted)."""
    import contourpy
    z = np.ma.masked_invalid(np.asarray(z, float))
    top = float(z.max()) if z.count() else level
    if not top > level:
        return 0.0
    gen = contourpy.contour_generator(np.asarray(x, float), np.asarray(y, float), z,
                                      name="serial", fill_type="OuterOffset")
    polys, offsets = gen.filled(float(level), np.nextafter(top, np.inf))
    area = 0.0
    for pts, off in zip(polys, offsets, strict=False):
        for a, b in zip(off[:-1], off[1:], strict=False):
            px, py = pts[a:b, 0], pts[a:b, 1]
            ring = 0.5 * abs(np.dot(px, np.roll(py, -1)) - np.dot(py, np.roll(px, -1)))
            area += ring if a == off[0] else -ring
    return area


def _sample_lines(lines, ds):
    """Points along polylines at most ``ds`` apart (piece midpoints) and their arc weights."""
    pts, wts = [], []
    for ln in lines:
        a, b = ln[:-1], ln[1:]
        seg = np.hypot(*(b - a).T)
        m = np.maximum(1, np.ceil(seg / ds).astype(int))
        rep = np.repeat(np.arange(seg.size), m)
        frac = (np.concatenate([np.arange(k) for k in m]) + 0.5) / m[rep]
        pts.append(a[rep] + frac[:, None] * (b - a)[rep])
        wts.append(seg[rep] / m[rep])
    if not pts:
        return np.zeros((0, 2)), np.zeros(0)
    return np.concatenate(pts), np.concatenate(wts)


def _dist_to_lines(p, lines, block=512):
    """Euclidean distance from each point of p (k, 2) to the nearest segment of ``lines``."""
    a = np.concatenate([ln[:-1] for ln in lines])
    b = np.concatenate([ln[1:] for ln in lines])
    ab = b - a
    ab2 = np.einsum("ij,ij->i", ab, ab)
    ab2 = np.where(ab2 > 0, ab2, 1.0)
    out = np.empty(len(p))
    for s in range(0, len(p), block):
        q = p[s:s + block, None, :]
        t = np.clip(np.einsum("kij,ij->ki", q - a, ab) / ab2, 0.0, 1.0)
        diff = q - (a + t[..., None] * ab)
        out[s:s + block] = np.sqrt(np.min(np.einsum("kij,kij->ki", diff, diff), axis=1))
    return out


def contour_distance(lines: list[np.ndarray], ref_lines: list[np.ndarray],
                     ds: float) -> tuple[float, float]:
    """(arc-length mean, max) distance from ``lines`` to ``ref_lines``, sampled every ``ds``.

    The max is the one-sided Hausdorff distance. NaN when either set of lines is empty.
    """
    if not lines or not ref_lines:
        return math.nan, math.nan
    p, w = _sample_lines(lines, ds)
    dist = _dist_to_lines(p, ref_lines)
    return float(np.sum(w * dist) / np.sum(w)), float(dist.max())
