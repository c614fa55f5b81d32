"""Event-driven exact VINES kernel (numba, nogil).

A trajectory is a sequence of *segments*, each starting at an absolute time t0 with a state
(z_m, z_m', z_b, z_b') and a mode: free flight (MODE_FREE = 0) or stuck at a wall (the mode
is then that wall: WALL_L = +1, WALL_R = -1).
Inside a segment the motion is the closed form of ``vines.flow`` in local time s = t - t0.
Segments end at an impact, at the start or end of sticking, at t_transient (so that every
segment lies wholly inside or outside the measurement window) or at t_end.

First-contact rule (cannot miss a crossing, grazing included). Between impacts
w = z_m - z_b has w'' = z_m'', and |z_m''| <= B2 on [s, s + h_cap]: the smaller of the
bound of the closed form's parts (``flow.part_bounds``) and the bound from the energy of the
whole state (``flow.state_bounds``; near resonance the parts, ~F/(d omega) each, nearly
cancel and the second is an order of magnitude tighter). From a point with gap g = 1 - w
(wall L) or 1 + w (wall R) >= 0 and closing speed c toward that wall, the gap stays above
g - c h - B h^2/2 for h <= H, where B (per wall, ``_wall_bounds``) takes the acceleration
towards the wall with its sign and the jerk and |z''''| bound with their Taylor weights
(H/3, H^2/12), at most B2; so the wall cannot be reached before
        h = 2 g / (c + sqrt(c^2 + 2 B g))       (root of c h + B h^2 / 2 = g;
                                                 (sqrt(...) - c)/B when c <= 0),
and each step goes to the smaller of the two walls' h (and at most h_cap = 1/rate); H is
chosen by a short fixed-point iteration towards the longest step its own bound allows
(``free_step_local``). The iteration approaches a transversal contact nearly cubically
(about five steps for a flight of half a period) and a grazing one geometrically,
and can never step over a wall. Contact is declared when c > 0 and g <= max(root_tol, floor),
and either g <= floor or the crossing is transversal (c^2 >= 2 B2 g); one Newton step
s += g/c then places the impact (error <= g/4). ``floor`` is the resolution of the computed
gap: a few ulps of |z_m|, |z_b| and of the parts of the closed form (homogeneous and
particular amplitudes, which can be far larger than z_m itself: F = 20 at resonance), plus
the change of the gap over a few ulps of the local time (c ulp(s)). Without it a root_tol
below the round-off of w could never be met and the step would shrink below ulp(s) (a
"stalled" run). Near-grazing approaches keep stepping conservatively (geometric
convergence) instead of taking a long, unsafe Newton step.
After an impact the ball sticks when |w'+| <= max(v_stick, v_floor), where v_floor is the
speed of a bounce only a few round-off units high (apex at least 4 x the floor above and
16 ROUNDOFF (1 + |z_m| + |z_b|): such bounces cannot be resolved; v_floor is ~2e-7 at
(eta, omega, F) = (0.05, 1, 0.05), ~3e-6 in the chatter at (0.2, 0.9, 0.4) and ~1e-4 for F = 20
at resonance, where |z_m| ~ 400 and the closed form's parts ~ 1700), and
the relative acceleration presses the ball onto the wall. Leaving a wall with zero
relative velocity (after sticking, or with r = 0) uses the first non-zero derivative of w
(second or third) and a bound on the next one to take a first step that provably moves away
(not applied while approaching the wall faster than round-off: that is a contact).

Release from sticking uses the same rule on the contact force, proportional to z_m'' of the
stuck body (mass 1 + eta), with a bound on z_m'''' (and the same kind of floor for z_m'').

Maximum of |z_m|: on each step interval [a, b] the value cannot exceed
max(|z(a)|, |z(b)|) + B2 (b - a)^2 / 8, nor the maximum of the cubic Hermite interpolant of
(z, z') at a and b plus B4 (b - a)^4 / 384; only intervals where both beat the running
maximum are refined (z' = 0 by safeguarded Newton from the interpolant's extremum, or
bisection).

Layout of ``run_kernel``: per segment, ``_advance_segment`` steps to the first event (free
flight: ``free_step_local`` / ``free_contact``; stuck: the same rules on the contact force),
``_land_on_event`` places an impact or release by one Newton step,
``_close_segment`` adds the segment's integrals, and ``_impact``, ``_start_sticking`` or
``_start_release`` start the next segment. Times are dimensionless (t, local time s = t - t0), the
forcing phase is omega t + phi, positions are in units of the half-clearance L.

Pauses (``run_kernel_until``, used by the periodic shortcut's section-by-section driver):
the run returns once it reaches t_pause, before a step inside a segment (the step state is
kept in ``acc``) or after the event closing the segment that holds t_pause, with a snapshot
of that segment in ``sec``; resuming gives the numbers of an uninterrupted run, bit for bit.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from .._jit import njit
from .flow import (
    I_D,
    I_FAMP,
    I_NRES,
    I_RATE,
    I_RES,
    deriv_bound,
    flow,
    flow_at_zero,
    flow_from,
    flow_start,
    forcing,
    part_bounds,
    state_bounds,
    v2_integral,
)
from .walls import WALL_L, WALL_R, impact_velocities

# Return codes of run_kernel. RC_PAUSED (``run_kernel_until`` only): the trajectory reached
# t_pause; ``sec`` holds the segment that contains t_pause and the counters at its start.
RC_DONE, RC_BUFFER_FULL, RC_MAX_IMPACTS, RC_STALLED, RC_PAUSED = 0, 1, 2, 3, 4
STATUS_TEXT = {RC_DONE: "ok", RC_MAX_IMPACTS: "max_impacts", RC_STALLED: "stalled"}

# Accumulator slots. A_SEG_S ... A_SEG_B1: local time reached in a segment interrupted by a
# pause and the closed form's (z, z', z'', z''', b1) there (``_advance_segment``).
A_INT_VM2, A_INT_VB2, A_XMAX_WIN, A_XMAX_ALL, A_TSTUCK_WIN, A_TSTUCK_ALL, A_NSTICK, A_NEVAL, \
    A_SEG_S, A_SEG_Z, A_SEG_V, A_SEG_A, A_SEG_J, A_SEG_B1 = range(14)
N_ACC = 14
# Counter slots. C_NIMP_L: impacts on wall L (whole run). C_SEG_STEP: > 0 while a segment
# is interrupted by a pause (the step index at which it resumes).
C_NIMP_TOTAL, C_NIMP_REC, C_NSEG_REC, C_NZERO, C_NIMP_L, C_SEG_STEP = range(6)
N_CNT = 6
# Slots of the pause snapshot ``sec`` (``run_kernel_until``): the start of the segment that
# contains t_pause (t0, z_m, z_m', z_b, z_b', mode), the time the segment had reached, and
# the counters and window integrals as they were at the segment start; from S_STACK on, the
# kernel's scratch (the bisection stack of ``_interval_max``: the kernel allocates nothing).
(S_T0, S_ZM, S_VM, S_ZB, S_VB, S_MODE, S_TREACHED, S_NIMP, S_NIMP_L, S_NSTICK, S_TSTUCK_ALL,
 S_TSTUCK_WIN, S_INT_VM2, S_INT_VB2, S_NIMP_REC, S_NSEG_REC, S_STACK) = range(17)
# Depth of the bisection of ``_interval_max`` (intervals shorter than MIN_BISECT are
# not split further), and the length of its stack (6 numbers an interval)
MAX_BISECT = 24
N_STACK = 6 * MAX_BISECT
N_SEC = S_STACK + N_STACK

# Walls (w = z_m - z_b = +1 and -1; impacts' ``wall`` column, first_contact's result).
# Segment modes (cur[CUR_MODE], seg[:, 5]): free flight, or stuck on wall WALL_L / WALL_R
# (the mode is the wall's sign).
MODE_FREE = 0
# How a segment ends (internal to run_kernel): at s_stop (t_transient or t_end), at an
# impact, at a release from sticking, when the ball is found pressed on a wall with zero
# relative velocity (it sticks), or stalled (a step below ulp(s), or the step limit
# reached with steps far below 1/rate: ``LONG_SEGMENT_STEP``).
EV_STOP, EV_IMPACT, EV_RELEASE, EV_STICK, EV_STALLED, EV_PAUSE = range(1, 7)
# first_contact returns CONTACT_PRESSED * wall when the ball starts pressed on that wall,
# CONTACT_STALLED when its steps did not reach a contact nor s_max (``first_contact``).
CONTACT_PRESSED = 2
CONTACT_STALLED = 3
# Slots of the state vector ``cur`` of run_kernel.
CUR_T, CUR_ZM, CUR_VM, CUR_ZB, CUR_VB, CUR_MODE, CUR_RELEASED = range(7)

#: The scalars of one kernel run, packed once (numba passes a named tuple by value, at no
#: cost): the oscillators of the free LO and of the stuck body (``flow.make_osc``), mass
#: ratio eta, restitution r, forcing frequency ratio omega and phase phi (forcing phase
#: omega t + phi), end of the run t_end and of the transient t_tr (the window is
#: [t_tr, t_end]), sticking speed v_stick, contact tolerance root_tol, the limit
#: max_impacts on impacts (whole run), and record_from: impacts and segments are recorded
#: from this time on. Build it with ``exact.kernel_params`` (floats and an int).
KernelParams = namedtuple("KernelParams", "osc_f osc_s eta r omega phi t_end t_tr v_stick "
                                          "root_tol max_impacts record_from")
#: One segment of the trajectory as the kernel steps it: mode (MODE_FREE or the wall it is
#: stuck on), released (a free flight that starts at a release from sticking), in_window
#: (t0 >= t_tr), start time t0, state (z_m, z_m', z_b, z_b') there, and sin, cos of the
#: forcing phase there.
Segment = namedtuple("Segment", "mode released in_window t0 zm0 vm0 zb0 vb0 sth0 cth0")

MAX_STEPS_PER_SEGMENT = 200_000
# A segment that takes MAX_STEPS_PER_SEGMENT steps without an event while its mean step is at
# least h_cap / LONG_SEGMENT_STEP (a long flight that never reaches a wall: 200000 steps
# cover only ~67000 time units at omega = 3) ends there, and the next segment goes on from
# that point (EV_STOP); one whose steps shrank below that is stalled
LONG_SEGMENT_STEP = 100.0
# evaluations of the step rule per step (``free_step_local``; odd: ends on a safe step)
N_STEP_ITER = 3
ROUNDOFF = 8.0 * 2.220446049250313e-16   # a few ulps: contact/release at this gap is exact


@njit(cache=True, nogil=True, inline="always")
def _floor(part, s, x, rate):
    """Resolution of a computed z^(n) of size |x| that changes at ``rate`` per unit time.

    A few ulps of |x| and of the magnitude ``part`` of its homogeneous and particular parts
    (``part_bounds`` at s), plus the change over a few ulps of the local time s.
    """
    return ROUNDOFF * (1.0 + abs(x) + part + abs(rate) * (1.0 + s))


@njit(cache=True, nogil=True, inline="always")
def _step_bounds(osc, z, v, b1, s, h_cap, parts):
    """Bounds for a step from local time s: the parts' sizes P0 ... P3 at s (for the
    floors), and bounds B2, B3, B4 of |z''|, |z'''|, |z''''| on [s, s + h_cap], each the
    smaller of the parts' bound (``part_bounds``; parts = ``part_bounds(osc, b1, s)``) and
    the whole state's (``state_bounds``, far tighter near resonance, where the parts nearly
    cancel)."""
    P0, P1, P2, P3, P4 = parts
    Q2, Q3, Q4 = P2, P3, P4
    if osc[I_RES] > 0.5 or osc[I_NRES] > 0.5:      # these parts' bounds grow with s
        _, _, Q2, Q3, Q4 = part_bounds(osc, b1, s + h_cap)
    T2, T3, T4 = state_bounds(osc, z, v, ROUNDOFF * (1.0 + P0 + P1), h_cap)
    return P0, P1, P2, P3, min(Q2, T2), min(Q3, T3), min(Q4, T4)


@njit(cache=True, nogil=True, inline="always")
def _safe_step(gap, closing, B):
    """Largest h with gap - closing h - B h^2/2 >= 0 for all [0, h] (B >= 0).

    The root is taken in the form without cancellation: 2 g/(c + D) when closing (c > 0),
    (D - c)/B when moving away (c <= 0), D = sqrt(c^2 + 2 B g). (2 g/(c + D) with c < 0
    cancels when 2 B g << c^2: a gap of one ulp after an impact then gave a step up to 10%
    too long, over the return to the same wall.)
    """
    if gap < 0.0:
        gap = 0.0
    disc = math.sqrt(closing * closing + 2.0 * B * gap)
    if closing > 0.0:
        return 2.0 * gap / (closing + disc)
    if B > 0.0:
        return (disc - closing) / B
    return math.inf if gap > 0.0 or closing < 0.0 else 0.0


# x_max refinement: a stationary point of z is placed to within EXTREMUM_DS / rate in local
# time, then z there is corrected by its Taylor term (error ~ (rate ds)^3 |z|, below round-off)
EXTREMUM_DS = 1e-6
MIN_BISECT = 1e-9


@njit(cache=True, nogil=True)
def _extremum(osc, start, pa, pb, s):
    """|z| at the zero of z' inside [sa, sb] (z'(sa) z'(sb) < 0), from the first guess s:
    safeguarded Halley iteration on z' (cubic: from the Hermite guess one step usually
    suffices), stopped once the next correction ds = -z'/z'' is below EXTREMUM_DS / rate,
    with z + z' ds / 2 as the value there. start: the closed form's (``flow.flow_start``),
    pa = (sa, z, z') and pb = (sb, z, z') the interval's ends."""
    sa, _, va = pa
    sb, _, vb = pb
    lo, hi = sa, sb
    vlo = va
    if not (lo < s < hi):
        s = sa - va * (sb - sa) / (vb - va)
    ds_tol = EXTREMUM_DS / osc[I_RATE]
    z = 0.0
    for _ in range(60):
        z, v, a, j, _ = flow_from(osc, start, s)
        if (v > 0.0) == (vlo > 0.0):
            lo = s
            vlo = v
        else:
            hi = s
        if a != 0.0 and abs(v) <= ds_tol * abs(a):
            return abs(z - 0.5 * v * v / a)
        s_new = 0.5 * (lo + hi)
        den = a - 0.5 * v * j / a if a != 0.0 else 0.0
        if den != 0.0:
            s_new = s - v / den
        if not (lo < s_new < hi):
            s_new = 0.5 * (lo + hi)
        if hi - lo <= 1e-12 * (1.0 + abs(s)):
            break
        s = s_new
    return abs(z)


