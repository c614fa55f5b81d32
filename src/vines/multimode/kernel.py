"""Event-driven exact engine of a linear host with absorbers (numba, nogil).

Segments: between two events the set of stuck absorbers (the configuration c, a bit mask)
is fixed and every coordinate is the closed form of ``system``: in local time s = t - t0,

    row(s) = Re(sum_k R[row, k] e^{lam_k s}) + Re(H[row] e^{i omega s}) + b0[row] + b1[row] s,

rows: the full positions (host x_0 .. x_{N-1}, absorbers y_0 ..) and the gaps
w_i = x_{j_i} - y_i; R = (mode shapes) x (modal amplitudes of the start state), H the
harmonic particular solution at the segment's start phase, b0, b1 the free flight of an
absorber without link (and the offset -k L of a stuck one).

Events are found by a step rule that cannot step over one (docs/model.md, "General model"):
every Re(lam_k) <= 0, so for all s' >= s

    |row^(n)(s')| <= B_n = sum_k |R[row, k]| |lam_k|^n e^{Re(lam_k) s} + |H[row]| omega^n,

and from a gap g to a wall, closing at speed c, the wall cannot be reached before
h = 2 g / (c + sqrt(c^2 + 2 B_2 g)) (``_safe_step``); steps converge quadratically on a
transversal contact and geometrically on a grazing one. Contact is accepted within
max(root_tol L, floor) of the wall when transversal (c^2 >= 2 B_2 g) or at the round-off
floor, then placed by one Newton step s += g / c. A stuck absorber's contact force
k (m x_j'' - k_i k L) is followed the same way (its second derivative bounded by
m B_4 of x_j) until it reaches zero: release.

Impacts (``_resolve``): the pair law per absorber (impulse P on host dof j, -P on the
absorber; the host's velocities change by Minv e_j P, Minv the inverse of the host mass
matrix with the stuck absorbers' masses lumped): momentum conserved and w'+ = -r w'-. Pairs
in contact at the same time are resolved one by one until none approaches. After an impact
with |w'+| <= max(v_stick, v_floor) the absorber sticks (a plastic impulse makes w' = 0); a
stuck absorber that an impulse would pull off its wall is freed first.

Measures over each step by 8-point Gauss quadrature of the closed form (steps are at most
1/omega_max long): kinetic energies, each damper's dissipation, the forcing's work; maxima
of |x_j|, |x_j''| and |w_i| by the derivative's root where it changes sign and a bound
elsewhere. Memory is fixed: window and whole-run accumulators, the first n_record impacts.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit

ROUNDOFF = 8.0 * 2.220446049250313e-16
MAX_STEPS_PER_SEGMENT = 2_000_000
MAX_RESOLVE = 1000
MAX_ZERO_SEGMENTS = 1000
MAX_BISECT = 40

# status codes
RC_DONE, RC_MAX_IMPACTS, RC_STALLED = 0, 2, 3
STATUS_TEXT = {RC_DONE: "ok", RC_MAX_IMPACTS: "max_impacts", RC_STALLED: "stalled"}
# cnt slots
C_STATUS, C_NREC, C_NSTEPS, C_NSEG, C_NIMP = range(5)
N_CNT = 5
# acc rows (columns: host dof or absorber index; col 0 for scalars). Window: [t_tr, t_end]
(A_XMAX, A_AMAX, A_TRAVEL, A_XMAX_ALL, A_KE_ABS, A_KE_HOST, A_DISS_ABS, A_DISS_HOST,
 A_IMP_LOSS, A_WORK, A_NIMP, A_NIMP_L, A_TSTUCK, A_DISS_ABS_ALL, A_DISS_HOST_ALL,
 A_IMP_LOSS_ALL, A_WORK_ALL, A_NIMP_ALL, A_TSTUCK_ALL, A_TRAVEL_ALL) = range(20)
N_ACC = 20
# record columns: t, absorber, wall, w' before, w' after, stuck after (1/0); a ring buffer
N_REC = 6

# 8-point Gauss-Legendre nodes and weights on [0, 1]
_GX = np.array([-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                -0.1834346424956498, 0.1834346424956498, 0.5255324099163290,
                0.7966664774136267, 0.9602898564975363])
_GW = np.array([0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                0.2223810344533745, 0.1012285362903763])
GX = 0.5 * (_GX + 1.0)
GW = 0.5 * _GW


@njit(cache=True, nogil=True)
def _safe_step(gap, closing, B):
    """Largest h with gap - closing h - B h^2/2 >= 0 on [0, h] (B >= 0)."""
    if gap < 0.0:
        gap = 0.0
    disc = math.sqrt(closing * closing + 2.0 * B * gap)
    if closing > 0.0:
        return 2.0 * gap / (closing + disc)
    if B > 0.0:
        return (disc - closing) / B
    return math.inf if gap > 0.0 or closing < 0.0 else 0.0


@njit(cache=True, nogil=True)
def _eval_row(R, H, b0, b1, lam, n, om, row, s, order):
    """d^order/ds^order of one row at local time s."""
    acc = 0.0
    for k in range(n):
        lk = lam[k]
        acc += (R[row, k] * lk ** order * np.exp(lk * s)).real
    iw = 1j * om
    acc += (H[row] * iw ** order * np.exp(iw * s)).real
    if order == 0:
        acc += b0[row] + b1[row] * s
    elif order == 1:
        acc += b1[row]
    return acc


@njit(cache=True, nogil=True)
def _eval_all(R, H, b0, b1, lam, n, om, s, nmax, D, ek):
    """D[o, row] = d^o/ds^o of every row at s, o = 0 .. nmax."""
    for k in range(n):
        ek[k] = np.exp(lam[k] * s)
    eiw = np.exp(1j * om * s)
    nr = D.shape[1]
    for row in range(nr):
        for o in range(nmax + 1):
            acc = 0.0
            for k in range(n):
                acc += (R[row, k] * lam[k] ** o * ek[k]).real
            acc += (H[row] * (1j * om) ** o * eiw).real
            if o == 0:
                acc += b0[row] + b1[row] * s
            elif o == 1:
                acc += b1[row]
            D[o, row] = acc


@njit(cache=True, nogil=True)
def _bounds(Rabs, Habs, lam, n, om, s, Bd):
    """Bd[o, row] (o = 0 .. 4): bound of |row^(o)| on [s, inf) from the parts' sizes."""
    nr = Bd.shape[1]
    for o in range(5):
        for row in range(nr):
            Bd[o, row] = Habs[row] * om ** o
    for k in range(n):
        dec = math.exp(min(lam[k].real, 0.0) * s)
        al = abs(lam[k])
        for row in range(nr):
            v = Rabs[row, k] * dec
            for o in range(5):
                Bd[o, row] += v
                v *= al


