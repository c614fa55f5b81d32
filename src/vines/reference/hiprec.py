"""High-precision reference trajectories (mpmath) for measuring the solvers' errors.

The model of SPEC sections 1-2, computed independently of the double-precision code (nothing
of ``vines.flow`` or ``vines._engine`` is used) at ``dps`` significant digits:

* Between events the LO (mass m = 1) or the stuck body (m = 1 + eta) follows the closed form
  of m z'' + d z' + z = F sin(W t + phi) + d W F cos(W t + phi) written with complex
  exponentials in local time s = t - t0 of the segment; the free ball moves uniformly.
* Events are located by sampling every segment at steps of ``h_sample`` and splitting each
  sample interval at the extrema of the event function (roots of its derivative, found from a
  sign change of the derivative at the samples): a crossing of a wall inside an interval
  needs an end value or an extremum beyond the wall, so none is missed unless the event
  function has two extrema within one interval (h_sample = 0.05 is far below the time scale
  of w' ~ 2 pi). Roots are refined by bracketed Illinois iteration to ~1e-30.
* Wall L is w = z_m - z_b = +1, wall R is w = -1; impacts conserve momentum with restitution
  r; after an impact the ball sticks when |w'+| <= v_stick while the relative acceleration
  presses it onto the wall, and is released when the contact force changes sign.
* Window measures: integrals of z_m'^2, z_b'^2 over [t_transient, t_end] from the exact
  antiderivatives of products of exponentials; max |z_m| from the roots of z_m'.

Cost: about a millisecond per sample interval, so short horizons (a few hundred time units)
only. Degenerate cases the complex-exponential form cannot represent (critical damping,
undamped resonance) raise ValueError; the extremes are tested against DOP853 instead.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import mpmath as mp
import numpy as np

from ..core.params import ModelParams, SolverSettings
from ..core.result import IMPACT_DTYPE

DPS_DEFAULT = 40
H_SAMPLE_DEFAULT = 0.05
V_STICK_REFERENCE = 1e-14   # default sticking threshold of the reference (accumulation limit)


class _Osc:
    """Closed-form motion of m z'' + d z' + z = f(t) from (z0, v0) at absolute time t0."""

    def __init__(self, m, d, W, F, phi, t0, z0, v0):
        self.t0 = t0
        disc = mp.sqrt(mp.mpc(d * d - 4 * m))
        if abs(disc) < mp.mpf(10) ** (-20):
            raise ValueError("critically damped oscillator: not handled by the reference")
        l1, l2 = (-d + disc) / (2 * m), (-d - disc) / (2 * m)
        den = 1 - m * W * W + 1j * d * W
        if abs(den) < mp.mpf(10) ** (-25):
            raise ValueError("undamped resonance: not handled by the reference")
        self.W = W
        self.fc = (F + 1j * d * W * F) * mp.expj(W * t0 + phi)     # forcing f = Im(fc e^{iWs})
        E = self.fc / den                                          # z_p = Im(E e^{iWs})
        h0 = z0 - E.imag
        h1 = v0 - W * E.real
        B = (l1 * h0 - h1) / (l1 - l2)
        A = h0 - B
        self.l1, self.l2, self.A, self.B, self.E = l1, l2, A, B, E
        # z_m' = sum c_k exp(mu_k s), real sum
        self.vterms = [(l1 * A, l1), (l2 * B, l2), (W * E / 2, mp.mpc(0, W)),
                       (W * mp.conj(E) / 2, mp.mpc(0, -W))]

    def state(self, s):
        """(z, z', z'') at local time s."""
        e1, e2, ew = mp.exp(self.l1 * s), mp.exp(self.l2 * s), mp.expj(self.W * s)
        A1, B2, Ew = self.A * e1, self.B * e2, self.E * ew
        W = self.W
        z = (A1 + B2).real + Ew.imag
        v = (self.l1 * A1 + self.l2 * B2).real + W * Ew.real
        a = (self.l1 ** 2 * A1 + self.l2 ** 2 * B2).real - W * W * Ew.imag
        return z, v, a

    def forcing(self, s):
        return (self.fc * mp.expj(self.W * s)).imag

    def int_v2(self, sa, sb):
        """Exact integral of z'^2 over local times [sa, sb]."""
        total = mp.mpc(0)
        for cj, mj in self.vterms:
            for ck, mk in self.vterms:
                mu = mj + mk
                if abs(mu) < mp.mpf(10) ** (-30):
                    total += cj * ck * (sb - sa)
                else:
                    total += cj * ck * (mp.exp(mu * sb) - mp.exp(mu * sa)) / mu
        return total.real