@njit(cache=True, nogil=True)
def _hermite_max(za, va, zb, vb, h):
    """(max |p| on [0, h], where) for the cubic p with p(0) = za, p'(0) = va, p(h) = zb,
    p'(h) = vb (Hermite interpolation; |z - p| <= max|z''''| h^4 / 384 on [0, h])."""
    dz = (zb - za) / h
    c2 = (3.0 * dz - 2.0 * va - vb) / h
    c3 = (va + vb - 2.0 * dz) / (h * h)
    best, t_best = abs(za), 0.0
    if abs(zb) > best:
        best, t_best = abs(zb), h
    # p'(t) = va + 2 c2 t + 3 c3 t^2 = 0, roots without cancellation
    qa, qb, qc = 3.0 * c3, 2.0 * c2, va
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0 or (qa == 0.0 and qb == 0.0):
        return best, t_best
    q = -0.5 * (qb + math.copysign(math.sqrt(disc), qb))
    for t in (q / qa if qa != 0.0 else -1.0, qc / q if q != 0.0 else -1.0):
        if 0.0 < t < h:
            p = abs(za + t * (va + t * (c2 + t * c3)))
            if p > best:
                best, t_best = p, t
    return best, t_best


@njit(cache=True, nogil=True, inline="always")
def _may_exceed(za, va, zb, vb, h, B2, B4, m):
    """(max |z| on an interval of length h may exceed m, first guess of where):
    max(|z(a)|, |z(b)|) + B2 h^2/8 and the Hermite bound (``_hermite_max``) both bound it."""
    if max(abs(za), abs(zb)) + 0.125 * B2 * h * h <= m:
        return False, 0.0
    p, t = _hermite_max(za, va, zb, vb, h)
    return p + B4 * h * h * h * h / 384.0 > m, t