@njit(cache=True, nogil=True)
def _refine_max(R, H, b0, b1, lam, n, om, row, order, sa, sb, fa, fpa, fb, fpb, B, m, stack):
    """max(m, max |row^(order)| on [sa, sb]) given the values and slopes at the ends and
    |row^(order + 2)| <= B."""
    top = 0
    stack[0, 0], stack[0, 1], stack[0, 2], stack[0, 3], stack[0, 4], stack[0, 5] = \
        sa, sb, fa, fpa, fb, fpb
    top = 1
    while top > 0:
        top -= 1
        a, b, ya, pa, yb, pb = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3], \
            stack[top, 4], stack[top, 5]
        h = b - a
        hi = max(abs(ya), abs(yb))
        if hi > m:
            m = hi
        if hi + B * h * h / 8.0 <= m:
            continue
        if pa * pb < 0.0:                       # the extremum: zero of the slope
            lo, up, plo = a, b, pa
            x = a + h * pa / (pa - pb)
            for _ in range(60):
                px = _eval_row(R, H, b0, b1, lam, n, om, row, x, order + 1)
                if (px < 0.0) == (plo < 0.0):
                    lo, plo = x, px
                else:
                    up = x
                cx = _eval_row(R, H, b0, b1, lam, n, om, row, x, order + 2)
                xn = x - px / cx if cx != 0.0 else 0.5 * (lo + up)
                if not (lo < xn < up):
                    xn = 0.5 * (lo + up)
                if abs(xn - x) <= 1e-15 * (1.0 + abs(x)) or up - lo <= 1e-15 * (1.0 + abs(x)):
                    x = xn
                    break
                x = xn
            v = abs(_eval_row(R, H, b0, b1, lam, n, om, row, x, order))
            if v > m:
                m = v
            continue
        if top + 2 > stack.shape[0] or h <= 1e-13 * (1.0 + abs(a)):
            continue
        c = 0.5 * (a + b)
        yc = _eval_row(R, H, b0, b1, lam, n, om, row, c, order)
        pc = _eval_row(R, H, b0, b1, lam, n, om, row, c, order + 1)
        stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3], stack[top, 4], \
            stack[top, 5] = a, c, ya, pa, yc, pc
        stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2], stack[top + 1, 3], \
            stack[top + 1, 4], stack[top + 1, 5] = c, b, yc, pc, yb, pb
        top += 2
    return m


