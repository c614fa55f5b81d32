"""Exact periodic shortcut: detect a settled periodic orbit, then model one period of it.

Most runs settle on a periodic orbit long before t_transient. The driver runs the kernel
section by section (``kernel.run_kernel_until``: pausing never changes the trajectory) and
watches the stroboscopic section x_k = state(t_k), t_k = t_transient + k T (T = 2 pi/omega,
the times of ``regime.strobe_times``). The state x = (z_m, z_m', z_b, z_b') plus the segment
mode (free, or stuck on a wall) determines the future: the forcing phase is the same at
every t_k, and z_b is kept absolute, not only w = z_m - z_b, so a ball drifting through the
cavity (z_b' != 0 without impacts) is never taken as periodic.

Differences of states are relative (``rel_diff``): the LO part (z_m, z_m') to
max(|z_m|, |z_m'|), the ball part (z_b, z_b') to the larger of that and max(|z_b|, |z_b'|),
so an LO decaying towards rest is never "periodic" relative to a resting ball's position.
A period p (1 <= p <= P_MAX) is declared at section k when

* the last N_CONFIRM p returns agree, rel_diff(x_i, x_(i-p)) <= SEC_TOL, with the same mode
  and the same impacts per forcing period (total, on wall L), stick starts and time stuck
  (to SEC_TOL T) as p periods earlier: the impact sequence repeats;
* the distance to the orbit, estimated as d / (1 - rho^p) with d the largest of the last p
  differences and rho the contraction per section measured since the last difference above
  DECAY_REF (or since the first one), is at most ERR_TOL (relative). Differences at the
  round-off floor (~1e-12) only make rho larger, and complex Floquet multipliers lambda
  give |1 - lambda^p| >= 1 - |lambda|^p, so the estimate stays an upper one.

A candidate period that is a multiple of the orbit's least period is reported as the
smallest divisor whose returns agree as long. Motion far from every period (all returns
differ by more than FAR, or in their events) is observed only in bursts (SKIP): that bounds
the cost on runs that never settle.

``exact._run_with_shortcut`` then integrates one period [t_s, t_s + pT] from x(t_s),
checks that it returns to x(t_s) with the same events, and builds every measure over
[t_transient, t_end] from whole periods plus the exact partial periods at the ends.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from .flow import I_D, I_NRES, I_OM, I_PAMP, I_RES, flow, v2_integral
from .kernel import (
    A_XMAX_ALL,
    MODE_FREE,
    RC_PAUSED,
    S_MODE,
    S_NIMP,
    S_NIMP_L,
    S_NSTICK,
    S_T0,
    S_TREACHED,
    S_TSTUCK_ALL,
    S_VB,
    S_VM,
    S_ZB,
    S_ZM,
    run_kernel_until,
)
from .regime import MAX_PERIOD

#: largest period (in forcing periods) the section is tested for
P_MAX = MAX_PERIOD
#: periods of the orbit (p returns each) that must repeat before the shortcut is taken
N_CONFIRM = 3
#: agreement of one return, relative to max |x| at the section
SEC_TOL = 2e-10
#: largest accepted estimate of the distance to the orbit, relative to max |x|
ERR_TOL = 1e-10
#: differences above this level restart the measurement of the contraction rate
DECAY_REF = 1e-6
#: no detection within this many forcing periods of t_end (a shortcut would not pay)
END_MARGIN = 4
#: back-off on motion far from any period: after p_max + 2 consecutive sections where every
#: return differs by more than FAR (relative) or in its events, SKIP sections are not
#: observed (the kernel runs through them without pausing); this bounds the cost on runs
#: that never settle, and delays a detection by at most SKIP periods
FAR = 1e-3
SKIP = 32

RC_PERIODIC = 5   # run_detect: a periodic orbit was detected (kernel.RC_* otherwise)
RC_AT_REST = 6    # run_detect: the ball rests out of the LO's reach until t_end

# hist columns (one row per section, ring buffer of H_ROWS rows)
H_X, H_MODE, H_NIMP, H_NIMP_L, H_NSTICK, H_TSTUCK, H_T, H_VALID = 0, 4, 5, 6, 7, 8, 9, 10
N_HIST = 11
H_ROWS = P_MAX + 2
# ist: row 0 = (section count k, index j of the next section t_tr + j T, period found,
# p_max, n_confirm, k of the first section after the last skip, consecutive far
# sections, 1 while the at-rest test is on); row 1 = first index of the current run of agreeing returns per p;
# row 2 = index of the reference difference per p. fst: row 0 = (T, t_transient, t_stop,
# sec_tol, err_tol, decay_ref); row 1 = reference difference per p.
I_K, I_J, I_FOUND, I_PMAX, I_NCONF, I_KSTART, I_NFAR, I_REST = range(8)
F_T, F_TTR, F_TSTOP, F_SECTOL, F_ERRTOL, F_REF, F_FAR = range(7)


def section_time_floor(T: float, t_transient: float, t_end: float) -> float:
    """Relative change of the state over the rounding of the section times.

    t_k = t_transient + j T is rounded to ~ulp(max(|t_transient|, |t_end|)); the state
    moves at a relative rate of about max(1, omega) (natural frequency 1), so two returns
    of an exactly periodic orbit can differ by this much. It is ~4e-12 for the defaults
    (far below SEC_TOL) and ~4e-9 for t_transient = 2.5e6; the tolerances are never
    tighter than it, or such runs would never be found periodic.
    """
    rate = max(1.0, 2.0 * math.pi / T)
    return 4.0 * rate * math.ulp(max(abs(t_transient), abs(t_end)))


def new_detector(T: float, t_transient: float, t_start: float, t_end: float,
                 p_max: int = P_MAX) -> tuple:
    """Detector state (hist, dr, ist, fst) for sections t_transient + j T > t_start.

    Sections within END_MARGIN periods of t_end are not tested.
    """
    hist = np.zeros((H_ROWS, N_HIST))
    dr = np.zeros((P_MAX + 1, H_ROWS))
    ist = np.zeros((3, P_MAX + 1), dtype=np.int64)
    fst = np.zeros((2, P_MAX + 1))
    ist[0, I_J] = math.floor((t_start - t_transient) / T) + 1
    ist[0, I_PMAX] = min(int(p_max), P_MAX)
    ist[0, I_NCONF] = N_CONFIRM
    ist[0, I_REST] = 1
    ist[2, :] = -1
    fst[0, F_T], fst[0, F_TTR] = T, t_transient
    fst[0, F_TSTOP] = t_end - END_MARGIN * T
    floor = section_time_floor(T, t_transient, t_end)
    fst[0, F_SECTOL] = max(SEC_TOL, floor)
    fst[0, F_ERRTOL] = max(ERR_TOL, 2.0 * floor)
    fst[0, F_REF] = DECAY_REF
    fst[0, F_FAR] = FAR
    return hist, dr, ist, fst


@njit(cache=True, nogil=True, inline="always")
def section_state(osc_f, osc_s, omega, phi, sec, t):
    """(z_m, z_m', z_b, z_b') at time t inside the snapshot segment ``sec`` (kernel S_*)."""
    mode = int(sec[S_MODE])
    osc = osc_f if mode == MODE_FREE else osc_s
    th0 = omega * sec[S_T0] + phi
    s = t - sec[S_T0]
    z, v, _, _, _ = flow(osc, sec[S_ZM], sec[S_VM], math.sin(th0), math.cos(th0), s)
    if mode == MODE_FREE:
        return z, v, sec[S_ZB] + sec[S_VB] * s, sec[S_VB]
    return z, v, z - mode, v


@njit(cache=True, nogil=True, inline="always")
def _ratio(a, scale):
    return a / scale if scale > 0.0 else (0.0 if a == 0.0 else math.inf)


@njit(cache=True, nogil=True, inline="always")
def rel_diff(x, y):
    """Relative difference of two states (z_m, z_m', z_b, z_b') (module docstring)."""
    sm = max(abs(x[0]), abs(x[1]))
    sb = max(abs(x[2]), abs(x[3]), sm)
    dm = max(abs(x[0] - y[0]), abs(x[1] - y[1]))
    db = max(abs(x[2] - y[2]), abs(x[3] - y[3]))
    return max(_ratio(dm, sm), _ratio(db, sb))


@njit(cache=True, nogil=True)
def segment_integrals(osc_f, osc_s, omega, phi, sec, t):
    """Integrals of z_m'^2 and z_b'^2 over [t0, t] of the snapshot segment ``sec`` (as the
    kernel's ``_close_segment`` computes them)."""
    mode = int(sec[S_MODE])
    osc = osc_f if mode == MODE_FREE else osc_s
    th0 = omega * sec[S_T0] + phi
    L = t - sec[S_T0]
    iv = v2_integral(osc, sec[S_ZM], sec[S_VM], math.sin(th0), math.cos(th0), L)
    if mode == MODE_FREE:
        return iv, sec[S_VB] * sec[S_VB] * L
    return iv, iv


@njit(cache=True, nogil=True, inline="always")
def _back(row, n, H):
    """Ring row n sections before ``row`` (0 <= n < H; no integer division: hot path)."""
    return row - n if row >= n else row - n + H


@njit(cache=True, nogil=True, inline="always")
def _same_events(hist, a, a1, p, t_tol):
    """Impacts (total, on L), stick starts and time stuck in the period ending at the
    section in ring row a (previous section: row a1) equal those p periods earlier."""
    H = hist.shape[0]
    b, b1 = _back(a, p, H), _back(a, p + 1, H)
    for c in range(H_NIMP, H_NSTICK + 1):
        if hist[a, c] - hist[a1, c] != hist[b, c] - hist[b1, c]:
            return False
    da = hist[a, H_TSTUCK] - hist[a1, H_TSTUCK]
    db = hist[b, H_TSTUCK] - hist[b1, H_TSTUCK]
    return abs(da - db) <= t_tol


@njit(cache=True, nogil=True, inline="always")
def _repeat_mask(hist, k, k_start, p_max, t_tol):
    """Bit p set when the events of the period ending at section k (counts already in its
    hist row) equal those p periods earlier (``_same_events``), 1 <= p <= p_max, where
    sections k - p - 1 ... k are consecutive (none before k_start)."""
    H = hist.shape[0]
    a = k % H
    a1 = _back(a, 1, H)
    mask = 0
    for p in range(1, min(p_max, k - k_start - 1) + 1):
        if _same_events(hist, a, a1, p, t_tol):
            mask |= 1 << p
    return mask


@njit(cache=True, nogil=True, inline="always")
def _settled(dr, p, k, row, k_ref, d_ref, err_tol):
    """Estimated distance to the orbit (relative) <= err_tol (module docstring); section
    k is in ring row ``row``."""
    dmax = 0.0
    for i in range(p):
        dmax = max(dmax, dr[p, _back(row, i, dr.shape[1])])
    if dmax == 0.0:
        return True                     # exact repetition (e.g. nothing moves)
    n = k - k_ref
    if n <= 0 or d_ref <= dmax:
        return False
    rho_p = (dmax / d_ref) ** (p / n)   # contraction per p periods, an upper estimate
    return dmax <= err_tol * (1.0 - rho_p)


@njit(cache=True, nogil=True, inline="always")
def observe(hist, dr, ist, fst, x, mode, mask):
    """Add section k = ist[0, I_K] (state x and segment mode at t_k; the counts are already
    in its hist row) and return the smallest settled period, or 0. Only periods p with bit
    p of ``mask`` (``_repeat_mask``) are compared; mask = 0: x was not evaluated."""
    H = hist.shape[0]
    k = ist[0, I_K]
    row = k % H
    for c in range(4):
        hist[row, H_X + c] = x[c]
    hist[row, H_MODE] = mode
    hist[row, H_VALID] = 1.0 if mask != 0 else 0.0
    found = 0
    near = False
    for p in range(1, ist[0, I_PMAX] + 1):
        q = _back(row, p, H)
        if k - ist[0, I_KSTART] < p + 1 or (mask >> p) & 1 == 0 or hist[q, H_VALID] == 0.0 \
                or mode != hist[q, H_MODE]:
            ist[1, p], ist[2, p] = k + 1, -1      # no agreement; decay measured anew
            continue
        d = rel_diff(x, hist[q, H_X:H_X + 4])
        dr[p, row] = d
        near = near or d <= fst[0, F_FAR]
        if d > fst[0, F_REF] or ist[2, p] < 0:
            ist[2, p], fst[1, p] = k, d
        if not d <= fst[0, F_SECTOL]:
            ist[1, p] = k + 1
        elif found == 0 and k - ist[1, p] + 1 >= ist[0, I_NCONF] * p and \
                _settled(dr, p, k, row, ist[2, p], fst[1, p], fst[0, F_ERRTOL]):
            found = p
    ist[0, I_K] = k + 1
    ist[0, I_NFAR] = 0 if near else ist[0, I_NFAR] + 1
    # the error estimate may pass first for a multiple of the period (rho^p is smaller):
    # report the smallest divisor whose returns agree as long
    for q in range(1, found):
        if found % q == 0 and k - ist[1, q] + 1 >= ist[0, I_NCONF] * q:
            return q
    return found


@njit(cache=True, nogil=True, inline="always")
def at_rest(osc_f, omega, phi, sec, t_k, t_tr, xmax_so_far, err_tol):
    """Ball at rest out of reach: 1 when, from the free segment ``sec`` at t_k < t_tr with
    z_b' = 0, the LO can never reach a wall (|z_b| + max |z_m| < 1 for all later times, by
    the energy bound of ``flow``: damped, non-resonant form), |z_m| never again exceeds
    ``xmax_so_far``, and at t_tr the decaying homogeneous part is at most err_tol relative
    to the state. Then the run until t_transient is this one segment (the kernel's state
    at t_tr is its closed form) and from there periodic to err_tol. 0: not yet (the
    bounds may hold at a later section); -1: never (undamped, or transient too large at
    t_tr)."""
    if osc_f[I_RES] > 0.5 or osc_f[I_NRES] > 0.5 or not osc_f[I_D] > 0.0:
        return -1
    th0 = omega * sec[S_T0] + phi
    sth0, cth0 = math.sin(th0), math.cos(th0)
    z, v, _, _, b1 = flow(osc_f, sec[S_ZM], sec[S_VM], sth0, cth0, t_k - sec[S_T0])
    zmax = b1 / osc_f[I_OM] + osc_f[I_PAMP]          # bound on |z_m| from t_k on
    if abs(sec[S_ZB]) + zmax >= 1.0 - 1e-9 or xmax_so_far < zmax:
        return 0
    z, v, _, _, b1 = flow(osc_f, sec[S_ZM], sec[S_VM], sth0, cth0, t_tr - sec[S_T0])
    h = b1 * max(1.0, 1.0 / osc_f[I_OM])             # bound on |z_h|, |z_h'| at t_tr
    return 1 if h <= err_tol * max(abs(z), abs(v)) else -1


@njit(cache=True, nogil=True, inline="always")
def _pending_sections(kp, sec, det, work, xmax_so_far):
    """Observe every section time the snapshot segment has reached; returns the period
    found (the section is then hist row (ist[0, I_K] - 1) % H), -1 when the ball rests out
    of reach (``at_rest``), or 0. kp: the run's ``kernel.KernelParams``; det = (hist, dr,
    ist, fst) (``new_detector``); work = (x, counts): work arrays of 4."""
    hist, dr, ist, fst = det
    x, counts = work
    osc_f, osc_s, omega, phi = kp.osc_f, kp.osc_s, kp.omega, kp.phi
    while True:
        t_k = fst[0, F_TTR] + ist[0, I_J] * fst[0, F_T]
        if t_k > sec[S_TREACHED] or t_k > fst[0, F_TSTOP]:
            return 0
        mode = int(sec[S_MODE])
        if ist[0, I_REST] == 1 and mode == MODE_FREE and sec[S_VB] == 0.0 \
                and t_k < fst[0, F_TTR]:
            rest = at_rest(osc_f, omega, phi, sec, t_k, fst[0, F_TTR], xmax_so_far,
                           fst[0, F_ERRTOL])
            if rest == 1:
                return -1
            if rest == -1:
                ist[0, I_REST] = 0
        counts[0], counts[1], counts[2] = sec[S_NIMP], sec[S_NIMP_L], sec[S_NSTICK]
        counts[3] = sec[S_TSTUCK_ALL] + (t_k - sec[S_T0] if mode != MODE_FREE else 0.0)
        k = ist[0, I_K]
        row = k % hist.shape[0]
        hist[row, H_T] = t_k
        for c in range(4):
            hist[row, H_NIMP + c] = counts[c]
        mask = _repeat_mask(hist, k, ist[0, I_KSTART], ist[0, I_PMAX],
                            fst[0, F_SECTOL] * fst[0, F_T])
        if mask != 0:           # else no candidate period: skip the closed form
            x[0], x[1], x[2], x[3] = section_state(osc_f, osc_s, omega, phi, sec, t_k)
        ist[0, I_J] += 1
        p = observe(hist, dr, ist, fst, x, mode, mask)
        if p > 0:
            ist[0, I_FOUND] = p
            return p
        if ist[0, I_NFAR] >= ist[0, I_PMAX] + 2:        # back off (SKIP)
            ist[0, I_J] += SKIP
            ist[0, I_KSTART] = ist[0, I_K]
            ist[0, I_NFAR] = 0


@njit(cache=True, nogil=True)
def run_detect(kp, ks, imp, seg, sec, det):
    """Run the kernel section by section until a periodic orbit is detected (RC_PERIODIC,
    period in ist[0, I_FOUND], the kernel paused inside the segment ``sec``) or the kernel
    returns (RC_DONE, RC_BUFFER_FULL, ...); RC_AT_REST when the ball rests out of the LO's
    reach (``at_rest``). Resumable: call again to continue. kp, ks, imp, seg as for
    ``kernel.run_kernel``; det = (hist, dr, ist, fst) (``new_detector``)."""
    ist, fst = det[2], det[3]
    acc = ks[1]
    work = (np.empty(4), np.empty(4))
    while True:
        found = _pending_sections(kp, sec, det, work, acc[A_XMAX_ALL])
        if found > 0:
            return RC_PERIODIC
        if found < 0:
            return RC_AT_REST
        t_next = fst[0, F_TTR] + ist[0, I_J] * fst[0, F_T]
        t_pause = t_next if t_next <= fst[0, F_TSTOP] else math.inf
        rc = run_kernel_until(kp, ks, imp, seg, t_pause, sec)
        if rc != RC_PAUSED:
            return rc