@njit(cache=True, nogil=True)
def _interval_max(osc, start, pa, pb, B2, B4, m, stack):
    """Running maximum m updated with max |z| over [sa, sb] (|z''| <= B2, |z''''| <= B4
    there): nothing more is computed where the bounds of ``_may_exceed`` stay <= m; a
    sign change of z' is refined by ``_extremum``, else the interval is bisected.
    start: the closed form's (``flow.flow_start``), pa = (sa, z, z'), pb = (sb, z, z');
    stack: N_STACK numbers of scratch (the intervals (a, z, z', b, z, z') to examine)."""
    sa, za, va = pa
    sb, zb, vb = pb
    m = max(m, abs(za), abs(zb))
    exceed, t = _may_exceed(za, va, zb, vb, sb - sa, B2, B4, m)
    if not exceed:
        return m
    if va * vb < 0.0:
        return max(m, _extremum(osc, start, pa, pb, sa + t))
    stack[0], stack[1], stack[2], stack[3], stack[4], stack[5] = sa, za, va, sb, zb, vb
    n = 1
    while n > 0:
        n -= 1
        i = 6 * n
        a_, za1, va1, b_, zb1, vb1 = stack[i], stack[i + 1], stack[i + 2], stack[i + 3], \
            stack[i + 4], stack[i + 5]
        exceed, t = _may_exceed(za1, va1, zb1, vb1, b_ - a_, B2, B4, m)
        if not exceed:
            continue
        if va1 * vb1 < 0.0:
            m = max(m, _extremum(osc, start, (a_, za1, va1), (b_, zb1, vb1), a_ + t))
            continue
        if n + 2 > MAX_BISECT or b_ - a_ <= MIN_BISECT:
            continue
        mid = 0.5 * (a_ + b_)
        zm, vm, _, _, _ = flow_from(osc, start, mid)
        m = max(m, abs(zm))
        stack[i], stack[i + 1], stack[i + 2], stack[i + 3], stack[i + 4], stack[i + 5] = \
            a_, za1, va1, mid, zm, vm
        stack[i + 6], stack[i + 7], stack[i + 8], stack[i + 9], stack[i + 10], \
            stack[i + 11] = mid, zm, vm, b_, zb1, vb1
        n += 2
    return m


@njit(cache=True, nogil=True, inline="always")
def _running_max(osc, start, pa, pb, B2, B4, m, stack):
    """``_interval_max``, its first test inline: most step intervals end there (the bound
    max(|z(a)|, |z(b)|) + B2 h^2/8 stays <= the running maximum), without a call."""
    za, zb = abs(pa[1]), abs(pb[1])
    h = pb[0] - pa[0]
    if max(za, zb) + 0.125 * B2 * h * h <= max(m, za, zb):
        return max(m, za, zb)
    return _interval_max(osc, start, pa, pb, B2, B4, m, stack)