@njit(cache=True, nogil=True)
def _mask(walls):
    m = 0
    for i in range(walls.size):
        if walls[i] != 0:
            m |= 1 << i
    return m


@njit(cache=True, nogil=True)
def _kinetic(M, ab, V, N):
    e = 0.0
    for a in range(N):
        for b in range(N):
            e += 0.5 * M[a, b] * V[a] * V[b]
    for i in range(ab.shape[0]):
        e += 0.5 * ab[i, 1] * V[N + i] ** 2
    return e


@njit(cache=True, nogil=True)
def _segment(c, lam_all, ns, phi, vinv, zq, hp, qidx, ab, N, P, V, walls, theta0,
             R, H, b0, b1, Rabs, Habs):
    """Fill the rows of the segment starting at state (P, V) with configuration c."""
    n = ns[c]
    nq = n // 2
    nP = P.size
    na = ab.shape[0]
    z = np.empty(n, np.complex128)
    e0 = np.exp(1j * theta0)
    for p in range(nq):
        g = qidx[c, p]
        z[p] = P[g] - (zq[c, p] * e0).real
        z[nq + p] = V[g] - (zq[c, nq + p] * e0).real
    a = np.zeros(n, np.complex128)
    for k in range(n):
        acc = 0j
        for p in range(n):
            acc += vinv[c, k, p] * z[p]
        a[k] = acc
    for row in range(nP):
        for k in range(n):
            R[row, k] = phi[c, row, k] * a[k]
        H[row] = hp[c, row] * e0
        b0[row] = 0.0
        b1[row] = 0.0
    for i in range(na):
        linked = ab[i, 2] > 0.0 or ab[i, 3] > 0.0
        if walls[i] != 0:
            b0[N + i] = -walls[i] * ab[i, 4]
        elif not linked:
            b0[N + i] = P[N + i]
            b1[N + i] = V[N + i]
    for i in range(na):
        j = int(ab[i, 0])
        g = nP + i
        for k in range(n):
            R[g, k] = R[j, k] - R[N + i, k]
        H[g] = H[j] - H[N + i]
        b0[g] = b0[j] - b0[N + i]
        b1[g] = b1[j] - b1[N + i]
    for row in range(R.shape[0]):
        for k in range(n):
            Rabs[row, k] = abs(R[row, k])
        for k in range(n, R.shape[1]):
            Rabs[row, k] = 0.0
        Habs[row] = abs(H[row])


@njit(cache=True, nogil=True)
def _integrate(R, H, b0, b1, lam, n, om, sa, sb, t0, fz, M, C, K, iota, ab, N, in_win,
               acc, D, ek):
    """Add the step [sa, sb]'s kinetic-energy integrals, dissipations and forcing work."""
    h = sb - sa
    if h <= 0.0:
        return
    A, W, ph = fz[1], fz[2], fz[3]
    na = ab.shape[0]
    ex = np.empty(N)
    for q in range(GX.size):
        s = sa + h * GX[q]
        w = h * GW[q]
        _eval_all(R, H, b0, b1, lam, n, om, s, 1, D, ek)
        th = W * (t0 + s) + ph
        ub, ubd = A * math.sin(th), A * W * math.cos(th)
        kh = 0.0
        dh = 0.0
        pw = 0.0
        for a in range(N):
            ex[a] = D[1, a] - iota[a] * ubd
        for a in range(N):
            fa = 0.0
            for b in range(N):
                kh += 0.5 * M[a, b] * D[1, a] * D[1, b]
                dh += C[a, b] * ex[a] * ex[b]
                fa += C[a, b] * ex[b] + K[a, b] * (D[0, b] - iota[b] * ub)
            pw -= ubd * iota[a] * fa
        acc[A_DISS_HOST_ALL, 0] += w * dh
        acc[A_WORK_ALL, 0] += w * pw
        if in_win:
            acc[A_KE_HOST, 0] += w * kh
            acc[A_DISS_HOST, 0] += w * dh
            acc[A_WORK, 0] += w * pw
        for i in range(na):
            dv = D[1, N + na + i]
            da = ab[i, 3] * dv * dv
            acc[A_DISS_ABS_ALL, i] += w * da
            if in_win:
                acc[A_DISS_ABS, i] += w * da
                acc[A_KE_ABS, i] += w * 0.5 * ab[i, 1] * D[1, N + i] ** 2


