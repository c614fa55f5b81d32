"""Independent reference solver: numerical integration with ``scipy.integrate.solve_ivp``.

This module is the test oracle for the closed-form solver. It deliberately shares no code
with it: the equations of motion are integrated numerically, impacts are located with
``solve_ivp`` terminal events (brentq on the dense output) and the window integrals are
carried as extra ODE states.

Model (dimensionless, see docs/model.md). Free flight, |w| < 1 with w = z_m - z_b::

    z_m'' + d z_m' + z_m = f(t) = F sin(omega t + phi) + d omega F cos(omega t + phi),   z_b'' = 0.

Wall L is w = +1, wall R is w = -1; an impact happens only when approaching the wall
(w' > 0 at L, w' < 0 at R) and maps pre (-) to post (+) velocities by::

    v_m+ = ((1 - r eta) v_m- + eta (1 + r) v_b-)/(1 + eta)
    v_b+ = ((1 + r) v_m- + (eta - r) v_b-)/(1 + eta).

Sticking. After an impact at wall ``s`` (+1 for L, -1 for R), if |w'+| <= v_stick and the free
relative acceleration g = f(t) - d v - z_m presses the ball on that wall (s g > 0, evaluated
with the common velocity v = (v_m+ + eta v_b+)/(1 + eta) the stuck phase starts from), ball
and LO move as one body ``(1 + eta) z'' + d z' + z = f(t)`` with z_b = z_m - s. The stuck
phase ends when g (evaluated on the stuck state) changes sign (from + to - at L, from - to +
at R); free flight resumes from w = s, w' = 0. With v_stick = 0 only a plastic impact
(w'+ = 0 exactly, r = 0) sticks, and so does a start on a wall with w' = 0 while pressed.

Restart rule (why an event never re-triggers at the point it restarts from)
----------------------------------------------------------------------------
After an impact at wall s (or a release from it) the state sits on that wall, so the wall's
event function w - s is zero at the restart time. The event of the departed wall is therefore
**not armed** at first. Instead a terminal *turning* event on w' = 0 (direction +1 after
leaving L, -1 after leaving R) watches for the moment the relative motion turns back towards
the departed wall. Until then w moves monotonically away from that wall, so it cannot be hit.
At the turning point the wall event is armed again; its value there is strictly on the inner
side (w < 1 at L), so its first root is a genuine new contact. The turning event itself starts
from w'+ != 0 on its non-triggering side. Departures with w' = 0 exactly (after a release, or
r = 0) are covered by the start-value rule: every event function reports, at the segment start
t0, the value of the initial state, or, when that is exactly 0, a value on the side it is
heading to (for the turning event: the side of the departure). So no function that leaves
zero at t0 can report a root at t0, while a genuine root later in the first step is still
bracketed. Release times are nudged forward (by a few ulps) until g has really changed sign,
so a free flight never starts while the ball is still pressed on the wall. The opposite wall
is always armed (its event starts at distance 2). The release event of a stuck phase starts
strictly signed, as the stick condition requires s g > 0.

Missed grazing contacts. ``solve_ivp`` only compares signs at step ends, so a wall excursion
that starts and ends inside one step would be missed. A non-terminal event on w' = 0 records
every extremum of w; if one lies beyond a wall (by more than a few atol), the crossing is
located with brentq between the previous extremum (or the segment start) and it, where w is
monotone, and the segment is cut there. So no contact is lost between turning points.

Degenerate cases: a turning point found numerically on or beyond the departed wall (a chatter
flight shorter than the integration accuracy) is put back on the wall with w' = 0 (common
velocity); if g presses the ball on the wall it starts a stuck phase (v_stick > 0), otherwise
the ball departs again. With v_stick = 0 such a turning point stops the run with status
"zeno" (an accumulation point of impacts that is not allowed to stick); a plastic impact
(r = 0) is no accumulation: it sticks when pressed, like the exact solver.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..core.params import ModelParams, SolverSettings
from ..core.result import IMPACT_DTYPE, RawRun

#: the scipy.integrate.solve_ivp methods the RK oracle runs
METHODS = ("DOP853", "RK45", "LSODA", "Radau")

__all__ = ["run_rk", "METHODS"]


class _Segment:
    """One integration piece: free flight (6 states) or stuck (4 states)."""

    __slots__ = ("t0", "t1", "sol", "stuck", "wall")

    def __init__(self, t0, t1, sol, stuck, wall):
        self.t0, self.t1, self.sol, self.stuck, self.wall = t0, t1, sol, stuck, wall

    def states(self, t):
        y = self.sol(np.atleast_1d(t)).reshape(-1, np.size(t))
        if self.stuck:
            z, v = y[0], y[1]
            return np.vstack([z, v, z - self.wall, v])
        return y[:4]


class _StateAt:
    """Callable mapping an array of times to the (4, n) state from the segments' dense outputs."""

    def __init__(self, segments, state0, t_last):
        self._segs = [s for s in segments if s.t1 > s.t0]
        self._starts = np.array([s.t0 for s in self._segs])
        self._state0 = np.asarray(state0, dtype=float)
        self.t_last = t_last

    def __call__(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty((4, t.size))
        if not self._segs:
            out[:] = self._state0[:, None]
            return out
        idx = np.clip(np.searchsorted(self._starts, t, side="right") - 1, 0, len(self._segs) - 1)
        for k in np.unique(idx):
            m = idx == k
            seg = self._segs[k]
            tt = np.clip(t[m], seg.t0, seg.t1)
            out[:, m] = seg.states(tt)
        return out


def run_rk(params: ModelParams, settings: SolverSettings, *, method: str = "DOP853",
           rtol: float = 1e-10, atol: float | None = None) -> RawRun:
    """Simulate one run with ``solve_ivp`` (event loop); see the module docstring.

    method  one of "DOP853", "RK45", "LSODA", "Radau"
    rtol    relative tolerance; atol defaults to rtol * 1e-2 (states are O(1))

    Returns a :class:`RawRun`. Window integrals of z_m'^2 and z_b'^2 over
    [t_transient, t_end] are integrated as extra ODE states (the run is split at
    t_transient); maxima of |z_m| come from a non-terminal event on z_m' = 0 plus every
    segment end point. ``status`` is "ok", "max_impacts" (stopped after
    settings.max_impacts impacts), "zeno" (see the module docstring) or "stalled" (a safety
    stop after 1000 consecutive segments without progress in time; not expected to occur).
    """
    if method not in METHODS:
        raise ValueError(f"invalid method = {method!r}: must be one of {', '.join(METHODS)}")
    rtol = float(rtol)
    if not (rtol > 0.0 and math.isfinite(rtol)):
        raise ValueError(f"invalid rtol = {rtol!r}: must be a finite number > 0")
    atol = rtol * 1e-2 if atol is None else float(atol)
    if not (atol > 0.0 and math.isfinite(atol)):
        raise ValueError(f"invalid atol = {atol!r}: must be a finite number > 0")
    return _RKEventLoop(params, settings, method, rtol, atol).run()


# ---- event functions ----------------------------------------------------------------------
# Every event function caches its values by time. solve_ivp detects a sign change from the
# values at the two step ends (computed from the solver's states) and brentq then evaluates
# the same function at the same two times on the dense output; the cache makes both see
# identical end values (LSODA's dense output does not reproduce the step ends exactly, which
# otherwise breaks the bracket when a value is near 0). At the segment start t0 the cached
# value is the one of the initial state or, if that is exactly 0, a value on the side the
# function is heading to: a function that leaves zero at t0 then never reports a root at t0.

def _cached_event(raw, t0, v0, heading, terminal, direction):
    """Event function ``raw(t, y)`` for solve_ivp with the time cache and start value above."""
    cache = {t0: v0 if v0 != 0.0 else (heading if heading != 0.0 else 1.0)}

    def ev(t, y):
        v = cache.get(t)
        if v is None:
            if len(cache) > 256:        # keep the latest step ends (largest times)
                keep = sorted(cache)[-2:]
                kept = {k: cache[k] for k in keep}
                cache.clear()
                cache.update(kept)
            v = cache[t] = raw(t, y)
        return v
    ev.terminal, ev.direction = terminal, direction
    return ev


def _raw_L(t, y):           # wall L: w - 1
    return y[0] - y[2] - 1.0


def _raw_R(t, y):           # wall R: w + 1
    return y[0] - y[2] + 1.0


def _raw_dw(t, y):          # w' (turning points and extrema of w)
    return y[1] - y[3]


def _raw_v(t, y):           # z_m' (extrema of z_m)
    return y[1]


class _RKEventLoop:
    """State and bookkeeping of one ``run_rk`` run: a loop over integration segments.

    The run alternates free-flight segments (6 ODE states: z_m, z_m', z_b, z_b' and the two
    window integrals) and stuck segments (4 states: z, z' of the common body and the two
    integrals), each one ``solve_ivp`` call ending at an event, t_transient or t_end. An
    impact is applied between segments (``pending_impact``). ``stuck`` is the wall the ball
    sticks to (0 in free flight), ``departed`` the wall just left in free flight (its event
    is not armed, see the restart rule in the module docstring).
    """

    def __init__(self, params: ModelParams, settings: SolverSettings, method, rtol, atol):
        self.method, self.rtol, self.atol = method, rtol, atol
        self.eta, self.omega, self.F = params.eta, params.omega, params.F
        self.r, self.d, self.phi = params.r, params.d, params.phi
        self.t_end, self.t_tr = settings.t_end, settings.t_transient
        self.v_stick, self.max_imp = settings.v_stick, settings.max_impacts
        self.root_tol, self.state0 = settings.root_tol, settings.state0
        self.dWF = self.d * self.omega * self.F
        self.inv1e = 1.0 / (1.0 + self.eta)
        self.tol_w = max(4.0 * atol, 1e-13)      # beyond-wall tolerance of the graze check
        # records
        self.impacts = []
        self.segments = []
        self.int_vm2 = self.int_vb2 = 0.0       # window integrals of z_m'^2, z_b'^2
        self.xmax_window = self.xmax_all = 0.0
        self.t_stuck_window = self.t_stuck_total = 0.0
        self.nfev = 0
        self.n_sticks = 0
        self.status = "ok"
        self.stalled = 0        # consecutive segments that made no progress in time
        # state
        self.t = 0.0
        self.zm, self.vm, self.zb, self.vb = settings.state0
        self.stuck = 0
        self.departed = 0
        self.pending_impact = None      # wall of an impact to apply at the current state
        # current segment: its end, whether it lies in the window, weight of the integrals
        self.t_stop, self.in_win, self.wgt = self.t_end, False, 0.0

    # ---- model ----
    def force(self, t):
        a = self.omega * t + self.phi
        return self.F * math.sin(a) + self.dWF * math.cos(a)

    def gfree(self, t, zm, vm):
        """Free relative acceleration z_m'' = w'' (the contact-force sign when stuck)."""
        return self.force(t) - self.d * vm - zm

    def _rhs_free(self, t, y):
        vm, vb, wgt = y[1], y[3], self.wgt
        return [vm, self.force(t) - self.d * vm - y[0], vb, 0.0, wgt * vm * vm, wgt * vb * vb]

    def _rhs_stuck(self, t, y):
        v, wgt = y[1], self.wgt
        return [v, (self.force(t) - self.d * v - y[0]) * self.inv1e, wgt * v * v, wgt * v * v]

    def _raw_g(self, t, y):      # contact-force sign of a stuck phase
        return self.gfree(t, y[0], y[1])

    # ---- bookkeeping ----
    def note_x(self, t, zm):
        a = abs(zm)
        if a > self.xmax_all:
            self.xmax_all = a
        if t >= self.t_tr and a > self.xmax_window:
            self.xmax_window = a

    def _stick(self, s):
        """Start a stuck phase on wall s (velocities already merged)."""
        self.stuck, self.departed = s, 0
        self.n_sticks += 1

    def _integrate(self, rhs, y0, events):
        res = solve_ivp(rhs, (self.t, self.t_stop), y0, method=self.method, rtol=self.rtol,
                        atol=self.atol, dense_output=True, events=events)
        self.nfev += res.nfev
        return res

    def _close_segment(self, t1, y1, sol, wall):
        """Store the segment [t, t1], add its window integrals and move t to t1.

        wall: the wall of a stuck segment, 0 for free flight."""
        self.stalled = self.stalled + 1 if t1 <= self.t else 0
        self.segments.append(_Segment(self.t, t1, sol, wall != 0, wall))
        k = 2 if wall else 4        # index of the integral of z_m'^2 in the ODE state
        if self.in_win:
            self.int_vm2 += y1[k]
            self.int_vb2 += y1[k + 1]
            if wall:
                self.t_stuck_window += t1 - self.t
        if wall:
            self.t_stuck_total += t1 - self.t
        self.t = t1

    # ---- the loop ----
    def run(self) -> RawRun:
        self.note_x(self.t, self.zm)
        self._start_on_wall()
        while self.status == "ok" and self.t < self.t_end:
            if self.stalled > 1000:
                self.status = "stalled"
                break
            if self.pending_impact is not None:
                self._impact()
                continue
            self.t_stop = self.t_tr if self.t < self.t_tr else self.t_end
            self.in_win = self.t >= self.t_tr
            self.wgt = 1.0 if self.in_win else 0.0
            if self.stuck:
                self._stuck_segment()
            else:
                self._free_segment()
        return self._result()

    def _start_on_wall(self):
        """A start within root_tol of a wall: impact, sticking or departure from it."""
        w0 = self.zm - self.zb
        root_tol = self.root_tol
        if w0 >= 1.0 - root_tol or w0 <= -(1.0 - root_tol):
            s = 1 if w0 > 0 else -1
            self.zb = self.zm - s
            dw = self.vm - self.vb
            if dw * s > 0:
                self.pending_impact = s
            elif dw == 0.0 and self.gfree(self.t, self.zm, self.vm) * s > 0:
                # resting on the wall and pressed on it: sticking (for any v_stick)
                self._stick(s)
            else:
                self.departed = s

    def _impact(self):
        """Apply the pending impact (recording pre-impact values), then stick or depart."""
        s, self.pending_impact = self.pending_impact, None
        t, zm, vm, vb, eta, r = self.t, self.zm, self.vm, self.vb, self.eta, self.r
        self.impacts.append((t, zm, vm, self.zb, vb, s))
        vm, vb = (((1.0 - r * eta) * vm + eta * (1.0 + r) * vb) * self.inv1e,
                  ((1.0 + r) * vm + (eta - r) * vb) * self.inv1e)
        self.vm, self.vb, self.zb = vm, vb, zm - s
        self.note_x(t, zm)
        if len(self.impacts) >= self.max_imp:
            self.status = "max_impacts"
            return
        dw = vm - vb
        vc = (vm + eta * vb) * self.inv1e
        if abs(dw) <= self.v_stick and self.gfree(t, zm, vc) * s > 0:
            # (v_stick = 0: only a plastic impact, w'+ = 0 exactly, as with r = 0)
            self.vm = self.vb = vc
            self._stick(s)
        else:
            self.departed = s

    def _stuck_segment(self):
        """Integrate the stuck body until the contact force changes sign (release)."""
        s, t, zm, vm = self.stuck, self.t, self.zm, self.vm
        g0 = self.gfree(t, zm, vm)
        rel = _cached_event(self._raw_g, t, g0, float(s), True, -float(s))
        ext = _cached_event(_raw_v, t, vm, g0, False, 0.0)
        res = self._integrate(self._rhs_stuck, [zm, vm, 0.0, 0.0], [rel, ext])
        t1 = float(res.t[-1])
        y1 = res.y[:, -1]
        for te, ye in zip(res.t_events[1], res.y_events[1], strict=False):
            self.note_x(te, ye[0])
        released = res.status == 1
        if released:
            t1, y1 = self._release_point(res, t1, y1, s)
        self._close_segment(t1, y1, res.sol, s)
        self.zm, self.vm = float(y1[0]), float(y1[1])
        self.zb, self.vb = self.zm - s, self.vm
        self.note_x(self.t, self.zm)
        if released:
            self.stuck, self.departed = 0, s

    def _release_point(self, res, t1, y1, s):
        """Nudge the release time forward until the contact force has really changed sign."""
        tr, k = t1, 0
        yr = y1
        while self.gfree(tr, yr[0], yr[1]) * s > 0 and k < 60:
            tr = t1 + 4.0 * np.finfo(float).eps * max(1.0, abs(t1)) * 2.0 ** k
            yr = res.sol(tr)
            k += 1
        return tr, yr

    def _free_events(self):
        """Event functions of a free-flight segment and their kinds (see the module docstring)."""
        t, zm, vm, zb, vb, departed = self.t, self.zm, self.vm, self.zb, self.vb, self.departed
        a0 = self.gfree(t, zm, vm)       # z_m'' = w'' at t
        dw0 = vm - vb
        w0 = zm - zb
        events = [_cached_event(_raw_v, t, vm, a0, False, 0.0),
                  _cached_event(_raw_dw, t, dw0, -float(departed) if departed else a0,
                                False, 0.0)]
        kinds = ["ext", "wext"]
        if departed != 1:       # L armed
            events.append(_cached_event(_raw_L, t, w0 - 1.0, -1.0, True, 1.0))
            kinds.append("L")
        if departed != -1:      # R armed
            events.append(_cached_event(_raw_R, t, w0 + 1.0, 1.0, True, -1.0))
            kinds.append("R")
        if departed:            # turning back towards the departed wall
            events.append(_cached_event(_raw_dw, t, dw0, -float(departed), True,
                                        float(departed)))
            kinds.append("turn")
        return events, kinds

    def _free_segment(self):
        """Integrate free flight until a wall is hit, the motion turns back towards the
        departed wall, or t_stop."""
        events, kinds = self._free_events()
        res = self._integrate(self._rhs_free, [self.zm, self.vm, self.zb, self.vb, 0.0, 0.0],
                              events)
        t1 = float(res.t[-1])
        y1 = res.y[:, -1]
        hit, turned = _terminal_event(res, kinds, t1)
        graze = self._grazed_wall(res, t1)
        if graze is not None:
            t1, hit = graze
            y1 = res.sol(t1)
            turned = False
        for te, ye in zip(res.t_events[0], res.y_events[0], strict=False):
            if te <= t1:
                self.note_x(te, ye[0])
        self._close_segment(t1, y1, res.sol, 0)
        self.zm, self.vm, self.zb, self.vb = (float(x) for x in y1[:4])
        self.note_x(self.t, self.zm)
        if hit is not None:
            self.pending_impact = hit
            self.departed = 0
        elif turned:
            self._turning_point()

    def _grazed_wall(self, res, t1):
        """Graze check: (crossing time, wall) of a wall crossing stepped over, or None.

        An extremum of w (non-terminal event "wext") beyond a wall means the crossing was
        stepped over; it is located with brentq between the previous extremum (or the
        segment start), where w is monotone, and the extremum."""
        t = t_prev = self.t
        for te, ye in zip(res.t_events[1], res.y_events[1], strict=False):
            if te > t1:
                break
            wx = ye[0] - ye[2]
            if te > t and abs(wx) > 1.0 + self.tol_w:
                s = 1 if wx > 0 else -1

                def wf(tt, s=s):
                    yy = res.sol(tt)
                    return yy[0] - yy[2] - s
                if wf(t_prev) * s < 0:
                    tc = brentq(wf, t_prev, te, xtol=4 * np.finfo(float).eps,
                                rtol=4 * np.finfo(float).eps)
                else:
                    tc = t_prev
                return tc, s
            t_prev = te
        return None

    def _turning_point(self):
        """The motion turned back towards the departed wall: re-arm it, or (a turning point
        on/over the wall: a flight below integration accuracy, cut short to w = s, w' = 0)
        stick when pressed on the wall (v_stick > 0) or stop ("zeno"); otherwise depart
        again with zero relative velocity."""
        s = self.departed
        if (self.zm - self.zb) * s >= 1.0:
            self.zb = self.zm - s
            vc = (self.vm + self.eta * self.vb) * self.inv1e
            self.vm = self.vb = vc
            if self.gfree(self.t, self.zm, vc) * s > 0:
                if self.v_stick > 0.0:
                    self._stick(s)
                else:
                    self.status = "zeno"
        else:
            self.departed = 0

    def _result(self) -> RawRun:
        t_last = min(self.t, self.t_end)
        imp = (np.array(self.impacts, dtype=IMPACT_DTYPE) if self.impacts
               else np.zeros(0, dtype=IMPACT_DTYPE))
        return RawRun(
            impacts=imp,
            int_vm2=float(self.int_vm2),
            int_vb2=float(self.int_vb2),
            xmax_window=float(self.xmax_window),
            xmax_whole_run=float(self.xmax_all),
            t_stuck_window=float(self.t_stuck_window),
            t_stuck_total=float(self.t_stuck_total),
            n_impacts=len(self.impacts),
            status=self.status,
            t_last=float(t_last),
            state_at=_StateAt(self.segments, self.state0, t_last),
            n_sticks=self.n_sticks,
            solver_info={"method": self.method, "rtol": self.rtol, "atol": self.atol,
                         "nfev": int(self.nfev)},
        )


def _terminal_event(res, kinds, t1):
    """(wall hit at t1 or None, turned back at t1) from the terminal events of a segment."""
    hit, turned = None, False
    if res.status == 1:
        for kind, te in zip(kinds, res.t_events, strict=False):
            if kind in ("L", "R", "turn") and te.size and te[-1] == t1:
                if kind == "L":
                    hit = 1
                elif kind == "R":
                    hit = -1
                else:
                    turned = True
        if hit is not None:
            turned = False
    return hit, turned