@njit(cache=True, nogil=True, inline="always")
def free_step(pt, ball, bounds, floors, released):
    """Step that provably reaches neither wall in free flight (module docstring).

    pt = (s, z, z', z'', z''', b1): the LO's closed form at local time s (``flow``);
    ball = (zb0, vb0): the ball's free flight zb0 + vb0 s. bounds = (BL, BR, B3, B4): the
    gap to wall L (R) stays above g - c h - BL h^2/2 (BR) over the step
    (``_wall_bounds``); B3 and B4 bound |z_m'''| and |z_m''''| over [s, s + h_cap].
    floors = (tol_z, floor_v, floor_a): the contact tolerance on the gap, and the resolution
    of the computed relative velocity and acceleration (``_floor``).

    Returns (h, pressed): pressed = +1/-1 when the ball rests on that wall with no relative
    velocity while the relative acceleration presses it on (sticking), else 0.
    ``released`` is True at the first step after a release from sticking, where the
    acceleration is zero by construction and only the sign of the jerk decides.
    """
    s, z, v, a, j, _ = pt
    zb0, vb0 = ball
    BL, BR, B3, B4 = bounds
    tol_z, floor_v, floor_a = floors
    w = z - (zb0 + vb0 * s)
    wd = v - vb0
    gL = 1.0 - w
    gR = 1.0 + w
    hL = _safe_step(gL, wd, BL)
    hR = _safe_step(gR, -wd, BR)
    # departure from a wall with (almost) zero relative velocity; an approach faster than
    # round-off is left to the contact test (it must neither be stepped over nor stick)
    sw = 1.0 if gL <= gR else -1.0
    if min(gL, gR) <= tol_z and sw * wd <= floor_v:
        acc_away = -sw * a
        jerk_away = -sw * j
        # -w' stays > 0 on (0, h0] by a Taylor bound of order 2 (acceleration away) or 3
        # (jerk away, acceleration not towards the wall beyond round-off)
        h0 = 0.0
        if acc_away > 0.0:
            h0 = acc_away / B3
        if jerk_away > 0.0 and (released or acc_away >= -floor_a):
            h0 = max(h0, jerk_away / B4)
        if h0 == 0.0 and sw * wd >= -floor_v:
            return 0.0, int(sw)
        if sw > 0.0:
            hL = max(hL, h0)
        else:
            hR = max(hR, h0)
    return min(hL, hR), 0


@njit(cache=True, nogil=True, inline="always")
def _third(x):
    """x / 3, without the division when x = +-0 (then x itself: the jerk term of
    ``_wall_bounds`` is 0 for one wall or the other at almost every step)."""
    return x / 3.0 if x != 0.0 else x


@njit(cache=True, nogil=True, inline="always")
def _wall_bounds(a, j, H, B2g, B4, floor_a, floor_j):
    """(BL, BR, B) for steps h <= H from a point where w'' = z_m'' = a, w''' = j.

    The gap to wall L, g_L = 1 - w, obeys g_L(h) = g_L - w' h - int_0^h (h - t) w''(t) dt
    with w''(t) <= a + j t + B4 t^2/2, so it stays above g_L - w' h - BL h^2/2 with
    BL = a + max(j, 0) H/3 + B4 H^2/12 (>= 0), and BR likewise with -a, -j (each widened by
    the round-off floors of a and j, and at most B2g, the bound of |z''| on [s, s + h_cap]).
    The acceleration counts with its sign: one pointing away from the wall allows a long
    step, one towards it is taken exactly, and the contact is approached nearly cubically.
    B = min(B2g, |a| + |j| H + B4 H^2/2) bounds |w''| itself on [s, s + H].
    """
    rest = B4 * H * H / 12.0
    BL = min(B2g, max(0.0, a + floor_a + _third(max(j + floor_j, 0.0) * H) + rest))
    BR = min(B2g, max(0.0, -a + floor_a + _third(max(floor_j - j, 0.0) * H) + rest))
    return BL, BR, min(B2g, abs(a) + abs(j) * H + 0.5 * B4 * H * H)


@njit(cache=True, nogil=True, inline="always")
def free_step_local(osc, pt, ball, h_cap, root_tol, released, parts):
    """``free_step`` with bounds for the step length H itself (``_wall_bounds``).

    The bounds over [s, s + H] shrink with H, so the step phi(H) they allow grows as H
    shrinks: any H with phi(H) >= H is a safe step, and the odd iterates of
    H -> min(phi(H), h_cap) from h_cap are such steps, approaching the longest one
    (N_STEP_ITER evaluations). Returns (h, pressed, B2, B4) with B2 bounding |w''| on
    [s, s + h] and B4 (bound of |z''''|) valid on [s, s + h_cap]. parts:
    ``part_bounds(osc, b1, s)`` at the point pt.
    """
    s, z, v, a, j, b1 = pt
    zb0, vb0 = ball
    P0, P1, P2, P3, B2g, B3, B4 = _step_bounds(osc, z, v, b1, s, h_cap, parts)
    zb = zb0 + vb0 * s
    tol_z = max(root_tol, _floor(P0, s, abs(z) + abs(zb), v - vb0))
    floor_v = _floor(P1, s, abs(v) + abs(vb0), a)
    floor_a = _floor(P2, s, a, j)
    floor_j = _floor(P3, s, j, B4)
    floors = (tol_z, floor_v, floor_a)
    H = h_cap
    BL, BR, B = _wall_bounds(a, j, H, B2g, B4, floor_a, floor_j)
    h_best, B_best = H, B
    for it in range(N_STEP_ITER):
        h, pressed = free_step(pt, ball, (BL, BR, B3, B4), floors, released)
        if pressed != 0:
            return 0.0, pressed, B2g, B4
        if it % 2 == 0:
            if h >= H:
                return H, 0, B, B4           # the bounds allow all of [s, s + H]
            if it == 0 or h > h_best:
                h_best, B_best = h, B        # valid: h <= phi(H) with the bounds for H >= h
        H = min(h, h_cap)
        BL, BR, B = _wall_bounds(a, j, H, B2g, B4, floor_a, floor_j)
    return h_best, 0, B_best, B4


@njit(cache=True, nogil=True, inline="always")
def free_contact(osc, pt, ball, B2, root_tol, parts):
    """(wall, gap, closing speed) when contact is accepted at the point pt = (s, z, z',
    z'', z''', b1) of the LO's closed form (parts: ``part_bounds(osc, b1, s)`` there), the
    ball at ball = (z_b, z_b') there; else wall = 0."""
    s, z, v, _, _, _ = pt
    zb, vb = ball
    w = z - zb
    wd = v - vb
    if wd > 0.0:
        gap = max(1.0 - w, 0.0)
        closing = wd
        wall = WALL_L
    else:
        gap = max(1.0 + w, 0.0)
        closing = -wd
        wall = WALL_R
    P0, P1 = parts[0], parts[1]
    floor = _floor(P0, s, abs(z) + abs(zb), closing)
    # a closing speed at round-off level is no impact (the departure rule handles it)
    if closing > _floor(P1, s, abs(v) + abs(vb), 0.0) and gap <= max(root_tol, floor) \
            and (gap <= floor or closing * closing >= 2.0 * B2 * gap):
        return wall, gap, closing
    return 0, gap, closing