@njit(cache=True, nogil=True)
def _maxima(R, H, b0, b1, lam, n, om, sa, sb, Da, Db, Bd, ab, N, walls, in_win, acc, stack):
    """Running maxima of |x_j|, |x_j''| (window and whole run) and |w_i| over [sa, sb]."""
    na = ab.shape[0]
    nP = N + na
    for j in range(N):
        m = _refine_max(R, H, b0, b1, lam, n, om, j, 0, sa, sb, Da[0, j], Da[1, j], Db[0, j],
                        Db[1, j], Bd[2, j], acc[A_XMAX_ALL, j], stack)
        acc[A_XMAX_ALL, j] = m
        if in_win:
            acc[A_XMAX, j] = _refine_max(R, H, b0, b1, lam, n, om, j, 0, sa, sb, Da[0, j],
                                         Da[1, j], Db[0, j], Db[1, j], Bd[2, j],
                                         acc[A_XMAX, j], stack)
            acc[A_AMAX, j] = _refine_max(R, H, b0, b1, lam, n, om, j, 2, sa, sb, Da[2, j],
                                         Da[3, j], Db[2, j], Db[3, j], Bd[4, j],
                                         acc[A_AMAX, j], stack)
    for i in range(na):
        g = nP + i
        if walls[i] != 0:
            m = ab[i, 4]
            acc[A_TRAVEL_ALL, i] = max(acc[A_TRAVEL_ALL, i], m)
            if in_win:
                acc[A_TRAVEL, i] = max(acc[A_TRAVEL, i], m)
            continue
        acc[A_TRAVEL_ALL, i] = _refine_max(R, H, b0, b1, lam, n, om, g, 0, sa, sb, Da[0, g],
                                           Da[1, g], Db[0, g], Db[1, g], Bd[2, g],
                                           acc[A_TRAVEL_ALL, i], stack)
        if in_win:
            acc[A_TRAVEL, i] = _refine_max(R, H, b0, b1, lam, n, om, g, 0, sa, sb, Da[0, g],
                                           Da[1, g], Db[0, g], Db[1, g], Bd[2, g],
                                           acc[A_TRAVEL, i], stack)


@njit(cache=True, nogil=True)
def _floor_gap(D, Bd, j, yrow, g, L):
    return ROUNDOFF * (1.0 + abs(D[0, j]) + abs(D[0, yrow]) + Bd[0, g] + L)


@njit(cache=True, nogil=True)
def _contact_force(ab, i, D, j, wall):
    """wall (m x_j'' - k wall L): the stop's push on stuck absorber i (>= 0 while stuck)."""
    return wall * ab[i, 1] * D[2, j] - ab[i, 2] * ab[i, 4]


@njit(cache=True, nogil=True)
def _find_event(D, Bd, ab, N, walls, root_tol):
    """(kind, absorber, wall, ds) of the first event at the current point, kind 0 if none:
    1 impact (contact closing), 2 stick (at a wall, not closing, pressed on it),
    3 release (a stuck absorber's contact force reaches zero)."""
    na = ab.shape[0]
    nP = N + na
    best, bi, bw, bds = 0, -1, 0, math.inf
    for i in range(na):
        L = ab[i, 4]
        j = int(ab[i, 0])
        g = nP + i
        if walls[i] != 0:
            wall = walls[i]
            force = _contact_force(ab, i, D, j, wall)
            dforce = wall * ab[i, 1] * D[3, j]
            scale = ab[i, 1] * (abs(D[2, j]) + Bd[2, j]) + ab[i, 2] * L
            floor = ROUNDOFF * (1.0 + scale)
            B = ab[i, 1] * Bd[4, j]
            if force < -floor:
                ds = 0.0
            elif force <= max(root_tol * scale, floor) and dforce < 0.0 and (
                    dforce * dforce >= 2.0 * B * max(force, 0.0) or force <= floor):
                ds = max(force, 0.0) / -dforce
            else:
                continue
            if ds < bds:
                best, bi, bw, bds = 3, i, wall, ds
            continue
        if math.isinf(L):
            continue
        u, up, upp = D[0, g], D[1, g], D[2, g]
        floor = _floor_gap(D, Bd, j, N + i, g, L)
        vfl = ROUNDOFF * (1.0 + abs(D[1, j]) + abs(D[1, N + i]) + Bd[1, g])
        for wall in (1, -1):
            gap = L - wall * u
            c = wall * up
            if gap > max(root_tol * L, floor):
                continue
            if c > vfl and (c * c >= 2.0 * Bd[2, g] * max(gap, 0.0) or gap <= floor):
                ds = max(gap, 0.0) / c
                if ds < bds:
                    best, bi, bw, bds = 1, i, wall, ds
            elif (gap <= floor and abs(c) <= vfl and bds > 0.0
                  and wall * upp > ROUNDOFF * (1.0 + Bd[2, g])):
                best, bi, bw, bds = 2, i, wall, 0.0
    return best, bi, bw, bds