def _illinois(f, a, b, fa, fb, tol):
    """Root of f in [a, b] with fa, fb of opposite signs (fa may be a stand-in for f(a))."""
    side = 0
    for _ in range(400):
        c = (a * fb - b * fa) / (fb - fa) if fb != fa else (a + b) / 2
        if not (min(a, b) < c < max(a, b)):
            c = (a + b) / 2
        fc = f(c)
        if fc == 0 or abs(b - a) <= tol:
            return c
        if (fc > 0) == (fb > 0):
            b, fb = c, fc
            if side == -1:
                fa /= 2
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb /= 2
            side = 1
    return (a + b) / 2


@dataclass
class Reference:
    """High-precision trajectory: impacts (pre-impact values, rounded to double) and measures.

    ke_ratio, xmax over the window [t_transient, t_end]; sticks: (start, end) times of the
    sticking phases; n_intervals: sample intervals evaluated (cost).
    """

    impacts: np.ndarray
    ke_ratio: float
    xmax: float
    K_m: float
    K_b: float
    sticks: list = field(default_factory=list)
    n_intervals: int = 0


def reference_run(params: ModelParams, settings: SolverSettings, *, dps: int = DPS_DEFAULT,
                  h_sample: float = H_SAMPLE_DEFAULT, v_stick: float | None = None,
                  max_events: int = 200_000) -> Reference:
    """Integrate one trajectory from settings.state0 at t = 0 to settings.t_end in mpmath.

    ``v_stick`` (default settings.v_stick) is the sticking threshold of the reference.
    The start state must lie strictly inside the cavity (|w0| < 1).
    """
    with mp.workdps(dps):
        return _run(params, settings, h_sample, settings.v_stick if v_stick is None else v_stick,
                    max_events)


