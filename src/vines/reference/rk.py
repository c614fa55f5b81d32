"""Independent reference solver: numerical integration with ``scipy.integrate.solve_ivp``.

This module is the test oracle for the closed-form solver. It deliberately shares no code
with it: the equations of motion are integrated numerically, impacts are located with
``solve_ivp`` terminal events (brentq on the dense output) and the window integrals are
carried as extra ODE states.

Model (dimensionless, see docs/model.md). Free flight, |w| < 1 with w = z_m - z_b::

    z_m'' + d z_m' + z_m = f(t) = F sin(W t + phi) + d W F cos(W t + phi),   z_b'' = 0.

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

    eta, W, F, r, d, phi = (params.eta, params.omega, params.F, params.r, params.d, params.phi)
    t_end, t_tr = settings.t_end, settings.t_transient
    v_stick, max_imp, root_tol = settings.v_stick, settings.max_impacts, settings.root_tol
    dWF = d * W * F
    inv1e = 1.0 / (1.0 + eta)
    tol_w = max(4.0 * atol, 1e-13)      # beyond-wall tolerance of the graze check

    def force(t):
        a = W * t + phi
        return F * math.sin(a) + dWF * math.cos(a)

    # ---- right-hand sides (weight 1 inside the window, 0 before) ----
    def rhs_free(wgt):
        def f(t, y):
            vm, vb = y[1], y[3]
            return [vm, force(t) - d * vm - y[0], vb, 0.0, wgt * vm * vm, wgt * vb * vb]
        return f

    def rhs_stuck(wgt):
        def f(t, y):
            v = y[1]
            return [v, (force(t) - d * v - y[0]) * inv1e, wgt * v * v, wgt * v * v]
        return f

    # ---- event functions ----
    # Every event function caches its values by time. solve_ivp detects a sign change from
    # the values at the two step ends (computed from the solver's states) and brentq then
    # evaluates the same function at the same two times on the dense output; the cache makes
    # both see identical end values (LSODA's dense output does not reproduce the step ends
    # exactly, which otherwise breaks the bracket when a value is near 0). At the segment
    # start t0 the cached value is the one of the initial state or, if that is exactly 0, a
    # value on the side the function is heading to: a function that leaves zero at t0 then
    # never reports a root at t0.
    def make_event(raw, t0, v0, heading, terminal, direction):
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

    def raw_L(t, y):            # wall L: w - 1
        return y[0] - y[2] - 1.0

    def raw_R(t, y):            # wall R: w + 1
        return y[0] - y[2] + 1.0

    def raw_dw(t, y):           # w' (turning points and extrema of w)
        return y[1] - y[3]

    def raw_v(t, y):            # z_m' (extrema of z_m)
        return y[1]

    def raw_g(t, y):            # contact-force sign of a stuck phase
        return force(t) - d * y[1] - y[0]

    # ---- bookkeeping ----
    impacts = []
    segments = []
    acc = {"ivm": 0.0, "ivb": 0.0, "xw": 0.0, "xa": 0.0, "tsw": 0.0, "tst": 0.0, "nfev": 0}
    n_sticks = 0
    status = "ok"

    def note_x(t, zm):
        a = abs(zm)
        if a > acc["xa"]:
            acc["xa"] = a
        if t >= t_tr and a > acc["xw"]:
            acc["xw"] = a

    def gfree(t, zm, vm):
        return force(t) - d * vm - zm

    zm, vm, zb, vb = settings.state0
    t = 0.0
    note_x(t, zm)

    # mode: "free" or "stuck"; departed: wall just left (0 = none, both walls armed)
    mode = "free"
    departed = 0
    stick_wall = 0
    pending_impact = None    # wall of an impact to apply at the current state

    w0 = zm - zb
    if w0 >= 1.0 - root_tol or w0 <= -(1.0 - root_tol):
        s = 1 if w0 > 0 else -1
        zb = zm - s
        dw = vm - vb
        if dw * s > 0:
            pending_impact = s
        elif dw == 0.0 and gfree(t, zm, vm) * s > 0:
            # resting on the wall and pressed on it: sticking (for any v_stick)
            mode, stick_wall = "stuck", s
            n_sticks += 1
        else:
            departed = s

    def apply_impact(t, zm, vm, zb, vb, s):
        """Record the impact (pre-impact values); return v_m+, v_b+ and z_b on the wall."""
        impacts.append((t, zm, vm, zb, vb, s))
        vmp = ((1.0 - r * eta) * vm + eta * (1.0 + r) * vb) * inv1e
        vbp = ((1.0 + r) * vm + (eta - r) * vb) * inv1e
        return vmp, vbp, zm - s

    stalled = 0             # consecutive segments that made no progress in time
    while status == "ok" and t < t_end:
        if stalled > 1000:
            status = "stalled"
            break
        if pending_impact is not None:
            s = pending_impact
            pending_impact = None
            vm, vb, zb = apply_impact(t, zm, vm, zb, vb, s)
            note_x(t, zm)
            if len(impacts) >= max_imp:
                status = "max_impacts"
                break
            dw = vm - vb
            vc = (vm + eta * vb) * inv1e
            gc = gfree(t, zm, vc)
            if abs(dw) <= v_stick and gc * s > 0:
                # (v_stick = 0: only a plastic impact, w'+ = 0 exactly, as with r = 0)
                mode, stick_wall = "stuck", s
                vm = vb = vc
                n_sticks += 1
            else:
                mode, departed = "free", s
            continue

        t_stop = t_tr if t < t_tr else t_end
        in_win = t >= t_tr
        wgt = 1.0 if in_win else 0.0

        if mode == "stuck":
            s = stick_wall
            g0 = force(t) - d * vm - zm
            rel = make_event(raw_g, t, g0, float(s), True, -float(s))
            ext = make_event(raw_v, t, vm, g0, False, 0.0)
            res = solve_ivp(rhs_stuck(wgt), (t, t_stop), [zm, vm, 0.0, 0.0], method=method,
                            rtol=rtol, atol=atol, dense_output=True, events=[rel, ext])
            acc["nfev"] += res.nfev
            t1 = float(res.t[-1])
            y1 = res.y[:, -1]
            for te, ye in zip(res.t_events[1], res.y_events[1]):
                note_x(te, ye[0])
            released = res.status == 1
            if released:
                # make sure the contact force has really changed sign at the release time
                tr, k = t1, 0
                yr = y1
                while (force(tr) - d * yr[1] - yr[0]) * s > 0 and k < 60:
                    tr = t1 + 4.0 * np.finfo(float).eps * max(1.0, abs(t1)) * 2.0 ** k
                    yr = res.sol(tr)
                    k += 1
                t1, y1 = tr, yr
            stalled = stalled + 1 if t1 <= t else 0
            segments.append(_Segment(t, t1, res.sol, True, s))
            if in_win:
                acc["ivm"] += y1[2]
                acc["ivb"] += y1[3]
                acc["tsw"] += t1 - t
            acc["tst"] += t1 - t
            t = t1
            zm, vm = float(y1[0]), float(y1[1])
            zb, vb = zm - s, vm
            note_x(t, zm)
            if released:
                mode, departed = "free", s
            continue

        # ---- free flight ----
        a0 = gfree(t, zm, vm)       # z_m'' = w'' at t
        dw0 = vm - vb
        w0 = zm - zb
        events = [make_event(raw_v, t, vm, a0, False, 0.0),
                  make_event(raw_dw, t, dw0, -float(departed) if departed else a0, False, 0.0)]
        kinds = ["ext", "wext"]
        if departed != 1:       # L armed
            events.append(make_event(raw_L, t, w0 - 1.0, -1.0, True, 1.0))
            kinds.append("L")
        if departed != -1:      # R armed
            events.append(make_event(raw_R, t, w0 + 1.0, 1.0, True, -1.0))
            kinds.append("R")
        if departed:            # turning back towards the departed wall
            events.append(make_event(raw_dw, t, dw0, -float(departed), True, float(departed)))
            kinds.append("turn")
        res = solve_ivp(rhs_free(wgt), (t, t_stop), [zm, vm, zb, vb, 0.0, 0.0], method=method,
                        rtol=rtol, atol=atol, dense_output=True, events=events)
        acc["nfev"] += res.nfev
        t1 = float(res.t[-1])
        y1 = res.y[:, -1]
        hit = None          # wall hit at t1
        turned = False
        if res.status == 1:
            for kind, te in zip(kinds, res.t_events):
                if kind in ("L", "R", "turn") and te.size and te[-1] == t1:
                    if kind == "L":
                        hit = 1
                    elif kind == "R":
                        hit = -1
                    else:
                        turned = True
            if hit is not None:
                turned = False

        # graze check: an extremum of w beyond a wall means a crossing was stepped over
        t_prev = t
        for te, ye in zip(res.t_events[1], res.y_events[1]):
            if te > t1:
                break
            wx = ye[0] - ye[2]
            if te > t and abs(wx) > 1.0 + tol_w:
                s = 1 if wx > 0 else -1

                def wf(tt, s=s):
                    yy = res.sol(tt)
                    return yy[0] - yy[2] - s
                if wf(t_prev) * s < 0:
                    tc = brentq(wf, t_prev, te, xtol=4 * np.finfo(float).eps,
                                rtol=4 * np.finfo(float).eps)
                else:
                    tc = t_prev
                t1 = tc
                y1 = res.sol(tc)
                hit, turned = s, False
                break
            t_prev = te

        for te, ye in zip(res.t_events[0], res.y_events[0]):
            if te <= t1:
                note_x(te, ye[0])
        stalled = stalled + 1 if t1 <= t else 0
        segments.append(_Segment(t, t1, res.sol, False, 0))
        if in_win:
            acc["ivm"] += y1[4]
            acc["ivb"] += y1[5]
        t = t1
        zm, vm, zb, vb = (float(x) for x in y1[:4])
        note_x(t, zm)

        if hit is not None:
            pending_impact = hit
            departed = 0
        elif turned:
            s = departed
            if (zm - zb) * s >= 1.0:
                # turning point on/over the departed wall: a flight below integration accuracy
                # (cut short to w = s, w' = 0). Pressed on the wall: stick (v_stick > 0) or
                # stop ("zeno"); otherwise depart again with zero relative velocity.
                zb = zm - s
                vc = (vm + eta * vb) * inv1e
                vm = vb = vc
                if gfree(t, zm, vc) * s > 0:
                    if v_stick > 0.0:
                        mode, stick_wall = "stuck", s
                        n_sticks += 1
                        departed = 0
                    else:
                        status = "zeno"
            else:
                departed = 0

    t_last = min(t, t_end)
    imp = np.array(impacts, dtype=IMPACT_DTYPE) if impacts else np.zeros(0, dtype=IMPACT_DTYPE)
    return RawRun(
        impacts=imp,
        int_vm2=float(acc["ivm"]),
        int_vb2=float(acc["ivb"]),
        xmax_window=float(acc["xw"]),
        xmax_whole_run=float(acc["xa"]),
        t_stuck_window=float(acc["tsw"]),
        t_stuck_total=float(acc["tst"]),
        n_impacts=len(impacts),
        status=status,
        t_last=float(t_last),
        state_at=_StateAt(segments, settings.state0, t_last),
        n_sticks=n_sticks,
        solver_info={"method": method, "rtol": rtol, "atol": atol, "nfev": int(acc["nfev"])},
    )