@njit(cache=True, nogil=True)
def first_contact(osc, x0, phase0, s_max, root_tol):
    """First wall contact of a free flight within local time [0, s_max].

    x0 = (z_m, z_m', z_b, z_b') at s = 0, phase0 = (sin, cos) of the forcing phase there.
    Same rule as the trajectory kernel. Returns (wall, s, z_m, z_m'): wall = WALL_L (+1) or
    WALL_R (-1) for an impact, 0 when no contact happens before s_max (then s = s_max),
    CONTACT_PRESSED * wall (+2/-2) when the ball starts pressed on that wall with zero
    relative velocity, and CONTACT_STALLED (3) with the point reached when the steps
    neither met a wall nor reached s_max (MAX_STEPS_PER_SEGMENT steps, or a step below
    ulp(s)): s, z_m, z_m' are always numbers, never NaN. A start on a wall moving into it
    (no step is possible) is an impact at s = 0, as in ``run_kernel``.
    """
    zm0, vm0, zb0, vb0 = x0
    sth0, cth0 = phase0
    ball = (zb0, vb0)
    h_cap = 1.0 / osc[I_RATE]
    s = 0.0
    z, v, a, j, b1 = flow(osc, zm0, vm0, sth0, cth0, 0.0)
    parts = part_bounds(osc, b1, s)
    for _ in range(MAX_STEPS_PER_SEGMENT):
        h, pressed, B2, _ = free_step_local(osc, (s, z, v, a, j, b1), ball, h_cap,
                                            root_tol, False, parts)
        if pressed != 0:
            return CONTACT_PRESSED * pressed, s, z, v
        h = min(h, h_cap)
        if s + h >= s_max:
            z, v, a, j, b1 = flow(osc, zm0, vm0, sth0, cth0, s_max)
            return 0, s_max, z, v
        if s + h <= s:   # no step at all: on a wall, approaching it (at s = 0: a start
            wall, gap, closing = free_contact(  # state there): an impact now, as run_kernel
                osc, (s, z, v, a, j, b1), (zb0 + vb0 * s, vb0), B2, root_tol, parts)
            if wall == 0:
                return CONTACT_STALLED, s, z, v
            s = s + gap / closing
            z, v, a, j, b1 = flow(osc, zm0, vm0, sth0, cth0, s)
            return wall, s, z, v
        s = s + h
        z, v, a, j, b1 = flow(osc, zm0, vm0, sth0, cth0, s)
        parts = part_bounds(osc, b1, s)
        wall, gap, closing = free_contact(osc, (s, z, v, a, j, b1), (zb0 + vb0 * s, vb0), B2,
                                          root_tol, parts)
        if wall != 0:
            s = s + gap / closing
            z, v, a, j, b1 = flow(osc, zm0, vm0, sth0, cth0, s)
            return wall, s, z, v
    return CONTACT_STALLED, s, z, v


# ---------------------------------------------------------------- segment helpers
# Parts of run_kernel, inlined into it at numba-IR level (inline="always"): as separate
# calls they made the kernel ~3% slower in instructions (~10% in time), inlined ~0.7%.

@njit(cache=True, nogil=True, inline="always")
def _record_row(buf, cnt, slot, row):
    """Append row = (t, z_m, z_m', z_b, z_b', last) to ``buf`` at row cnt[slot];
    cnt[slot] += 1."""
    k = cnt[slot]
    t, zm, vm, zb, vb, last = row
    buf[k, 0], buf[k, 1], buf[k, 2], buf[k, 3], buf[k, 4], buf[k, 5] = t, zm, vm, zb, vb, last
    cnt[slot] = k + 1


@njit(cache=True, nogil=True, inline="always")
def _set_state(cur, t, zm, vm, zb, vb, mode):
    """Start of the next segment: cur[CUR_T:CUR_MODE + 1] = (t, z_m, z_m', z_b, z_b', mode)."""
    cur[CUR_T], cur[CUR_ZM], cur[CUR_VM], cur[CUR_ZB], cur[CUR_VB], cur[CUR_MODE] = \
        t, zm, vm, zb, vb, mode


@njit(cache=True, nogil=True, inline="always")
def _common_velocity(eta, vm, vb):
    """Velocity of LO and ball moving as one body (momentum v_m + eta v_b conserved)."""
    return (vm + eta * vb) / (1.0 + eta)


@njit(cache=True, nogil=True, inline="always")
def _clamp_step(s, h, h_cap, s_stop):
    """(s_new, forced): s + min(h, h_cap), cut at s_stop (then forced = True)."""
    if h >= h_cap:
        h = h_cap
    if s + h >= s_stop:
        return s_stop, True
    return s + h, False


@njit(cache=True, nogil=True, inline="always")
def _start(sg):
    """(z_m, z_m', sin, cos of the forcing phase) at the start of segment ``sg``: the
    initial values of its closed form (``flow``)."""
    return sg.zm0, sg.vm0, sg.sth0, sg.cth0