@njit(cache=True, nogil=True)
def _step(D, Bd, ab, N, walls, h_cap):
    """Longest step from the current point that provably reaches no event."""
    na = ab.shape[0]
    nP = N + na
    h = h_cap
    for i in range(na):
        L = ab[i, 4]
        j = int(ab[i, 0])
        g = nP + i
        if walls[i] != 0:
            wall = walls[i]
            force = max(_contact_force(ab, i, D, j, wall), 0.0)
            dforce = wall * ab[i, 1] * D[3, j]
            B = ab[i, 1] * Bd[4, j]
            hs = _safe_step(force, -dforce, B)
            if hs <= 0.0:               # touching zero with zero slope: the next term
                d2force = wall * ab[i, 1] * D[4, j]
                hs = d2force / (ab[i, 1] * Bd[4, j] + 1e-300) if d2force > 0.0 else 0.0
            h = min(h, hs)
            continue
        if math.isinf(L):
            continue
        u, up, upp = D[0, g], D[1, g], D[2, g]
        floor = _floor_gap(D, Bd, j, N + i, g, L)
        for wall in (1, -1):
            gap = L - wall * u
            c = wall * up
            hs = _safe_step(gap, c, Bd[2, g])
            vfl = ROUNDOFF * (1.0 + abs(D[1, j]) + abs(D[1, N + i]) + Bd[1, g])
            if gap <= floor and c <= vfl:
                # leaving the wall with ~zero speed: the first derivative that moves away
                # and a bound on the next one; at round-off level a step whose overshoot
                # is at most the floor
                a_away = -wall * upp
                j_away = -wall * D[3, g]
                if a_away > ROUNDOFF * (1.0 + Bd[2, g]):
                    hs = max(hs, a_away / (Bd[3, g] + 1e-300))
                elif a_away >= 0.0 and j_away > 0.0:
                    hs = max(hs, j_away / (Bd[4, g] + 1e-300))
                else:
                    hs = max(hs, math.sqrt(2.0 * floor / (Bd[2, g] + 1e-300)))
            h = min(h, hs)
    return h


@njit(cache=True, nogil=True)
def _apply_pair(i, wall, r, ab, N, minv_c, walls, V, target):
    """Impulse on pair i (host dof j, absorber i) that sets w_i' = target if r < 0, else
    -r w_i'; stuck absorbers follow their host dof."""
    j = int(ab[i, 0])
    wd = V[j] - V[N + i]
    new = target if r < 0.0 else -r * wd
    P = (new - wd) / (minv_c[j, j] + 1.0 / ab[i, 1])
    for a in range(N):
        V[a] += minv_c[a, j] * P
    V[N + i] -= P / ab[i, 1]
    for other in range(ab.shape[0]):
        if walls[other] != 0:
            V[N + other] = V[int(ab[other, 0])]


@njit(cache=True, nogil=True)
def _pair_impulse(i, wall, r, ab, N, minv, walls, V, Vtmp, v_stick):
    """The pair impulse, freeing first each stuck absorber that it would pull off its stop
    (its host dof's velocity change pointing away from the stop's push by more than
    v_stick: below, it stays stuck, as a bounce below v_stick would)."""
    for _ in range(ab.shape[0] + 1):
        Vtmp[:] = V
        _apply_pair(i, wall, r, ab, N, minv[_mask(walls)], walls, Vtmp, 0.0)
        freed = False
        for other in range(ab.shape[0]):
            if walls[other] != 0 and other != i:
                jl = int(ab[other, 0])
                if walls[other] * (Vtmp[jl] - V[jl]) < -v_stick:
                    walls[other] = 0
                    freed = True
        if not freed:
            V[:] = Vtmp
            return