def _run(p, st, h_sample, v_stick, max_events):
    mpf = mp.mpf
    eta, r, d, W, F, phi = (mpf(p.eta), mpf(p.r), mpf(p.d), mpf(p.omega), mpf(p.F), mpf(p.phi))
    t_end, t_tr, h = mpf(st.t_end), mpf(st.t_transient), mpf(h_sample)
    v_stick = mpf(v_stick)
    tol = mpf(10) ** (-(mp.mp.dps - 8))
    zm, vm, zb, vb = (mpf(x) for x in st.state0)
    if abs(zm - zb) >= 1:
        raise ValueError("the reference needs a start state strictly inside the cavity")
    t = mpf(0)
    mode, departed = 0, 0          # mode: 0 free, +-1 stuck at L/R; departed: wall just left
    impacts, sticks = [], []
    acc = {"vm2": mpf(0), "vb2": mpf(0), "xmax": mpf(0), "n": 0}
    if t_tr == 0:
        acc["xmax"] = abs(zm)

    def window(sa_abs, sb_abs):
        return max(sa_abs, t_tr), min(sb_abs, t_end)

    while t < t_end:
        if len(impacts) + len(sticks) > max_events:
            raise RuntimeError("reference: too many events")
        if mode == 0:
            osc = _Osc(mpf(1), d, W, F, phi, t, zm, vm)
            s_w = 0

            def wfun(s):            # (w, w', z_m, z_m') at local time s
                z, v, _ = osc.state(s)
                return z - (zb + vb * s), v - vb, z, v

            s_end = t_end - t
            a_s = mpf(0)
            wa, dwa, za, va = wfun(a_s)
            # heading of w' at the start: away from the departed wall when w' is 0 there
            dwa_sign = dwa if dwa != 0 else (-departed if departed else 1)
            hit = None
            while a_s < s_end:
                b_s = min(a_s + h, s_end)
                acc["n"] += 1
                wb, dwb, zb_, vb_ = wfun(b_s)
                # x_max: extrema of z_m inside (a, b)
                _note_extremum(acc, osc, t, a_s, b_s, va, vb_, tol, t_tr, t_end)
                # split (a, b) at an extremum of w
                pieces = [(a_s, wa, b_s, wb)]
                if dwa_sign * dwb < 0:
                    se = _illinois(lambda s: wfun(s)[1], a_s, b_s,
                                   dwa if dwa != 0 else dwa_sign * tol, dwb, tol)
                    we = wfun(se)[0]
                    pieces = [(a_s, wa, se, we), (se, we, b_s, wb)]
                for (x0, w0, x1, w1) in pieces:
                    for wall in (1, -1):
                        g0, g1 = wall * (w0 - wall), wall * (w1 - wall)   # <= 0 inside
                        leaving = (x0 == 0 and departed == wall)
                        if g1 >= 0 and (g0 < 0 or (g0 == 0 and not leaving and x0 > 0)):
                            if g0 == 0:
                                hit = (x0, wall)
                            else:
                                sr = _illinois(lambda s, wall=wall: wall * (wfun(s)[0] - wall),
                                               x0, x1, g0, g1, tol)
                                hit = (sr, wall)
                            break
                    if hit:
                        break
                if hit:
                    break
                a_s, wa, dwa, dwa_sign, za, va = b_s, wb, dwb, dwb, zb_, vb_
            s1 = hit[0] if hit else s_end
            z1, v1, _ = osc.state(s1)
            if t < t_tr < t + s1:
                _note_x(acc, t_tr, osc.state(t_tr - t)[0], t_tr, t_end)
            ta, tb = window(t, t + s1)
            if tb > ta:
                acc["vm2"] += osc.int_v2(ta - t, tb - t)
                acc["vb2"] += vb * vb * (tb - ta)
            zb1 = zb + vb * s1
            t = t + s1
            zm, vm, zb = z1, v1, zb1
            _note_x(acc, t, zm, t_tr, t_end)
            if hit is None:
                break
            wall = hit[1]
            zb = zm - wall
            impacts.append((t, zm, vm, zb, vb, wall))
            vmp = ((1 - r * eta) * vm + eta * (1 + r) * vb) / (1 + eta)
            vbp = ((1 + r) * vm + (eta - r) * vb) / (1 + eta)
            vm, vb = vmp, vbp
            dw = vm - vb
            vc = (vm + eta * vb) / (1 + eta)
            press = wall * (F * mp.sin(W * t + phi) + d * W * F * mp.cos(W * t + phi)
                            - d * vc - zm)
            if abs(dw) <= v_stick and press > 0:
                mode, vm, vb = wall, vc, vc
                sticks.append([t, None])
            else:
                departed = wall
        else:
            wall = mode
            osc = _Osc(1 + eta, d, W, F, phi, t, zm, vm)

            def gfun(s):            # contact force (times wall): > 0 while pressed
                z, v, a = osc.state(s)
                return wall * (osc.forcing(s) - d * v - z)

            def dgfun(s):
                z, v, a = osc.state(s)
                dfor = (1j * W * osc.fc * mp.expj(W * s)).imag
                return wall * (dfor - d * a - v)

            s_end = t_end - t
            a_s = mpf(0)
            ga, dga = gfun(a_s), dgfun(a_s)
            _, va, _ = osc.state(a_s)
            rel = None
            while a_s < s_end:
                b_s = min(a_s + h, s_end)
                acc["n"] += 1
                gb, dgb = gfun(b_s), dgfun(b_s)
                _, vb_, _ = osc.state(b_s)
                _note_extremum(acc, osc, t, a_s, b_s, va, vb_, tol, t_tr, t_end)
                pieces = [(a_s, ga, b_s, gb)]
                if dga * dgb < 0:
                    se = _illinois(dgfun, a_s, b_s, dga, dgb, tol)
                    pieces = [(a_s, ga, se, gfun(se)), (se, gfun(se), b_s, gb)]
                for (x0, g0, x1, g1) in pieces:
                    if g1 <= 0 < g0:
                        rel = _illinois(gfun, x0, x1, g0, g1, tol)
                        break
                if rel is not None:
                    break
                a_s, ga, dga, va = b_s, gb, dgb, vb_
            s1 = rel if rel is not None else s_end
            z1, v1, _ = osc.state(s1)
            if t < t_tr < t + s1:
                _note_x(acc, t_tr, osc.state(t_tr - t)[0], t_tr, t_end)
            ta, tb = window(t, t + s1)
            if tb > ta:
                iv = osc.int_v2(ta - t, tb - t)
                acc["vm2"] += iv
                acc["vb2"] += iv
            t = t + s1
            zm, vm = z1, v1
            zb, vb = zm - wall, vm
            _note_x(acc, t, zm, t_tr, t_end)
            sticks[-1][1] = t
            if rel is None:
                break
            mode, departed = 0, wall

    t_win = t_end - t_tr
    K_m = acc["vm2"] / (2 * t_win)
    K_b = eta * acc["vb2"] / (2 * t_win)
    tot = K_m + K_b
    imp = np.array([tuple(float(x) for x in row[:5]) + (row[5],) for row in impacts],
                   dtype=IMPACT_DTYPE) if impacts else np.zeros(0, dtype=IMPACT_DTYPE)
    return Reference(impacts=imp, ke_ratio=float(K_b / tot) if tot > 0 else 0.0,
                     xmax=float(acc["xmax"]), K_m=float(K_m), K_b=float(K_b),
                     sticks=[(float(a), float(b)) for a, b in sticks], n_intervals=acc["n"])


def _note_extremum(acc, osc, t, a, b, va, vb, tol, t_tr, t_end):
    """Note |z_m| at an extremum of z_m inside local times (a, b) (z_m' changes sign)."""
    if va * vb < 0:
        se = _illinois(lambda s: osc.state(s)[1], a, b, va, vb, tol)
        _note_x(acc, t + se, osc.state(se)[0], t_tr, t_end)


def _note_x(acc, t, z, t_tr, t_end):
    if t_tr <= t <= t_end and abs(z) > acc["xmax"]:
        acc["xmax"] = abs(z)