@njit(cache=True, nogil=True, inline="always")
def _advance_segment(osc, sg, s_stop, root_tol, acc, step0, s_pause, stack):
    """Step segment ``sg`` (``Segment``; closed form of ``osc``) to its first event.

    Free flight: ``free_step_local`` steps, ``free_contact`` tests. Stuck (mode = wall):
    the contact force ~ mode z'' of the stuck body (mass 1 + eta) is the gap, -mode z''' its
    closing speed, with the same step and test rules (|z''''| <= B4). ``sg.released``: the
    segment starts at a release from sticking (first step only). Updates the |z_m| maxima
    and the step count in ``acc``. Returns (event, wall, pt, gap, closing, step) with
    pt = (s, z, z', z'', z''', b1) the closed form at the local time s of the event:
    EV_STICK (pressed on ``wall``), EV_IMPACT (at ``wall``),
    EV_RELEASE (gap, closing: for the final Newton step), EV_STOP (s = s_stop, or a long
    segment cut after MAX_STEPS_PER_SEGMENT steps: ``LONG_SEGMENT_STEP``), EV_STALLED,
    and the index of the step that would come next (last item).
    Pauses: before a step from s >= s_pause it returns EV_PAUSE; the caller stores s and
    the closed form there in acc[A_SEG_S:A_SEG_B1 + 1], and calling again with step0 = the
    returned index (1 for a new segment) resumes with bit-identical numbers (every other
    quantity of the loop is recomputed each step). s_pause = inf: no pause. stack: scratch
    of ``_interval_max`` (N_STACK numbers).
    The step loop stays in one function on purpose (hot path): its helpers are inlined
    (as calls they cost ~20 % of the kernel's time) and ``run_kernel_until`` runs without
    numba's reference counting (another ~20 %).
    """
    mode, in_window = sg.mode, sg.in_window
    zm0, vm0, sth0, cth0 = _start(sg)
    start = flow_start(osc, zm0, vm0, sth0, cth0)
    ball = (sg.zb0, sg.vb0)
    h_cap = 1.0 / osc[I_RATE]
    if step0 > 1:
        s, z, v, a, j, b1 = acc[A_SEG_S], acc[A_SEG_Z], acc[A_SEG_V], acc[A_SEG_A], \
            acc[A_SEG_J], acc[A_SEG_B1]
    else:
        s = 0.0
        z, v, a, j, b1 = flow_at_zero(osc, start)
    parts = part_bounds(osc, b1, s)     # at the current point, for the step and the test
    B4 = 0.0
    gap = 0.0
    closing = 0.0
    for steps in range(step0, MAX_STEPS_PER_SEGMENT + 1):
        if s >= s_pause:
            return EV_PAUSE, 0, (s, z, v, a, j, b1), gap, closing, steps
        if mode == MODE_FREE:
            h, pressed, B2, B4 = free_step_local(osc, (s, z, v, a, j, b1), ball, h_cap,
                                                 root_tol, sg.released and steps == 1, parts)
            if pressed != 0:
                return EV_STICK, pressed, (s, z, v, a, j, b1), gap, closing, steps
        else:
            _, _, _, _, B2, _, B4 = _step_bounds(osc, z, v, b1, s, h_cap, parts)
            gap = mode * a                    # contact force, > 0 while stuck
            closing = -mode * j
            h = _safe_step(gap, closing, B4)
        s_new, forced = _clamp_step(s, h, h_cap, s_stop)
        if s_new <= s:
            if mode == MODE_FREE:   # no step at all: on a wall, approaching it (a start
                wall, gap, closing = free_contact(  # state there): an impact right now
                    osc, (s, z, v, a, j, b1), (sg.zb0 + sg.vb0 * s, sg.vb0), B2, root_tol,
                    parts)
                if wall != 0:
                    return EV_IMPACT, wall, (s, z, v, a, j, b1), gap, closing, steps
            break
        z1, v1, a1, j1, b11 = flow_from(osc, start, s_new)
        if in_window:
            m = _running_max(osc, start, (s, z, v), (s_new, z1, v1), B2, B4,
                             acc[A_XMAX_WIN], stack)
            acc[A_XMAX_WIN] = m
            if m > acc[A_XMAX_ALL]:
                acc[A_XMAX_ALL] = m
        else:
            acc[A_XMAX_ALL] = _running_max(osc, start, (s, z, v), (s_new, z1, v1), B2, B4,
                                           acc[A_XMAX_ALL], stack)
        s, z, v, a, j, b1 = s_new, z1, v1, a1, j1, b11
        parts = part_bounds(osc, b1, s)
        acc[A_NEVAL] += 1.0
        if mode == MODE_FREE:
            wall, gap, closing = free_contact(osc, (s, z, v, a, j, b1),
                                              (sg.zb0 + sg.vb0 * s, sg.vb0), B2, root_tol,
                                              parts)
            if wall != 0:
                return EV_IMPACT, wall, (s, z, v, a, j, b1), gap, closing, steps
        else:                                 # release test on the contact force
            gap = mode * a
            closing = -mode * j
            floor = _floor(parts[2], s, a, closing)
            if closing > 0.0 and gap <= max(root_tol, floor) and (
                    gap <= floor or closing * closing >= 2.0 * B4 * gap):
                return EV_RELEASE, 0, (s, z, v, a, j, b1), max(gap, 0.0), closing, steps
        if forced:
            return EV_STOP, 0, (s, z, v, a, j, b1), gap, closing, steps
    # MAX_STEPS_PER_SEGMENT steps and no event: a long segment is cut here, the next one
    # starts from this point; one that hardly advanced is stalled
    event = EV_STOP if s * LONG_SEGMENT_STEP >= MAX_STEPS_PER_SEGMENT * h_cap else EV_STALLED
    return event, 0, (s, z, v, a, j, b1), gap, closing, MAX_STEPS_PER_SEGMENT + 1


@njit(cache=True, nogil=True, inline="always")
def _land_on_event(osc, sg, s_end, pt, gap, closing, acc):
    """One Newton step s += gap/closing onto the event surface (error ~ gap^2), never past
    the local time s_end of t_end; the maxima in ``acc`` see the new point. Returns the
    point pt = (s, z, z', z'', z''', b1) there."""
    s = pt[0]
    ds = gap / closing
    if s + ds > s_end:
        ds = max(s_end - s, 0.0)
    if ds > 0.0:
        s_new = s + ds
        zm0, vm0, sth0, cth0 = _start(sg)
        z1, v1, a1, j1, b11 = flow(osc, zm0, vm0, sth0, cth0, s_new)
        m_ref = acc[A_XMAX_WIN] if sg.in_window else acc[A_XMAX_ALL]
        if abs(z1) > m_ref:
            if sg.in_window:
                acc[A_XMAX_WIN] = abs(z1)
            if abs(z1) > acc[A_XMAX_ALL]:
                acc[A_XMAX_ALL] = abs(z1)
        return s_new, z1, v1, a1, j1, b11
    return pt


@njit(cache=True, nogil=True, inline="always")
def _clear_of_contact(osc, sg, s_end, pt):
    """Move a release forward (doubling round-off steps) until the contact force mode z'' is
    zero or pulling away, else the free flight would find the ball pressed again (a
    stick-release loop); never past the local time s_end of t_end. Returns the point
    pt = (s, z, z', z'', z''', b1) reached."""
    s, z, v, a, j, b1 = pt
    zm0, vm0, sth0, cth0 = _start(sg)
    delta = ROUNDOFF * (1.0 + sg.t0 + s)
    for _ in range(64):
        if sg.mode * a <= 0.0 or s + delta > s_end:
            break
        s = s + delta
        z, v, a, j, b1 = flow(osc, zm0, vm0, sth0, cth0, s)
        delta *= 2.0
    return s, z, v, a, j, b1