@njit(cache=True, nogil=True)
def _resolve(t, P, V, walls, ab, N, M, minv, first, first_wall, v_stick, v_keep, root_tol,
             t_tr, record_from, acc, rec, cnt, Vtmp, D2):
    """Impacts at time t: the pair law for the absorber ``first`` and every pair found in
    contact and closing, until none closes; sticking after impacts slower than v_stick; a
    stuck absorber stays stuck through an impulse that pulls it off by less than v_keep."""
    na = ab.shape[0]
    i, wall = first, first_wall
    in_win = t >= t_tr
    for _ in range(MAX_RESOLVE):
        if i < 0:
            best = 0.0
            for other in range(na):
                L = ab[other, 4]
                if walls[other] != 0 or math.isinf(L):
                    continue
                jl = int(ab[other, 0])
                u = P[jl] - P[N + other]
                floor = ROUNDOFF * (1.0 + abs(P[jl]) + abs(P[N + other]) + L)
                for w in (1, -1):
                    c = w * (V[jl] - V[N + other])
                    vfl = ROUNDOFF * (1.0 + abs(V[jl]) + abs(V[N + other]))
                    if L - w * u <= max(root_tol * L, floor) and c > vfl and c > best:
                        best, i, wall = c, other, w
            if i < 0:
                return
        j = int(ab[i, 0])
        before = V[j] - V[N + i]
        e0 = _kinetic(M, ab, V, N)
        _pair_impulse(i, wall, ab[i, 5], ab, N, minv, walls, V, Vtmp, v_keep)
        after = V[j] - V[N + i]
        # sticking: slow rebound (at or below the round-off floor of a bounce) -> plastic
        apex = 16.0 * ROUNDOFF * (1.0 + abs(P[j]) + abs(P[N + i]))
        acc_rel = abs(D2[j] - D2[N + i])
        v_floor = math.sqrt(2.0 * acc_rel * apex)
        stuck = 0
        if abs(after) <= max(v_stick, v_floor):
            _pair_impulse(i, wall, -1.0, ab, N, minv, walls, V, Vtmp, v_keep)
            walls[i] = wall
            V[N + i] = V[j]
            P[N + i] = P[j] - wall * ab[i, 4]
            stuck = 1
        loss = e0 - _kinetic(M, ab, V, N)
        acc[A_IMP_LOSS_ALL, i] += loss
        acc[A_NIMP_ALL, i] += 1.0
        cnt[C_NIMP] += 1
        if in_win:
            acc[A_IMP_LOSS, i] += loss
            acc[A_NIMP, i] += 1.0
            if wall == 1:
                acc[A_NIMP_L, i] += 1.0
        if t >= record_from and rec.shape[0] > 0:
            k = cnt[C_NREC] % rec.shape[0]
            rec[k, 0], rec[k, 1], rec[k, 2] = t, i, wall
            rec[k, 3], rec[k, 4], rec[k, 5] = before, after, stuck
            cnt[C_NREC] += 1
        i = -1


