"""High-precision reference trajectories (mpmath) for measuring the solvers' errors.

The model of SPEC sections 1-2, computed independently of the double-precision code (no
numerical code of ``vines.core`` is used, only its containers) at ``dps`` significant digits:

* Between events the LO (mass m = 1) or the stuck body (m = 1 + eta) follows the closed form
  of m z'' + d z' + z = F sin(omega t + phi) + d omega F cos(omega t + phi) written with
  complex exponentials in local time s = t - t0 of the segment; the free ball moves
  uniformly. Both phases (free flight, stuck) run on one skeleton (``_RefRun._phase``).
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

from ..core.params import ModelParams, ParameterError, SolverSettings
from ..core.result import IMPACT_DTYPE

DPS_DEFAULT = 40
H_SAMPLE_DEFAULT = 0.05
V_STICK_REFERENCE = 1e-14   # default sticking threshold of the reference (accumulation limit)


class _Osc:
    """Closed-form motion of m z'' + d z' + z = f(t) from (z0, v0) at absolute time t0."""

    def __init__(self, m, d, omega, F, phi, t0, z0, v0):
        self.t0 = t0
        disc = mp.sqrt(mp.mpc(d * d - 4 * m))
        if abs(disc) < mp.mpf(10) ** (-20):
            raise ValueError("critically damped oscillator: not handled by the reference")
        l1, l2 = (-d + disc) / (2 * m), (-d - disc) / (2 * m)
        den = 1 - m * omega * omega + 1j * d * omega
        if abs(den) < mp.mpf(10) ** (-25):
            raise ValueError("undamped resonance: not handled by the reference")
        self.omega = omega
        # forcing f = Im(fc e^{i omega s})
        self.fc = (F + 1j * d * omega * F) * mp.expj(omega * t0 + phi)
        E = self.fc / den                                   # z_p = Im(E e^{i omega s})
        h0 = z0 - E.imag
        h1 = v0 - omega * E.real
        B = (l1 * h0 - h1) / (l1 - l2)
        A = h0 - B
        self.l1, self.l2, self.A, self.B, self.E = l1, l2, A, B, E
        # z_m' = sum c_k exp(mu_k s), real sum
        self.vterms = [(l1 * A, l1), (l2 * B, l2), (omega * E / 2, mp.mpc(0, omega)),
                       (omega * mp.conj(E) / 2, mp.mpc(0, -omega))]

    def state(self, s):
        """(z, z', z'') at local time s."""
        e1, e2, ew = mp.exp(self.l1 * s), mp.exp(self.l2 * s), mp.expj(self.omega * s)
        A1, B2, Ew = self.A * e1, self.B * e2, self.E * ew
        omega = self.omega
        z = (A1 + B2).real + Ew.imag
        v = (self.l1 * A1 + self.l2 * B2).real + omega * Ew.real
        a = (self.l1 ** 2 * A1 + self.l2 ** 2 * B2).real - omega * omega * Ew.imag
        return z, v, a

    def forcing(self, s):
        return (self.fc * mp.expj(self.omega * s)).imag

    def dforcing(self, s):
        """Time derivative of the forcing at local time s."""
        return (1j * self.omega * self.fc * mp.expj(self.omega * s)).imag

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


def check_reference_params(p: ModelParams) -> None:
    """Refuse the two cases the reference's closed form does not handle, for the free LO
    (mass 1) and the stuck body (mass 1 + eta): critical damping d^2 = 4 m and undamped
    resonance (d ~ 0, m omega^2 = 1), each to a few round-off units of the double inputs."""
    eps = 2.220446049250313e-16
    for m in (1.0, 1.0 + p.eta):
        if abs(p.d * p.d - 4.0 * m) <= 16.0 * eps * 4.0 * m:
            raise ParameterError("d", p.d, f"is critical damping 2 sqrt(m) for m = {m:g}: "
                                           "not handled by the reference")
        if p.d * p.omega <= 1e-24 and abs(1.0 - m * p.omega * p.omega) <= 16.0 * eps:
            raise ParameterError("omega", p.omega, f"is the undamped resonance 1/sqrt(m) for "
                                                   f"m = {m:g} (d ~ 0): not handled by the "
                                                   "reference")


def reference_run(params: ModelParams, settings: SolverSettings, *, dps: int = DPS_DEFAULT,
                  h_sample: float = H_SAMPLE_DEFAULT, v_stick: float | None = None,
                  max_events: int = 200_000) -> Reference:
    """Integrate one trajectory from settings.state0 at t = 0 to settings.t_end in mpmath.

    ``v_stick`` (default settings.v_stick) is the sticking threshold of the reference.
    The start state must lie strictly inside the cavity (|w0| < 1).
    """
    check_reference_params(params)
    with mp.workdps(dps):
        return _run(params, settings, h_sample, settings.v_stick if v_stick is None else v_stick,
                    max_events)