@njit(cache=True, nogil=True, inline="always")
def _close_segment(osc, sg, pt, acc, cnt):
    """Window integrals and time stuck over the segment ``sg`` up to the point pt = (s, z,
    z', ...); guard against segments that do not advance the absolute time (C_NZERO).
    Returns (t_new, z_b, z_b') at its end."""
    s, z, v = pt[0], pt[1], pt[2]
    mode, t0 = sg.mode, sg.t0
    if mode == MODE_FREE:
        vb_end = sg.vb0
        zb_end = sg.zb0 + sg.vb0 * s
    else:
        vb_end = v
        zb_end = z - mode
    if sg.in_window:
        zm0, vm0, sth0, cth0 = _start(sg)
        iv = v2_integral(osc, zm0, vm0, sth0, cth0, s)
        acc[A_INT_VM2] += iv
        if mode == MODE_FREE:
            acc[A_INT_VB2] += sg.vb0 * sg.vb0 * s
        else:
            acc[A_INT_VB2] += iv
            acc[A_TSTUCK_WIN] += s
    if mode != MODE_FREE:
        acc[A_TSTUCK_ALL] += s
    t_new = t0 + s
    cnt[C_NZERO] = cnt[C_NZERO] + 1 if t_new <= t0 else 0
    return t_new, zb_end, vb_end


@njit(cache=True, nogil=True, inline="always")
def _stick_speed_floor(osc_f, g, z, zb, b1, dvm):
    """Smallest resolvable rebound speed |w'+| at an impact (module docstring).

    Bounces lower than a few round-off units of w cannot be resolved: they count as
    sticking. Apex v^2/(2|g|) >= 16 ulps-scale of |z|, |z_b| and >= 4 contact floors,
    whose round-off includes the parts of the closed form of the next flight (b1 changes
    by at most dvm = |v_m+ - v_m-| at the impact). g: free LO acceleration.
    """
    zscale = 1.0 + abs(z) + abs(zb)
    zparts = deriv_bound(osc_f, b1 + dvm, 0, 0.0)
    return math.sqrt(2.0 * abs(g) * ROUNDOFF * max(16.0 * zscale, 4.0 * (zscale + zparts)))


@njit(cache=True, nogil=True, inline="always")
def _impact(cur, acc, cnt, imp, osc_f, law, sg, hit):
    """Impact hit = (s, t_new, z_m, z_m', z_b', b1, wall) at local time s of segment ``sg``
    (z_m, z_m', b1 from the closed form there, z_b' the ball's velocity), with
    law = (eta, r, v_stick, record_from).

    Records it (pre-impact state, ball placed exactly on the wall) from record_from on,
    applies the impact law and sets ``cur`` to the next segment: stuck on ``wall`` when
    the rebound is below max(v_stick, ``_stick_speed_floor``) and the free LO acceleration
    presses the ball on the wall, else free flight.
    """
    eta, r, v_stick, record_from = law
    s, t_new, z, v, vb, b1, wall = hit
    zb_imp = z - wall
    if t_new >= record_from:
        _record_row(imp, cnt, C_NIMP_REC, (t_new, z, v, zb_imp, vb, wall))
    cnt[C_NIMP_TOTAL] += 1
    if wall == WALL_L:
        cnt[C_NIMP_L] += 1
    vm_p, vb_p = impact_velocities(eta, r, v, vb)      # Newton's law, restitution r
    mode_new = MODE_FREE
    vc = _common_velocity(eta, v, vb)
    rebound = abs(vm_p - vb_p)
    dvm = abs(vm_p - v)
    # the floor grows with |g| <= FAMP + d |vc| + |z| (|forcing| <= FAMP): a rebound above
    # the floor of twice that bound cannot stick, and g (a sin and cos) is not needed
    g_max = 2.0 * (osc_f[I_FAMP] + osc_f[I_D] * abs(vc) + abs(z))
    if rebound <= max(v_stick, _stick_speed_floor(osc_f, g_max, z, zb_imp, b1, dvm)):
        g = forcing(osc_f, sg.sth0, sg.cth0, s) - osc_f[I_D] * vc - z  # free LO acceleration
        v_floor = _stick_speed_floor(osc_f, g, z, zb_imp, b1, dvm)
        if rebound <= max(v_stick, v_floor) and wall * g > 0.0:
            mode_new = wall
            vm_p = vc
            vb_p = vc
            acc[A_NSTICK] += 1.0
    _set_state(cur, t_new, z, vm_p, zb_imp, vb_p, mode_new)


@njit(cache=True, nogil=True, inline="always")
def _start_sticking(cur, acc, eta, t_new, z, v, vb, wall):
    """Ball found pressed on ``wall`` with zero relative velocity: stick (one body)."""
    vc = _common_velocity(eta, v, vb)
    acc[A_NSTICK] += 1.0
    _set_state(cur, t_new, z, vc, z - wall, vc, wall)


@njit(cache=True, nogil=True, inline="always")
def _start_release(cur, t_new, z, v, mode):
    """Release from wall ``mode``: free flight from the wall with zero relative velocity."""
    _set_state(cur, t_new, z, v, z - mode, v, MODE_FREE)
    cur[CUR_RELEASED] = 1.0


# ---------------------------------------------------------------- trajectory

@njit(cache=True, nogil=True, inline="always")
def _snapshot(sec, cur, acc, cnt, t_reached):
    """Pause snapshot (slots S_*): the segment starting at ``cur`` (not yet closed), the time
    it has reached, and the counters and integrals as they are at its start."""
    for k in range(6):
        sec[k] = cur[k]
    sec[S_TREACHED] = t_reached
    sec[S_NIMP], sec[S_NIMP_L] = cnt[C_NIMP_TOTAL], cnt[C_NIMP_L]
    sec[S_NSTICK], sec[S_TSTUCK_ALL] = acc[A_NSTICK], acc[A_TSTUCK_ALL]
    sec[S_TSTUCK_WIN], sec[S_INT_VM2], sec[S_INT_VB2] = \
        acc[A_TSTUCK_WIN], acc[A_INT_VM2], acc[A_INT_VB2]
    sec[S_NIMP_REC], sec[S_NSEG_REC] = cnt[C_NIMP_REC], cnt[C_NSEG_REC]