@njit(cache=True, nogil=True)
def run_model(lam_all, ns, phi, vinv, zq, hp, qidx, minv, M, C, K, iota, ab, fz, omega_max,
              t_start, P0, V0, walls0, t_end, t_tr, v_stick, root_tol, max_impacts,
              record_from, acc, rec, cnt, state):
    """Simulate from (t_start, P0, V0, walls0) to t_end; measures into acc (window
    [t_tr, t_end] and whole run), impacts into rec (the first rec.shape[0]), counters and
    status into cnt, the final (t, P, V, walls) into state. rec is a ring buffer: it keeps the
last rec.shape[0] impacts at t >= record_from (cnt[C_NREC] counts them all)."""
    N = M.shape[0]
    na = ab.shape[0]
    nP = N + na
    nr = nP + na
    nsm = lam_all.shape[1]
    W, ph = fz[2], fz[3]
    h_cap = 1.0 / omega_max
    R = np.zeros((nr, nsm), np.complex128)
    H = np.zeros(nr, np.complex128)
    b0 = np.zeros(nr)
    b1 = np.zeros(nr)
    Rabs = np.zeros((nr, nsm))
    Habs = np.zeros(nr)
    Da = np.zeros((5, nr))
    Db = np.zeros((5, nr))
    Dq = np.zeros((2, nr))
    Bd = np.zeros((5, nr))
    ek = np.zeros(nsm, np.complex128)
    stack = np.zeros((2 * MAX_BISECT + 2, 6))
    Vtmp = np.zeros(nP)
    P = P0.copy()
    V = V0.copy()
    walls = walls0.copy()
    t = t_start
    n_zero = 0
    cnt[C_STATUS] = RC_DONE
    while True:
        c = _mask(walls)
        n = ns[c]
        lam = lam_all[c]
        theta0 = W * t + ph
        _segment(c, lam_all, ns, phi, vinv, zq, hp, qidx, ab, N, P, V, walls, theta0,
                 R, H, b0, b1, Rabs, Habs)
        in_win = t >= t_tr
        s_stop = (t_tr - t) if t < t_tr else (t_end - t)
        cnt[C_NSEG] += 1
        s = 0.0
        _eval_all(R, H, b0, b1, lam, n, W, s, 4, Da, ek)
        kind, ev_i, ev_w = 0, -1, 0
        steps = 0
        while True:
            _bounds(Rabs, Habs, lam, n, W, s, Bd)
            kind, ev_i, ev_w, ds = _find_event(Da, Bd, ab, N, walls, root_tol)
            if kind != 0 and s + ds > s_stop:
                kind = 0
            if kind != 0:
                sb = s + ds
                if sb > s:
                    _eval_all(R, H, b0, b1, lam, n, W, sb, 4, Db, ek)
                    _integrate(R, H, b0, b1, lam, n, W, s, sb, t, fz, M, C, K, iota, ab, N,
                               in_win, acc, Dq, ek)
                    _maxima(R, H, b0, b1, lam, n, W, s, sb, Da, Db, Bd, ab, N, walls, in_win,
                            acc, stack)
                    Da[:, :] = Db
                    s = sb
                break
            if s >= s_stop:
                break
            h = _step(Da, Bd, ab, N, walls, h_cap)
            sb = s + h
            if sb >= s_stop:
                sb = s_stop
            if not sb > s:
                cnt[C_STATUS] = RC_STALLED
                break
            _eval_all(R, H, b0, b1, lam, n, W, sb, 4, Db, ek)
            _integrate(R, H, b0, b1, lam, n, W, s, sb, t, fz, M, C, K, iota, ab, N, in_win,
                       acc, Dq, ek)
            _maxima(R, H, b0, b1, lam, n, W, s, sb, Da, Db, Bd, ab, N, walls, in_win, acc,
                    stack)
            Da[:, :] = Db
            s = sb
            steps += 1
            cnt[C_NSTEPS] += 1
            if steps > MAX_STEPS_PER_SEGMENT:
                cnt[C_STATUS] = RC_STALLED
                break
        for i in range(na):
            if walls[i] != 0:
                acc[A_TSTUCK_ALL, i] += s
                if in_win:
                    acc[A_TSTUCK, i] += s
        t = t + s if s < s_stop else (t_tr if t < t_tr else t_end)
        for p in range(nP):
            P[p] = Da[0, p]
            V[p] = Da[1, p]
        if cnt[C_STATUS] != RC_DONE:
            break
        if s == 0.0 and kind != 0:
            n_zero += 1
            if n_zero > MAX_ZERO_SEGMENTS:     # events without motion: cannot resolve
                cnt[C_STATUS] = RC_STALLED
                break
        else:
            n_zero = 0
        if kind == 1 or kind == 2:
            if kind == 2:       # pressed on the wall at zero speed: sticks (plastic)
                _resolve(t, P, V, walls, ab, N, M, minv, ev_i, ev_w, math.inf, v_stick, root_tol,
                         t_tr, record_from, acc, rec, cnt, Vtmp, Da[2])
            else:
                _resolve(t, P, V, walls, ab, N, M, minv, ev_i, ev_w, v_stick, v_stick, root_tol,
                         t_tr, record_from, acc, rec, cnt, Vtmp, Da[2])
            if cnt[C_NIMP] >= max_impacts:
                cnt[C_STATUS] = RC_MAX_IMPACTS
                break
        elif kind == 3:
            walls[ev_i] = 0
        elif t >= t_end:
            break
    state[0] = t
    state[1:1 + nP] = P
    state[1 + nP:1 + 2 * nP] = V
    for i in range(na):
        state[1 + 2 * nP + i] = walls[i]