def _run(p, st, h_sample, v_stick, max_events):
    """The run at the current mpmath precision (see ``reference_run``)."""
    return _RefRun(p, st, h_sample, v_stick, max_events).run()


class _RefRun:
    """One reference run: the state, the records and the phase loop, all in mpmath numbers.

    ``mode`` is 0 in free flight and +-1 while stuck on wall L/R; ``departed`` is the wall
    the ball left last (a start on it is no new contact).
    """

    def __init__(self, p, st, h_sample, v_stick, max_events):
        mpf = mp.mpf
        self.eta, self.r, self.d = mpf(p.eta), mpf(p.r), mpf(p.d)
        self.omega, self.F, self.phi = mpf(p.omega), mpf(p.F), mpf(p.phi)
        self.t_end, self.t_tr, self.h = mpf(st.t_end), mpf(st.t_transient), mpf(h_sample)
        self.v_stick = mpf(v_stick)
        self.max_events = max_events
        self.tol = mpf(10) ** (-(mp.mp.dps - 8))
        self.zm, self.vm, self.zb, self.vb = (mpf(x) for x in st.state0)
        if abs(self.zm - self.zb) >= 1:
            raise ValueError("the reference needs a start state strictly inside the cavity")
        self.t = mpf(0)
        self.mode, self.departed = 0, 0
        self.impacts, self.sticks = [], []
        self.vm2, self.vb2, self.xmax, self.n = mpf(0), mpf(0), mpf(0), 0
        if self.t_tr == 0:
            self.xmax = abs(self.zm)

    def run(self) -> Reference:
        while self.t < self.t_end:
            if len(self.impacts) + len(self.sticks) > self.max_events:
                raise RuntimeError("reference: too many events")
            if self.mode == 0:
                wall = self._free_phase()
                if wall is None:
                    break
                self._impact(wall)
            else:
                wall = self.mode
                released = self._stuck_phase()
                self.sticks[-1][1] = self.t
                if not released:
                    break
                self.mode, self.departed = 0, wall
        return self._result()

    # ---- the two phases ----
    def _free_phase(self):
        """Free flight to the first wall contact (returns its wall) or t_end (None)."""
        zb, vb, departed, tol = self.zb, self.vb, self.departed, self.tol
        osc = _Osc(mp.mpf(1), self.d, self.omega, self.F, self.phi, self.t, self.zm, self.vm)

        def probe(s):           # (w, w', z_m') at local time s
            z, v, _ = osc.state(s)
            return z - (zb + vb * s), v - vb, v

        def contact(x0, w0, x1, w1):
            """First wall reached in a piece where w is monotone: (local time, wall)."""
            for wall in (1, -1):
                g0, g1 = wall * (w0 - wall), wall * (w1 - wall)   # <= 0 inside
                # (g0 = 0 at x0 = 0 is the departed wall: no new contact)
                if g1 >= 0 and (g0 < 0 or (g0 == 0 and x0 > 0)):
                    if g0 == 0:
                        return x0, wall
                    return _illinois(lambda s, wall=wall: wall * (probe(s)[0] - wall),
                                     x0, x1, g0, g1, tol), wall
            return None

        # heading of w' at the start: away from the departed wall when w' is 0 there
        s1, wall = self._phase(osc, probe, contact, -departed if departed else 1, vb)
        self.zb = zb + vb * s1
        return wall

    def _stuck_phase(self):
        """Stuck on wall ``mode`` until the contact force changes sign (returns True) or
        t_end (False)."""
        wall, d = self.mode, self.d
        osc = _Osc(1 + self.eta, d, self.omega, self.F, self.phi, self.t, self.zm, self.vm)

        def probe(s):           # (contact force times wall: > 0 while pressed, its rate, z')
            z, v, a = osc.state(s)
            return wall * (osc.forcing(s) - d * v - z), wall * (osc.dforcing(s) - d * a - v), v

        def release(x0, g0, x1, g1):
            if g1 <= 0 < g0:
                return _illinois(lambda s: probe(s)[0], x0, x1, g0, g1, self.tol), wall
            return None

        _, released = self._phase(osc, probe, release, 0, None)
        self.zb, self.vb = self.zm - wall, self.vm
        return released is not None

    # ---- the shared skeleton ----
    def _phase(self, osc, probe, crossing, heading, ball_speed):
        """Advance one phase from t to its first event or to t_end.

        osc       closed-form motion of the LO (free) or of the stuck body, from (t, zm, vm)
        probe     s -> (e, e', z_m') at local time s: the event function, its derivative and
                  the LO velocity
        crossing  (x0, e0, x1, e1) -> (local time, tag) of the event in a piece where e is
                  monotone, or None
        heading   sign assumed for e' at s = 0 when e'(0) = 0 (0: no split there)
        ball_speed  the free ball's constant z_b' (None: the ball moves with the LO)

        Adds the window integrals and x_max, moves t, zm, vm to the end of the phase and
        returns (phase length, tag of the event or None at t_end).
        """
        t, t_tr, t_end = self.t, self.t_tr, self.t_end
        s_end = t_end - t
        event = self._first_event(osc, probe, crossing, heading, s_end)
        s1 = event[0] if event else s_end
        z1, v1, _ = osc.state(s1)
        if t < t_tr < t + s1:
            self._note_x(t_tr, osc.state(t_tr - t)[0])
        ta, tb = max(t, t_tr), min(t + s1, t_end)
        if tb > ta:
            iv = osc.int_v2(ta - t, tb - t)
            self.vm2 += iv
            self.vb2 += iv if ball_speed is None else ball_speed * ball_speed * (tb - ta)
        self.t = t + s1
        self.zm, self.vm = z1, v1
        self._note_x(self.t, self.zm)
        return s1, (event[1] if event else None)

    def _first_event(self, osc, probe, crossing, heading, s_end):
        """Sample [0, s_end] at steps h, split each interval at an extremum of the event
        function e and return the first crossing (local time, tag), or None."""
        tol = self.tol
        a_s = mp.mpf(0)
        ea, dea, va = probe(a_s)
        dea_sign = dea if dea != 0 else heading
        while a_s < s_end:
            b_s = min(a_s + self.h, s_end)
            self.n += 1
            eb, deb, vb = probe(b_s)
            self._note_extremum(osc, a_s, b_s, va, vb)
            pieces = [(a_s, ea, b_s, eb)]
            if dea_sign * deb < 0:      # split (a, b) at the extremum of e
                se = _illinois(lambda s: probe(s)[1], a_s, b_s,
                               dea if dea != 0 else dea_sign * tol, deb, tol)
                ee = probe(se)[0]
                pieces = [(a_s, ea, se, ee), (se, ee, b_s, eb)]
            for piece in pieces:
                event = crossing(*piece)
                if event is not None:
                    return event
            a_s, ea, dea, dea_sign, va = b_s, eb, deb, deb, vb
        return None

    # ---- impacts and records ----
    def _impact(self, wall):
        """Impact on ``wall`` at the current state: record it, apply the impact law, then
        stick (|w'+| <= v_stick while pressed) or depart."""
        t, zm, eta, r, d, omega, F, phi = (self.t, self.zm, self.eta, self.r, self.d,
                                           self.omega, self.F, self.phi)
        self.zb = zm - wall
        self.impacts.append((t, zm, self.vm, self.zb, self.vb, wall))
        vm, vb = self.vm, self.vb
        vm, vb = (((1 - r * eta) * vm + eta * (1 + r) * vb) / (1 + eta),
                  ((1 + r) * vm + (eta - r) * vb) / (1 + eta))
        dw = vm - vb
        vc = (vm + eta * vb) / (1 + eta)
        press = wall * (F * mp.sin(omega * t + phi) + d * omega * F * mp.cos(omega * t + phi)
                        - d * vc - zm)
        if abs(dw) <= self.v_stick and press > 0:
            self.mode, self.vm, self.vb = wall, vc, vc
            self.sticks.append([t, None])
        else:
            self.vm, self.vb = vm, vb
            self.departed = wall

    def _note_extremum(self, osc, a, b, va, vb):
        """Note |z_m| at an extremum of z_m inside local times (a, b) (z_m' changes sign)."""
        if va * vb < 0:
            se = _illinois(lambda s: osc.state(s)[1], a, b, va, vb, self.tol)
            self._note_x(self.t + se, osc.state(se)[0])

    def _note_x(self, t, z):
        if self.t_tr <= t <= self.t_end and abs(z) > self.xmax:
            self.xmax = abs(z)

    def _result(self) -> Reference:
        t_win = self.t_end - self.t_tr
        K_m = self.vm2 / (2 * t_win)
        K_b = self.eta * self.vb2 / (2 * t_win)
        tot = K_m + K_b
        imp = np.array([tuple(float(x) for x in row[:5]) + (row[5],) for row in self.impacts],
                       dtype=IMPACT_DTYPE) if self.impacts else np.zeros(0, dtype=IMPACT_DTYPE)
        return Reference(impacts=imp, ke_ratio=float(K_b / tot) if tot > 0 else 0.0,
                         xmax=float(self.xmax), K_m=float(K_m), K_b=float(K_b),
                         sticks=[(float(a), float(b)) for a, b in self.sticks],
                         n_intervals=self.n)
