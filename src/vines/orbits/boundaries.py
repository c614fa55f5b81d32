"""Curves of codimension-one points of 1:1 orbits in the (eta, omega) plane at fixed F.

``boundaries(F, eta_range, omega_range)``:

1. seeds: one-parameter continuations (``continuation.continue_branch``, arclength, with
   switching onto the asymmetric branches) along ``n_scan`` lines omega = const (in eta)
   and ``n_scan`` lines eta = const (in omega), from every 1:1 orbit the map solver finds
   at the line's start; their events on admissible orbits are the seeds (an
   admissibility-loss becomes the grazing closest to contact, ``augmented.grazing_guess``);
2. each seed not already on a traced curve of its kind is continued both ways with
   pseudo-arclength (``arclength.Tracer``) on its augmented system
   (``augmented.Codim1System``, free parameters eta and omega) until the curve leaves the
   box (the crossing is located), closes, or has ``max_points`` points per direction;
3. fold, flip, neimark-sacker and symmetry-breaking curves keep only their stretches on
   admissible orbits (elsewhere they are no edge of a stability class); neimark-sacker
   curves only where the crossing pair is complex (the second compound matrix also
   vanishes at real pairs lambda_1 lambda_2 = 1).

These curves are the edges of the classes of ``stability_map`` (Fig 16).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core.params import (D_DEFAULT, R_DEFAULT, ModelParams, ParameterError, check_int,
                           check_param, check_real)
from . import augmented as ag
from . import shooting as sh
from .arclength import Tracer
from .branches import is_ns, orbit_at

CURVE_TYPES = ("fold", "flip", "neimark-sacker", "symmetry-breaking", "grazing")
U_WEIGHT = 0.2          # weight of the orbit unknowns in the arclength (eta, omega: 1)


@dataclass
class Curve:
    """One traced curve: points (n, 2) of (eta, omega) and the full unknowns z (n, m)."""

    type: str
    family: str
    graze: tuple | None
    points: np.ndarray
    z: np.ndarray
    stopped: list = field(default_factory=list)

    def to_dict(self) -> dict:
        out = {"type": self.type, "family": self.family,
               "points": [[float(a), float(b)] for a, b in self.points]}
        if self.graze is not None:
            out["flight"], out["wall"] = int(self.graze[0]), self.graze[1]
        return out


@dataclass
class Boundaries:
    """The curves of one F (``boundaries``)."""

    F: float
    eta_range: tuple
    omega_range: tuple
    curves: list

    def to_dict(self) -> dict:
        return {"F": self.F, "eta_range": list(self.eta_range),
                "omega_range": list(self.omega_range),
                "curves": [c.to_dict() for c in self.curves]}


def _system(model, family, kind, graze, F):
    return ag.Codim1System(model, family, kind, ("eta", "omega"), {"F": F}, graze)


class _CurveTracer:
    """Continuation of one curve inside the box."""

    def __init__(self, system, box, step, max_points):
        self.sys, self.box, self.step, self.max_points = system, box, step, max_points

    def inside(self, z) -> bool:
        (e0, e1), (w0, w1) = self.box
        return e0 <= z[-2] <= e1 and w0 <= z[-1] <= w1

    def half(self, z0, sign):
        """Points from z0 (excluded) in one direction; (list of z, why it stopped)."""
        scale = np.full(len(z0), U_WEIGHT)
        scale[-2:] = 1.0
        d = np.zeros(len(z0))
        try:
            tr = Tracer(self.sys, z0, d, self.step, 1e-6, self.step, scale=scale)
        except (np.linalg.LinAlgError, ValueError):
            return [], "singular start"
        tr.t = sign * tr.tangent(self.sys(z0)[1], np.ones(len(z0)))
        out = []
        while len(out) < self.max_points:
            st = tr.step()
            if st is None:
                return out, "step below min_step"
            if not self.inside(st.z1):
                out.append(self._exit(tr, st))
                return [z for z in out if z is not None], "left the box"
            out.append(st.z1)
            if len(out) > 5 and np.hypot(*(st.z1[-2:] - z0[-2:])) < 0.5 * tr.h:
                return out, "closed"
        return out, "max_points"

    def _exit(self, tr, st):
        """The point where the step leaves the box (None if it cannot be located)."""
        (e0, e1), (w0, w1) = self.box
        z = st.z1
        for k, lo, hi in ((-2, e0, e1), (-1, w0, w1)):
            if z[k] > hi or z[k] < lo:
                b = hi if z[k] > hi else lo
                loc = tr.locate(st, lambda zz, t, k=k, b=b: zz[k] - b, st.z0[k] - b, z[k] - b)
                return None if loc is None else loc[1]
        return None


def trace(model, family, kind, graze, z0, F, box, step=0.01, max_points=400) -> Curve:
    """The curve through z0 = (u, [s_g], eta, omega) of the augmented system, both ways."""
    system = _system(model, family, kind, graze, F)
    ct = _CurveTracer(system, box, step, max_points)
    fwd, why_f = ct.half(np.asarray(z0, float), 1.0)
    bwd, why_b = ct.half(np.asarray(z0, float), -1.0)
    zs = np.array(bwd[::-1] + [np.asarray(z0, float)] + fwd)
    (e0, e1), (w0, w1) = box
    tol = 1e-9
    inside = (zs[:, -2] >= e0 - tol) & (zs[:, -2] <= e1 + tol) & (zs[:, -1] >= w0 - tol) \
        & (zs[:, -1] <= w1 + tol)
    zs = zs[inside]          # a located exit can overshoot when its correction fails
    return Curve(kind, family, graze, zs[:, -2:].copy(), zs, [why_b, why_f])


def _keep(curve: Curve, model, F) -> list:
    """The stretches of a curve that are class edges (module docstring, step 3)."""
    if curve.type == "grazing":
        return [curve]
    ok = []
    for z in curve.z:
        p = ModelParams(eta=z[-2], omega=z[-1], F=F, r=model.r, d=model.d, phi=model.phi)
        o = orbit_at(p, curve.family, z[:sh.N_UNKNOWNS[curve.family]])
        good = o is not None and o.admissible
        if good and curve.type == "neimark-sacker":
            good = is_ns(curve.family, o, tol=1e-6)
        ok.append(good)
    ok = np.array(ok, bool)
    pieces = []
    start = None
    for i, g in enumerate(list(ok) + [False]):
        if g and start is None:
            start = i
        elif not g and start is not None:
            if i - start >= 2:
                sl = slice(start, i)
                pieces.append(Curve(curve.type, curve.family, curve.graze,
                                    curve.points[sl], curve.z[sl], curve.stopped))
            start = None
    return pieces


def crossings(curve: Curve, model, F, omega: float) -> list:
    """Exact eta values where the curve crosses omega = const (square system in eta)."""
    out = []
    w = curve.z[:, -1] - omega
    for i in np.nonzero(np.sign(w[:-1]) * np.sign(w[1:]) < 0)[0]:
        f = w[i] / (w[i] - w[i + 1])
        z = curve.z[i] + f * (curve.z[i + 1] - curve.z[i])
        system = ag.Codim1System(model, curve.family, curve.type, ("eta",),
                                 {"F": F, "omega": omega}, curve.graze)
        zs = ag.solve(system, z[:-1])
        if zs is not None:
            out.append(float(zs[-1]))
    return out


def boundaries(F, eta_range, omega_range, r=R_DEFAULT, d=D_DEFAULT, n_scan=5, step=0.01,
               max_points=400) -> Boundaries:
    """Codimension-one curves of 1:1 orbits in the box eta_range x omega_range at F."""
    F = check_param("F", F)
    box = (_range("eta_range", eta_range), _range("omega_range", omega_range))
    n_scan = check_int("n_scan", n_scan, lo=1, hi=100)
    step = check_real("step", step, lo=1e-5, hi=1.0)
    max_points = check_int("max_points", max_points, lo=1, hi=100_000)
    model = sh.Model(r, d)
    curves = []
    for seed in _seeds(model, F, box, n_scan):
        family, kind, graze, z0 = seed
        if _on_curve(curves, seed, step):
            continue
        c = trace(model, family, kind, graze, z0, F, box, step, max_points)
        c.all_points = c.points
        curves.append(c)
    kept = []
    for c in curves:
        kept.extend(_keep(c, model, F))
    return Boundaries(F, box[0], box[1], kept)


def _range(name, value) -> tuple:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be two numbers lo < hi") from None
    q = name.split("_")[0]
    try:
        lo, hi = check_param(q, lo), check_param(q, hi)
    except ParameterError as err:
        raise ParameterError(name, list(value), f"{err.allowed} (both ends)") from None
    if not lo < hi:
        raise ParameterError(name, value, "must be two numbers lo < hi")
    return lo, hi


def _on_curve(curves, seed, step) -> bool:
    family, kind, graze, z0 = seed
    # the mirror image of an asymmetric orbit swaps its flights: one curve for both
    key = (family, kind, None if graze is None else graze[1])
    for c in curves:
        if (c.family, c.type, None if c.graze is None else c.graze[1]) == key:
            if np.min(np.hypot(*(c.all_points - z0[-2:]).T)) < 3.0 * step:
                return True
    return False


def _seeds(model, F, box, n_scan):
    """(family, kind, graze, z0) from one-parameter scans (module docstring, step 1)."""
    from .continuation import continue_branch
    from .periodic import find_1to1
    (e0, e1), (w0, w1) = box
    lines = [("eta", e0, e1, {"omega": w, "F": F}) for w in np.linspace(w0, w1, n_scan)]
    lines += [("omega", w0, w1, {"eta": e, "F": F}) for e in np.linspace(e0, e1, n_scan)]
    for param, start, stop, fixed in lines:
        p = dict(fixed, **{param: start})
        orbits = find_1to1(p["eta"], p["omega"], F, r=model.r, d=model.d, simulation=False)
        for kind in ("symmetric", "asymmetric"):
            cands = [o for o in orbits if o.symmetric == (kind == "symmetric")]
            for o in cands[:1 if kind == "asymmetric" else 2]:
                br = continue_branch(param, start, stop, (stop - start) / 50.0, fixed,
                                     orbit=o, r=model.r, d=model.d, branch=kind,
                                     switch=kind == "symmetric", max_inadmissible=20,
                                     max_points=2000)
                for b in [br] + br.switched:
                    yield from _branch_seeds(model, b, param, fixed, F)


def _branch_seeds(model, br, param, fixed, F):
    for ev in br.events:
        o = br.orbits[ev["index"]]
        typ = ev["type"]
        if typ == "symmetry-breaking" and br.kind == "asymmetric":
            continue
        z = np.asarray(ev["z"], float)
        par = dict(fixed, **{param: float(z[-1])})
        u = list(z[:-1])
        graze, extra = None, []
        if typ == "admissibility-loss":
            graze, s_g, margin = ag.grazing_guess(model, br.kind, u, par)
            if margin > 1e-3:
                continue
            extra = [] if graze[1] == "arrival" else [s_g]
            typ = "grazing"
        elif not o.admissible:
            continue
        z0 = np.array(u + extra + [par["eta"], par["omega"]])
        system = ag.Codim1System(model, br.kind, typ, (param,),
                                 {q: v for q, v in par.items() if q != param}, graze)
        zs = ag.solve(system, z0[:-1] if param == "eta" else np.append(z0[:-2], z0[-1]))
        if zs is None:
            continue
        z0[:-2] = zs[:-1]
        z0[-2 if param == "eta" else -1] = zs[-1]
        yield br.kind, typ, graze, z0
