"""Differential checks of the exact solver against the independent references (issue 41).

Used by ``tests/test_differential_fuzz.py``. A draw is a parameter point, a start state
and a horizon; ``compare`` runs the exact solver (``core.exact.run_exact``, no periodic
shortcut) and a reference (the DOP853 event loop ``run_rk`` at rtol 1e-12, or the
40-digit ``reference_run`` on short horizons) and compares their impact sequences within a
bound from the reference's tolerance and the problem's conditioning; where they part, the
draw is classed by why the reference cannot be trusted there, or fails as a mismatch.
``invariants`` checks what every exact run must satisfy whatever the reference says.

Conditioning: the exact solver is rerun from two start states perturbed by ``EPS_PERT``
(displacements of LO and ball together and both velocities: w0 is kept, so a start on a
wall stays valid); A_k = max_{j <= k} |dt_j| / EPS_PERT (at least 1) is the amplification
of a state error into the time of impact k. An error of the reference per impact of
``tau`` (its tolerance times the state's scale) grows at most like (k + 1) tau A_k.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from hypothesis import strategies as st

from vines.core.exact import run_exact
from vines.core.params import MAX_GAIN, ModelParams, ParameterError, SolverSettings
from vines.reference.hiprec import reference_run
from vines.reference.rk import run_rk

EPS_PERT = 1e-9          # start-state perturbation of the sensitivity runs
RK_RTOL = 1e-12          # the RK reference's tolerance (atol = rtol 1e-2, its default)
MAX_IMPACTS = 2000       # per draw: beyond, an accumulation the references cannot follow
#                           at a bounded cost (r near 1 resolves ~log(1e6)/(1 - r) impacts
#                           per chatter sequence): "chatter"
MP_MAX_IMPACTS = 200     # the 40-digit reference: its cost grows with the events
TRUST = 1e-5             # beyond this predicted error the comparison stops: "sensitive"
GAP_AMBIGUOUS = 1e-7     # a near miss closer than this to a wall (an impact for the other
#                           solver) is a grazing contact


@dataclass(frozen=True)
class RefKind:
    """What limits a comparison with one reference: ``tau`` the error per impact in time
    per unit state scale, ``depth`` the accuracy of positions (per unit scale) near a wall,
    ``chatter_dt`` the shortest return to a wall it is sure to resolve."""

    tau: float
    depth: float
    chatter_dt: float


REFS = {
    # DOP853 at rtol 1e-12: measured 3e-9..5e-9 over ~100 impacts at scale ~1
    # (tests/test_exact_vs_rk.py), i.e. ~50 rtol per impact; positions to ~rtol per step
    "rk": RefKind(tau=100.0 * RK_RTOL, depth=1e3 * RK_RTOL, chatter_dt=0.0),
    # 40 digits: the error is the exact solver's own, round-off of the closed form
    # (8 eps per evaluation, a few hundred evaluations per impact); the reference samples
    # every H_SAMPLE_DEFAULT = 0.05 and may miss a return to a wall within one interval
    "mp": RefKind(tau=1e3 * 2.2e-16, depth=1e3 * 2.2e-16, chatter_dt=2 * 0.05),
}

#: classes of a draw; every draw gets exactly one (``Outcome.cls``)
CLASSES = ("agree", "refused", "sensitive", "grazing", "chatter", "ref_failed")


@dataclass(frozen=True)
class Draw:
    """One differential case: model parameters, start state, horizon (t_end)."""

    eta: float
    omega: float
    F: float
    r: float
    d: float
    phi: float
    state0: tuple
    t_end: float

    def params(self) -> ModelParams:
        return ModelParams(eta=self.eta, omega=self.omega, F=self.F, r=self.r, d=self.d,
                           phi=self.phi)

    def settings(self) -> SolverSettings:
        return SolverSettings(t_end=self.t_end, t_transient=0.5 * self.t_end,
                              state0=self.state0, max_impacts=MAX_IMPACTS)


@dataclass
class Outcome:
    """Class of a draw, impacts compared, and the worst error / bound ratio among them."""

    cls: str
    reason: str = ""
    n_compared: int = 0
    worst_ratio: float = 0.0
    detail: dict = field(default_factory=dict)


# ------------------------------------------------------------------------------ drawing

def _log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda x: 10.0 ** x)


def _with_edges(edges, body):
    return st.one_of(st.sampled_from(edges), body)


@st.composite
def draws(draw, t_end=60.0):
    """A draw over the documented domain, edges included (docs/model.md, ``core.params``):
    eta 1e-4..10, omega 0.05..8, F 0..10, r 0..1 (0 and 1 themselves), d 0..3 (0, the
    default, critical damping 2), any phase, start states inside the cavity: at rest, on a
    wall, a near-grazing start (a whisker from a wall, slowly approaching it) or anywhere."""
    eta = draw(_with_edges([1e-4, 10.0, 0.05, 0.2], _log_uniform(1e-4, 10.0)))
    omega = draw(_with_edges([1.0, 0.05, 8.0], _log_uniform(0.05, 8.0)))
    F = draw(_with_edges([0.0, 10.0, 0.05], _log_uniform(1e-3, 10.0)))
    r = draw(_with_edges([0.0, 1.0, 0.65], st.floats(0.0, 1.0)))
    d = draw(_with_edges([0.0, 0.011998, 2.0], _log_uniform(1e-4, 3.0)))
    phi = draw(st.floats(-math.pi, math.pi))
    kind = draw(st.sampled_from(("rest", "wall", "graze", "any")))
    zb = draw(st.floats(-2.0, 2.0))
    if kind == "rest":
        s0 = (0.0, 0.0, 0.0, 0.0)
    elif kind == "wall":
        wall = draw(st.sampled_from((-1.0, 1.0)))
        s0 = (zb + wall, draw(st.floats(-2.0, 2.0)), zb, draw(st.floats(-2.0, 2.0)))
    elif kind == "graze":
        wall = draw(st.sampled_from((-1.0, 1.0)))
        gap = draw(_log_uniform(1e-12, 1e-3))
        vm = draw(st.floats(-1.0, 1.0))
        dv = draw(_log_uniform(1e-9, 1e-3))             # slowly towards the wall
        s0 = (zb + wall * (1.0 - gap), vm + wall * dv, zb, vm)
    else:
        w0 = draw(st.floats(-1.0, 1.0))
        s0 = (zb + w0, draw(st.floats(-3.0, 3.0)), zb, draw(st.floats(-3.0, 3.0)))
    return Draw(eta, omega, F, r, d, phi, s0, t_end)


# --------------------------------------------------------------------------- invariants

def _forcing(p: ModelParams, t):
    a = p.omega * t + p.phi
    return p.F * np.sin(a) + p.d * p.omega * p.F * np.cos(a)


_GL_X, _GL_W = np.polynomial.legendre.leggauss(20)


def _gauss(f, a: float, b: float, piece: float) -> float:
    """Integral of the smooth f over [a, b] by 20-point Gauss-Legendre on pieces <= piece."""
    if b <= a:
        return 0.0
    n = max(1, math.ceil((b - a) / piece))
    edges = np.linspace(a, b, n + 1)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    t = (mid[:, None] + half[:, None] * _GL_X[None, :]).ravel()
    return float(np.sum(f(t).reshape(n, -1) * _GL_W[None, :] * half[:, None]))


def _energy(p: ModelParams, y) -> np.ndarray:
    """Mechanical energy (LO kinetic + spring + ball kinetic), M = 1."""
    return 0.5 * (y[1] ** 2 + y[0] ** 2) + 0.5 * p.eta * y[3] ** 2


def closed_form_gain(p: ModelParams) -> float:
    """Largest 1/|1 - m omega^2 + i d omega| of the free LO (m = 1) and the stuck body
    (m = 1 + eta), at most the exact solver's MAX_GAIN (undamped near-resonant points use a
    form without cancellation)."""
    g = max(1.0 / max(abs(complex(1.0 - m * p.omega ** 2, p.d * p.omega)), 1e-300)
            for m in (1.0, 1.0 + p.eta))
    return min(g, MAX_GAIN)


def invariants(p: ModelParams, st_: SolverSettings, raw) -> dict:
    """Assert the exact run's invariants and return their worst values.

    * |w| <= 1 (w = z_m - z_b) on a grid of step 1e-2 and just after every impact, to the
      round-off of w: 8 eps (1 + |z_m| + |z_b|) plus root_tol;
    * at every impact momentum v_m + eta v_b is conserved (to round-off) and the relative
      velocity after it is -r w'- (bounce) or 0 (stick);
    * energy over the window [t_transient, t_end]: E(t_end) - E(t_transient) = work of the
      forcing - d int z_m'^2 (the kernel's ``int_vm2``) - impact losses
      eta/(1 + eta) (w'-^2 - w'+^2)/2, the work by Gauss-Legendre between impacts; and
      d int z_m'^2 itself against the same quadrature.
    """
    eps = 2.220446049250313e-16
    t_last = raw.t_last
    imp = raw.impacts
    grid = np.linspace(0.0, t_last, max(2, int(t_last / 1e-2) + 1))
    imp = imp[imp["t"] < t_last]        # a run stopped at max_impacts ends on an impact
    y = raw.state_at(np.concatenate([grid, imp["t"]]))
    # round-off of w: of z_m, z_b and of the closed form's parts (F gain, see below)
    parts = p.F * (1.0 + p.omega) * closed_form_gain(p)
    w_tol = 8 * eps * (1.0 + np.abs(y[0]) + np.abs(y[2]) + parts) + st_.root_tol
    w_excess = float(np.max(np.abs(y[0] - y[2]) - 1.0 - w_tol))
    assert w_excess <= 0.0, f"|w| exceeds 1 by {w_excess:.3g} beyond round-off"
    post = y[:, grid.size:]
    mu = p.eta / (1.0 + p.eta)
    if imp.size:
        # round-off: the impact law's, and the closed form's restart from the post-impact
        # state (its parts reach F gain omega, ``core.params.check_conditioning``)
        mom_pre = imp["v_m"] + p.eta * imp["v_b"]
        mom_post = post[1] + p.eta * post[3]
        scale = np.abs(imp["v_m"]) + p.eta * np.abs(imp["v_b"]) + parts
        mom_err = float(np.max(np.abs(mom_post - mom_pre) / (8 * eps * (1.0 + scale))))
        assert mom_err <= 1.0, f"momentum not conserved at an impact (x{mom_err:.3g} round-off)"
        dw_pre, dw_post = imp["v_m"] - imp["v_b"], post[1] - post[3]
        tol = 8 * eps * (1.0 + np.abs(imp["v_m"]) + np.abs(imp["v_b"]) + parts) * (1 + p.eta)
        bounce = np.abs(dw_post + p.r * dw_pre) <= tol
        stick = np.abs(dw_post) <= tol
        assert np.all(bounce | stick), "relative velocity after an impact is neither -r w' nor 0"
    balance = _energy_balance(p, st_, raw, imp, post, mu)
    return {"w_excess": w_excess, **balance}


def _energy_balance(p, st_, raw, imp, post, mu) -> dict:
    a, b = st_.t_transient, raw.t_last
    if b <= a:
        return {}
    win = (imp["t"] >= a) & (imp["t"] <= b)
    starts = raw.state_at.segments[:, 0]   # impacts, sticks, releases: kinks of z_m'
    starts = starts[(starts > a) & (starts < b)]
    cuts = np.unique(np.concatenate([[a], starts, imp["t"][win], [b]]))
    scale_t = min(0.25, 0.25 / p.omega)

    def power(t):
        s = raw.state_at(t)
        return s[1] * _forcing(p, t)

    def v2(t):
        return raw.state_at(t)[1] ** 2

    work = sum(_gauss(power, c0, c1, scale_t) for c0, c1 in zip(cuts[:-1], cuts[1:], strict=True))
    vm2 = sum(_gauss(v2, c0, c1, scale_t) for c0, c1 in zip(cuts[:-1], cuts[1:], strict=True))
    dw_pre = imp["v_m"][win] - imp["v_b"][win]
    dw_post = post[1][win] - post[3][win]
    loss = float(np.sum(0.5 * mu * (dw_pre ** 2 - dw_post ** 2)))
    e_a, e_b = _energy(p, raw.state_at([a, b]))
    damp = p.d * raw.int_vm2
    terms = abs(e_a) + abs(e_b) + abs(work) + abs(damp) + abs(loss)
    resid = e_b - e_a - work + damp + loss
    # round-off of the closed form and of the sums: 1e-12 of the terms per 1000 events
    tol = 1e-9 * (1.0 + imp.size / 1e3) * (1.0 + terms)
    assert abs(resid) <= tol, f"energy balance off by {resid:.3g} (terms {terms:.3g})"
    assert abs(raw.int_vm2 - vm2) <= tol + 1e-12 * vm2 * 1e3, \
        f"int z_m'^2 {raw.int_vm2!r} against quadrature {vm2!r}"
    return {"energy_resid": resid / (1.0 + terms), "vm2_rel": abs(raw.int_vm2 - vm2) / (1 + vm2)}


# --------------------------------------------------------------------------- comparison

def _sensitivity(p, st_, raw) -> tuple[np.ndarray, int]:
    """A_k for the exact run's impacts and the first index where a perturbed run's wall
    sequence departs from it (len(impacts) if never)."""
    imp = raw.impacts
    amp = np.ones(imp.size)
    split = imp.size
    for u in ((1.0, 0.6, 1.0, -0.8), (-0.7, -0.9, -0.7, 0.5)):
        s0 = tuple(x + EPS_PERT * ui for x, ui in zip(st_.state0, u, strict=True))
        if abs(s0[0] - s0[2]) > 1.0:
            continue
        other = run_exact(p, SolverSettings(t_end=st_.t_end, t_transient=st_.t_transient,
                                            v_stick=st_.v_stick, root_tol=st_.root_tol,
                                            max_impacts=st_.max_impacts, state0=s0)).impacts
        n = min(imp.size, other.size)
        same = imp["wall"][:n] == other["wall"][:n]
        k = int(np.argmin(same)) if not same.all() else n
        split = min(split, k)
        dt = np.abs(imp["t"][:k] - other["t"][:k]) / EPS_PERT
        amp[:k] = np.maximum(amp[:k], np.maximum.accumulate(dt) if k else dt)
        amp[k:] = np.inf
    return amp, split


def _state_scale(raw, t_end) -> float:
    y = raw.state_at(np.linspace(0.0, min(raw.t_last, t_end), 2001))
    return float(np.max(np.abs(y)))


def _near_graze(raw, wall, t, scale) -> bool:
    """Does ``raw``'s trajectory come within GAP_AMBIGUOUS x scale of ``wall`` near t
    without an impact (a grazing approach the other solver counted)?"""
    lo, hi = max(0.0, t - 0.3), min(raw.t_last, t + 0.3)
    tt = np.linspace(lo, hi, 6001)
    y = raw.state_at(tt)
    gap = 1.0 - wall * (y[0] - y[2])
    return float(np.min(gap)) <= GAP_AMBIGUOUS * (1.0 + scale)


def _ambiguous(imps, k, scale, p, ref) -> str:
    """"chatter", "grazing" or "" for impact k of ``imps``: an approach whose depth beyond
    the wall, w'^2 / (2 |w''|), is within 1e3 x the reference's position accuracy
    (``RefKind.depth``), so that whether and when it happens is ambiguous; "chatter" when it
    is part of an accumulation (the same wall as the impact before), or for the 40-digit
    reference an impact within two of its sample intervals of the one before at the same
    wall (a return it may not sample). |w''| <= |z_m''| <= F (1 + d omega) + (1 + d) scale."""
    if k < 0 or k >= imps.size:
        return ""
    dw = abs(imps["v_m"][k] - imps["v_b"][k])
    acc = p.F * (1.0 + p.d * p.omega) + (1.0 + p.d) * scale
    same = k > 0 and imps["wall"][k] == imps["wall"][k - 1]
    if same and imps["t"][k] - imps["t"][k - 1] < ref.chatter_dt:
        return "chatter"
    if dw * dw <= 2.0 * acc * 1e3 * ref.depth * (1.0 + scale):
        return "chatter" if same else "grazing"
    return ""


def compare(dr: Draw, reference: str = "rk") -> Outcome:
    """Run the exact solver and ``reference`` ("rk" or "mp") on ``dr`` and class the draw."""
    try:
        p = dr.params()
        st_ = dr.settings()
        raw = run_exact(p, st_)
    except ParameterError as err:        # near-resonant weakly damped points: documented
        return Outcome("refused", f"exact solver refuses: {err}")
    inv = invariants(p, st_, raw)
    assert raw.status in ("ok", "max_impacts"), f"exact run {raw.status} at t = {raw.t_last}"
    if raw.status != "ok":                   # an accumulation of impacts without sticking
        return Outcome("chatter", f"exact run stopped: {raw.status}", detail=inv)
    if reference == "mp" and raw.n_impacts > MP_MAX_IMPACTS:
        return Outcome("chatter", f"{raw.n_impacts} impacts: beyond the 40-digit reference's "
                       "budget", detail=inv)
    try:
        if reference == "rk":
            ref_imp = run_rk(p, st_, rtol=RK_RTOL)
            if ref_imp.status == "max_impacts":
                return Outcome("chatter", "the RK reference resolves more than "
                               f"{MAX_IMPACTS} impacts", detail=inv)
            if ref_imp.status != "ok":
                return Outcome("ref_failed", f"RK status {ref_imp.status}", detail=inv)
            ref, ref_raw = ref_imp.impacts, ref_imp
        else:
            ref, ref_raw = reference_run(p, st_).impacts, None
    except (ParameterError, ValueError, RuntimeError) as err:
        return Outcome("ref_failed", f"reference refuses: {err}", detail=inv)
    return _compare_sequences(p, st_, raw, ref, ref_raw, REFS[reference], inv)


def _compare_sequences(p, st_, raw, ref, ref_raw, kind, inv) -> Outcome:
    ex = raw.impacts
    t_cmp = st_.t_end - 1.0        # an impact near the end may fall beyond it for one solver
    n = max(int(np.sum(ex["t"] <= t_cmp)), int(np.sum(ref["t"] <= t_cmp)))
    amp, split = _sensitivity(p, st_, raw)
    scale = _state_scale(raw, st_.t_end)
    bound = kind.tau * (1.0 + scale) * (1.0 + np.arange(ex.size)) * amp
    worst = 0.0
    for k in range(n):
        if k < ex.size and bound[k] > TRUST:
            return Outcome("sensitive", f"predicted error {bound[k]:.2g} at impact {k} "
                           f"(amplification {amp[k]:.2g})", k, worst, inv)
        if k >= split:
            return Outcome("sensitive", f"a start {EPS_PERT:g} away changes the wall "
                           f"sequence at impact {k}", k, worst, inv)
        same = (k < ex.size and k < ref.size and ex["wall"][k] == ref["wall"][k])
        err = abs(ex["t"][k] - ref["t"][k]) if same else math.inf
        if same and err <= bound[k]:
            worst = max(worst, err / bound[k])
            continue
        return _class_split(p, raw, ref, ref_raw, kind, ex, k, scale, worst, inv, err)
    return Outcome("agree", "", n, worst, inv)


def _class_split(p, raw, ref, ref_raw, kind, ex, k, scale, worst, inv, err) -> Outcome:
    """Why exact and reference part at impact k; an unexplained split fails."""
    for imps in (ex, ref):
        for j in (k - 1, k):
            cls = _ambiguous(imps, j, scale, p, kind)
            if cls:
                return Outcome(cls, f"impact {j} (w' = "
                               f"{imps['v_m'][j] - imps['v_b'][j]:.2g}) where the solvers "
                               f"part at impact {k}", k, worst, inv)
    # an impact one solver sees and the other grazes past
    if k < ex.size and ref_raw is not None and _near_graze(ref_raw, ex["wall"][k],
                                                           ex["t"][k], scale):
        return Outcome("grazing", f"the reference grazes past impact {k}", k, worst, inv)
    if k < ref.size and _near_graze(raw, ref["wall"][k], ref["t"][k], scale):
        return Outcome("grazing", f"the exact solver grazes past impact {k}", k, worst, inv)
    t_ex = ex["t"][k] if k < ex.size else None
    t_ref = ref["t"][k] if k < ref.size else None
    raise AssertionError(f"exact and reference part at impact {k}: t {t_ex} vs {t_ref}, "
                         f"error {err:.3g}, walls "
                         f"{ex['wall'][k] if t_ex is not None else None} vs "
                         f"{ref['wall'][k] if t_ref is not None else None}")