@njit(cache=True, nogil=True, inline="always")
def _next_segment(cur, cnt, seg, times):
    """The ``Segment`` starting at ``cur`` (recorded in ``seg`` from record_from on, unless
    it resumes after a pause) and the step it starts from (> 1: resumed);
    times = (omega, phi, t_tr, record_from)."""
    omega, phi, t_tr, record_from = times
    t0 = cur[CUR_T]
    zm0, vm0, zb0, vb0 = cur[CUR_ZM], cur[CUR_VM], cur[CUR_ZB], cur[CUR_VB]
    mode = int(cur[CUR_MODE])
    released = cur[CUR_RELEASED] != 0.0   # this free segment starts at a release
    cur[CUR_RELEASED] = 0.0
    step0 = cnt[C_SEG_STEP]               # > 0: resume a segment interrupted by a pause
    if step0 == 0:
        step0 = 1
        if t0 >= record_from:
            _record_row(seg, cnt, C_NSEG_REC, (t0, zm0, vm0, zb0, vb0, mode))
    cnt[C_SEG_STEP] = 0
    th0 = omega * t0 + phi
    sg = Segment(mode, released, t0 >= t_tr, t0, zm0, vm0, zb0, vb0, math.sin(th0),
                 math.cos(th0))
    return sg, step0


@njit(cache=True, nogil=True)
def run_kernel(kp, ks, imp, seg):
    """Advance the trajectory in ``cur`` = [t, z_m, z_m', z_b, z_b', mode, released] to t_end.

    kp             the run's ``KernelParams`` (oscillators, model, window, tolerances)
    ks             (cur, acc, cnt): the kernel state (slots CUR_*, A_*, C_*)
    imp            (cap, 6) buffer of impacts: t, z_m, z_m', z_b, z_b' (pre-impact), wall
    seg            (cap, 6) buffer of segment starts: t0, z_m, z_m', z_b, z_b', mode
    Impacts and segments are recorded only from t >= record_from. ``cur``, ``acc`` and
    ``cnt`` are updated in place, so a call that returns RC_BUFFER_FULL can be resumed with
    larger buffers. Returns one of RC_DONE, RC_BUFFER_FULL, RC_MAX_IMPACTS, RC_STALLED.
    """
    sec = np.empty(N_SEC)
    return run_kernel_until(kp, ks, imp, seg, math.inf, sec)


# _nrt=False: numba's option to compile without its runtime (numba's own extending
# example, ``register_jitable(_nrt=False)``): no reference counting of the arrays the
# inlined helpers pass around (atomic increments, ~20 % of the kernel's time), and nothing
# in it or its callees may allocate (compile error if one does).
@njit(cache=True, nogil=True, _nrt=False)
def run_kernel_until(kp, ks, imp, seg, t_pause, sec):
    """``run_kernel`` that also returns RC_PAUSED once the trajectory reaches t_pause.

    The pause comes either inside a segment, before the first step from a time >= t_pause,
    or after the event that closes the segment containing t_pause; ``sec`` then holds that
    segment's start and the counters at its start (``_snapshot``), so the state at t_pause
    follows from the closed form. Calling again (with a later t_pause, or inf) continues
    with exactly the numbers of an uninterrupted run: pausing never changes the trajectory.
    """
    cur, acc, cnt = ks
    osc_f, osc_s = kp.osc_f, kp.osc_s
    eta, r, omega, phi, t_end, t_tr, v_stick, root_tol, max_impacts, record_from = kp[2:]
    law = (eta, r, v_stick, record_from)
    times = (omega, phi, t_tr, record_from)
    while True:
        t0 = cur[CUR_T]
        if cnt[C_NZERO] > 1000:
            return RC_STALLED
        if t0 >= t_end:
            return RC_DONE
        if cnt[C_NSEG_REC] >= seg.shape[0] or cnt[C_NIMP_REC] >= imp.shape[0]:
            return RC_BUFFER_FULL
        sg, step0 = _next_segment(cur, cnt, seg, times)
        osc = osc_f if sg.mode == MODE_FREE else osc_s
        s_stop = t_end - t0
        if t0 < t_tr:
            s_stop = min(s_stop, t_tr - t0)
        event, wall, pt, gap, closing, steps = _advance_segment(
            osc, sg, s_stop, root_tol, acc, step0, t_pause - t0, sec[S_STACK:])
        if event == EV_PAUSE:
            _snapshot(sec, cur, acc, cnt, t0 + pt[0])
            acc[A_SEG_S], acc[A_SEG_Z], acc[A_SEG_V], acc[A_SEG_A], acc[A_SEG_J], \
                acc[A_SEG_B1] = pt
            cnt[C_SEG_STEP] = steps
            cur[CUR_RELEASED] = 1.0 if sg.released else 0.0
            return RC_PAUSED
        if event == EV_STALLED:
            cur[CUR_T] = t0
            return RC_STALLED
        if event == EV_IMPACT or event == EV_RELEASE:  # noqa: SIM109 (numba: no tuple search)
            pt = _land_on_event(osc, sg, t_end - t0, pt, gap, closing, acc)
        if event == EV_RELEASE:
            pt = _clear_of_contact(osc, sg, t_end - t0, pt)
        paused = t0 + pt[0] >= t_pause
        if paused:
            _snapshot(sec, cur, acc, cnt, t0 + pt[0])
        end = _close_segment(osc, sg, pt, acc, cnt)
        t_new, zb_end, vb_end = end
        if event == EV_STOP:
            _set_state(cur, t_new, pt[1], pt[2], zb_end, vb_end, sg.mode)
            if t_new >= t_end:
                cur[CUR_T] = t_end
                return RC_DONE
        elif event == EV_RELEASE:
            _start_release(cur, t_new, pt[1], pt[2], sg.mode)
        elif event == EV_STICK:
            _start_sticking(cur, acc, eta, t_new, pt[1], pt[2], vb_end, wall)
        else:
            _impact(cur, acc, cnt, imp, osc_f, law, sg,
                    (pt[0], t_new, pt[1], pt[2], vb_end, pt[5], wall))
            if cnt[C_NIMP_TOTAL] >= max_impacts:
                return RC_MAX_IMPACTS
        if paused:
            return RC_PAUSED


@njit(cache=True, nogil=True)
def dense_states(seg, idx, times, osc_f, osc_s, omega, phi, out):
    """State (z_m, z_m', z_b, z_b') at ``times``; idx[k] is the segment holding times[k].

    seg as recorded by ``run_kernel``; omega, phi: forcing frequency ratio and phase.
    """
    for k in range(times.shape[0]):
        i = idx[k]
        t0 = seg[i, 0]
        mode = int(seg[i, 5])
        osc = osc_f if mode == MODE_FREE else osc_s
        th0 = omega * t0 + phi
        s = times[k] - t0
        z, v, _, _, _ = flow(osc, seg[i, 1], seg[i, 2], math.sin(th0), math.cos(th0), s)
        out[0, k] = z
        out[1, k] = v
        if mode == MODE_FREE:
            out[2, k] = seg[i, 3] + seg[i, 4] * s
            out[3, k] = seg[i, 4]
        else:
            out[2, k] = z - mode
            out[3, k] = v
