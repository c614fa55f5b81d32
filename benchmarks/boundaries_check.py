"""Boundary curves against the stability map's class changes, and against older curves.

Run: PYTHONPATH=src python benchmarks/boundaries_check.py BOUNDARIES.nc STABILITY.nc
                                                          [--reference OLD_BOUNDARIES.nc]

1. Every pair of neighbouring cells of the stability map (a ``stability_map`` dataset at the
   same F) whose classes differ and that has a cell inside the curves' box is a class
   change; it is explained when a curve point lies within 1.5 cells of the pair's middle
   (the rule ``orbits.curves.boundaries`` seeds curves by). Prints how many are not, by class
   pair, and exits with status 1 if any is not.
2. With ``--reference``: for every curve of the reference dataset (e.g. computed before a
   change of the tracer) the largest distance of its points to the new curves of the same
   type, family and grazing (nearest point, and the curve: a cubic spline through the
   points, ``densified``), and the same the other way round, restricted to the box both
   datasets cover. Prints the largest of each: the curve distance is what tells whether
   the same curves are traced (a different step sequence along the same curve moves the
   points along it, up to a step).
"""
import argparse
import sys
from collections import Counter

import numpy as np
import xarray as xr

from vines.orbits.curves.one_to_one import class_edges


def curves_of(ds) -> list:
    """[(key, points (n, 2))] of a boundaries dataset; key = (type, family, flight, wall)."""
    ends = np.cumsum(ds["row_size"].values)
    pts = np.stack([ds["eta"].values, ds["omega"].values], axis=1)
    out = []
    for i, end in enumerate(ends):
        key = tuple(str(ds[q].values[i]) for q in ("curve_type", "family", "flight", "wall"))
        out.append((key, pts[end - ds["row_size"].values[i]:end]))
    return out


def in_box(pts, box) -> np.ndarray:
    (e0, e1), (w0, w1) = box
    return (pts[:, 0] >= e0) & (pts[:, 0] <= e1) & (pts[:, 1] >= w0) & (pts[:, 1] <= w1)


def unexplained(bnd, smap) -> tuple:
    """(class changes with a cell in the box, of them with both cells in the box, Counter
    of the unexplained by (class pair, both cells in the box))."""
    box = (tuple(bnd.attrs["eta_range"]), tuple(bnd.attrs["omega_range"]))
    pts = np.concatenate([p for _, p in curves_of(bnd)])
    n, n_both, bad = 0, 0, Counter()
    for a, b, cell, cls in class_edges(smap["eta"].values, smap["omega"].values,
                                       smap["cls"].values):
        inside = in_box(np.array([a, b]), box)
        if not inside.any():
            continue
        n, n_both = n + 1, n_both + bool(inside.all())
        mid = 0.5 * (np.asarray(a) + np.asarray(b))
        if np.min(np.hypot(*((pts - mid) / cell).T)) > 1.5:
            bad[(tuple(sorted(cls)), bool(inside.all()))] += 1
    return n, n_both, bad


def segment_distance(p, poly) -> float:
    """Distance of point p to the polyline poly (n, 2)."""
    if len(poly) == 1:
        return float(np.hypot(*(p - poly[0])))
    a, b = poly[:-1], poly[1:]
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab),
                                                               1e-300), 0.0, 1.0)
    return float(np.min(np.hypot(*(a + t[:, None] * ab - p).T)))


def densified(pts, per_segment=40) -> np.ndarray:
    """The cubic spline through the points (over the chord length), sampled per_segment
    times per segment: a polyline within ~h^4 of the curve (h the point spacing), so the
    distance to it measures the distance to the curve rather than the chord error."""
    from scipy.interpolate import CubicSpline
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    keep = np.concatenate([[True], np.diff(s) > 0.0])
    if keep.sum() < 4:
        return pts
    s, pts = s[keep], pts[keep]
    fine = np.concatenate([np.linspace(a, b, per_segment, endpoint=False)
                           for a, b in zip(s[:-1], s[1:], strict=False)] + [s[-1:]])
    return CubicSpline(s, pts, axis=0)(fine)


def distances(src, dst, box) -> list:
    """[(key, n points, max point distance, max distance to the curve)] of src's curves to
    dst's curves of the same key (points inside box only; the curve: ``densified``)."""
    out = []
    for key, pts in src:
        pts = pts[in_box(pts, box)]
        others = [p for k, p in dst if k == key]
        if not len(pts):
            continue
        if not others:
            out.append((key, len(pts), np.inf, np.inf))
            continue
        allo = np.concatenate(others)
        dp = max(float(np.min(np.hypot(*(allo - p).T))) for p in pts)
        dense = [densified(o) for o in others]
        ds = max(min(segment_distance(p, o) for o in dense) for p in pts)
        out.append((key, len(pts), dp, ds))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("boundaries")
    ap.add_argument("stability")
    ap.add_argument("--reference")
    args = ap.parse_args()
    bnd, smap = xr.open_dataset(args.boundaries), xr.open_dataset(args.stability)
    n, n_both, bad = unexplained(bnd, smap)
    n_bad_both = sum(v for (_, both), v in bad.items() if both)
    print(f"F = {bnd.attrs['F']}: {sum(bad.values())} of {n} class changes with a cell in the "
          f"box farther than 1.5 cells from a curve ({n_bad_both} of {n_both} with both cells "
          f"in the box) {dict(bad) if bad else ''}")
    if args.reference:
        ref = xr.open_dataset(args.reference)
        box = tuple(tuple(max(lo) if i == 0 else min(lo) for i, lo in enumerate(zip(*r, strict=False)))
                    for r in ((bnd.attrs["eta_range"], ref.attrs["eta_range"]),
                              (bnd.attrs["omega_range"], ref.attrs["omega_range"])))
        new, old = curves_of(bnd), curves_of(ref)
        for label, rows in (("reference -> new", distances(old, new, box)),
                            ("new -> reference", distances(new, old, box))):
            worst_p = max(r[2] for r in rows)
            worst_s = max(r[3] for r in rows)
            print(f"  {label}: {len(rows)} curves, max point distance {worst_p:.2e}, "
                  f"max distance to the curve {worst_s:.2e}")
            for key, npt, dp, ds in rows:
                if ds > 1e-6:
                    print(f"    {key}: {npt} points, point {dp:.2e}, curve {ds:.2e}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
