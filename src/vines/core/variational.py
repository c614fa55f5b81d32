"""Variational flow along an exact trajectory: state-transition and saltation matrices.

Tangent vectors dx = (dz_m, dz_m', dz_b, dz_b') follow the linearised motion of the
recorded trajectory (``kernel.run_kernel``: segments of free flight or sticking, separated
by events):

* Between events the motion is linear and its homogeneous part does not depend on the
  forcing, so the state-transition matrix over a local time h is exact and closed-form:
  free flight  [[C, S], [C', S']] (fundamentals of z'' + d z' + z = 0, ``flow.fundamentals``)
               on (dz_m, dz_m'), and [[1, h], [0, 1]] on (dz_b, dz_b');
  stuck        the fundamentals of the stuck body (mass 1 + eta) on (dz_m, dz_m'), and
               dz_b = dz_m, dz_b' = dz_m' (the tangent space of the stuck manifold).
* At an impact (event surface h(x) = w - wall = 0, normal n = (1, 0, -1, 0)) the saltation
  matrix  S = D R + (f+ - D R f-) n^T / (n . f-)  (impact law R with Jacobian D R, vector
  fields f- before and f+ after the impact; n . f- = w'- is the closing speed). Its
  determinant is r^2 whatever the state (det D R = -r, n . f+ = -r n . f-).
* An impact after which the ball sticks: the same formula with R replaced by the sticking
  map (z_m, v_c, z_m - wall, v_c), v_c the common velocity, and f+ the stuck body's field.
  Its rank is 2: every perturbation across the stuck manifold {w = wall, w' = 0} is removed
  in finite time. A stick that starts without an impact (the ball found pressed on the wall
  with zero relative velocity) is the projection onto that manifold.
* A release needs no matrix: the contact force is zero there, so the stuck and free vector
  fields agree (both accelerations vanish) and the saltation matrix is the identity.

Sticking removes two dimensions: after a stick only two tangent directions survive, so
the Benettin frame keeps two vectors (``tangent_pass``: the two others count log 0 =
-inf) until the release, where the frame is completed again by two vectors orthogonal to
the surviving ones. A window that contains a stick has lambda_3 = lambda_4 = -inf.
"""
from __future__ import annotations

import math

import numpy as np

from .. import progress
from .._jit import njit
from .flow import I_D, I_F, I_W, fundamentals

#: slots of the tangent pass's state ``tp``: active frame columns (4, or 2 while stuck),
#: index of the next impact record, stick starts and impacts inside the accumulation span
#: and TP_PLAIN = 1 for the plain product of the matrices (no re-orthonormalisation)
TP_K, TP_IMP, TP_NSTICK, TP_NIMP, TP_PLAIN = range(5)
N_TP = 5


@njit(cache=True, nogil=True)
def stm_free(osc_f, h, M):
    """Fill M (4x4) with the state-transition matrix of free flight over local time h."""
    C, dC, S, dS = fundamentals(osc_f, h)
    M[:, :] = 0.0
    M[0, 0], M[0, 1], M[1, 0], M[1, 1] = C, S, dC, dS
    M[2, 2], M[2, 3], M[3, 3] = 1.0, h, 1.0


@njit(cache=True, nogil=True)
def stm_stuck(osc_s, h, M):
    """Fill M with the state-transition matrix of the stuck body over h (rank 2: it maps
    every vector into the tangent space of the stuck manifold, dz_b = dz_m, dz_b' = dz_m')."""
    C, dC, S, dS = fundamentals(osc_s, h)
    M[:, :] = 0.0
    for row in (0, 2):
        M[row, 0], M[row, 1] = C, S
        M[row + 1, 0], M[row + 1, 1] = dC, dS


@njit(cache=True, nogil=True)
def _forcing_at(osc_f, t, phi):
    """F sin(theta) + d omega F cos(theta), theta = omega t + phi."""
    omega = osc_f[I_W]
    th = omega * t + phi
    F = osc_f[I_F]
    return F * math.sin(th) + osc_f[I_D] * omega * F * math.cos(th)


@njit(cache=True, nogil=True)
def saltation_impact(kp, t, zm, vm, vb, S):
    """Fill S with the saltation matrix of an impact at time t from the pre-impact state
    (z_m, v_m, ., v_b) (free flight on both sides, module docstring); kp: the run's
    ``kernel.KernelParams`` (its free oscillator, eta, r and phi are used)."""
    osc_f, eta, r, phi = kp.osc_f, kp.eta, kp.r, kp.phi
    one = 1.0 + eta
    a11, a12 = (1.0 - r * eta) / one, eta * (1.0 + r) / one
    a21, a22 = (1.0 + r) / one, (eta - r) / one
    vm_p = a11 * vm + a12 * vb
    vb_p = a21 * vm + a22 * vb
    g = _forcing_at(osc_f, t, phi)
    d = osc_f[I_D]
    acc_m = g - d * vm - zm                  # LO acceleration before ...
    acc_p = g - d * vm_p - zm                # ... and after the impact
    S[:, :] = 0.0
    S[0, 0], S[2, 2] = 1.0, 1.0
    S[1, 1], S[1, 3], S[3, 1], S[3, 3] = a11, a12, a21, a22
    # u = f+ - DR f-, added as u n^T / (n . f-), n = (1, 0, -1, 0)
    u0 = vm_p - vm
    u1 = acc_p - a11 * acc_m
    u2 = vb_p - vb
    u3 = -a21 * acc_m
    _add_rank_one(S, u0, u1, u2, u3, vm - vb)


@njit(cache=True, nogil=True)
def saltation_impact_stick(kp, t, zm, vm, vb, S):
    """Fill S with the saltation matrix of an impact after which the ball sticks (rank 2;
    kp as in ``saltation_impact``)."""
    osc_f, eta, phi = kp.osc_f, kp.eta, kp.phi
    one = 1.0 + eta
    c1, c2 = 1.0 / one, eta / one
    vc = c1 * vm + c2 * vb
    g = _forcing_at(osc_f, t, phi)
    d = osc_f[I_D]
    acc_m = g - d * vm - zm                  # free LO before the impact
    acc_s = (g - d * vc - zm) / one          # stuck body after it
    stick_projection(eta, S)
    u0 = vc - vm
    u1 = acc_s - c1 * acc_m
    _add_rank_one(S, u0, u1, u0, u1, vm - vb)


@njit(cache=True, nogil=True)
def stick_projection(eta, S):
    """Fill S with the Jacobian of the sticking map (z_m, v_m, z_b, v_b) ->
    (z_m, v_c, z_m - wall, v_c), v_c = (v_m + eta v_b) / (1 + eta)."""
    one = 1.0 + eta
    S[:, :] = 0.0
    for row in (0, 2):
        S[row, 0] = 1.0
        S[row + 1, 1], S[row + 1, 3] = 1.0 / one, eta / one


@njit(cache=True, nogil=True, inline="always")
def _add_rank_one(S, u0, u1, u2, u3, closing):
    """S += u n^T / closing with n = (1, 0, -1, 0) (gradient of w - wall)."""
    u = (u0, u1, u2, u3)
    for i in range(4):
        S[i, 0] += u[i] / closing
        S[i, 2] -= u[i] / closing


@njit(cache=True, nogil=True)
def qr_columns(Y, k, Q, rdiag):
    """Orthonormalise the first k columns of Y into Q (Gram-Schmidt applied twice, which
    keeps them orthogonal to round-off); rdiag[i] = |R_ii| (0 for a dependent column, whose
    Q column is then 0)."""
    for j in range(k):
        for i in range(4):
            Q[i, j] = Y[i, j]
        for _ in range(2):
            for m in range(j):
                dot = 0.0
                for i in range(4):
                    dot += Q[i, m] * Q[i, j]
                for i in range(4):
                    Q[i, j] -= dot * Q[i, m]
        nrm = math.sqrt(Q[0, j] ** 2 + Q[1, j] ** 2 + Q[2, j] ** 2 + Q[3, j] ** 2)
        rdiag[j] = nrm
        for i in range(4):
            Q[i, j] = Q[i, j] / nrm if nrm > 0.0 else 0.0


@njit(cache=True, nogil=True)
def complete_frame(Q, k):
    """Columns k..3 of Q: orthonormal vectors orthogonal to the first k (from the unit
    vectors, largest remainder first; deterministic)."""
    tmp = np.empty(4)
    for j in range(k, 4):
        best = -1.0
        for e in range(4):
            for i in range(4):
                tmp[i] = 1.0 if i == e else 0.0
            for _ in range(2):
                for m in range(j):
                    dot = tmp[0] * Q[0, m] + tmp[1] * Q[1, m] + tmp[2] * Q[2, m] \
                        + tmp[3] * Q[3, m]
                    for i in range(4):
                        tmp[i] -= dot * Q[i, m]
            nrm = math.sqrt(tmp[0] ** 2 + tmp[1] ** 2 + tmp[2] ** 2 + tmp[3] ** 2)
            if nrm > best + 1e-12:
                best = nrm
                for i in range(4):
                    Q[i, j] = tmp[i] / nrm


@njit(cache=True, nogil=True)
def _matmul_cols(A, B, k, out):
    """out[:, :k] = A @ B[:, :k] (4x4 matrices)."""
    for j in range(k):
        for i in range(4):
            acc = 0.0
            for m in range(4):
                acc += A[i, m] * B[m, j]
            out[i, j] = acc


@njit(cache=True, nogil=True)
def _event_matrix(kp, seg, k, imp, n_imp, tp, t_acc, S):
    """Saltation matrix at the end of segment k (start of segment k + 1) into S; returns
    the kind: 0 none (identity), 1 impact, 2 stick (rank 2), 3 release. Impacts from
    t_acc on are counted in tp[TP_NIMP]."""
    t1 = seg[k + 1, 0]
    m0 = int(seg[k, 5])
    m1 = int(seg[k + 1, 5])
    ip = int(tp[TP_IMP])
    while ip < n_imp and imp[ip, 0] < t1:  # never expected: every impact ends a segment
        ip += 1
    tp[TP_IMP] = ip
    hit = ip < n_imp and imp[ip, 0] == t1
    if hit:
        tp[TP_IMP] = ip + 1
        if t1 >= t_acc:
            tp[TP_NIMP] += 1
    if m0 == 0 and hit:
        zm, vm, vb = imp[ip, 1], imp[ip, 2], imp[ip, 4]
        if m1 == 0:
            saltation_impact(kp, t1, zm, vm, vb, S)
            return 1
        saltation_impact_stick(kp, t1, zm, vm, vb, S)
        return 2
    if m0 == 0 and m1 != 0:
        stick_projection(kp.eta, S)
        return 2
    if m0 != 0 and m1 == 0:
        return 3
    return 0


@njit(cache=True, nogil=True)
def _piece(osc_f, osc_s, mode, h, Q, tp, Y, M):
    """Y[:, :k] = STM(h) Q[:, :k] for the segment's mode."""
    if mode == 0:
        stm_free(osc_f, h, M)
    else:
        stm_stuck(osc_s, h, M)
    _matmul_cols(M, Q, int(tp[TP_K]), Y)


@njit(cache=True, nogil=True)
def _accumulate(Y, Q, tp, rdiag, sums, b, collapse):
    """QR of the active columns of Y into Q and log |R_ii| into sums[b] (b < 0: not
    accumulated); collapse: the frame drops to two columns (a stick). Plain products
    (tp[TP_PLAIN]): Q = Y, all four columns, nothing summed."""
    if tp[TP_PLAIN] > 0.0:
        for j in range(4):
            for i in range(4):
                Q[i, j] = Y[i, j]
        return
    if collapse:
        tp[TP_K] = 2
    k = int(tp[TP_K])
    qr_columns(Y, k, Q, rdiag)
    if b >= 0:
        for j in range(k):
            sums[b, j] += math.log(rdiag[j])
        if collapse:
            sums[b, 2] = -math.inf
            sums[b, 3] = -math.inf
    for j in range(k):
        if rdiag[j] == 0.0:                 # a (non-generic) lost direction: start anew
            complete_frame(Q, j)
            break


@njit(cache=True, nogil=True)
def tangent_pass(kp, seg, n_seg, t_last, imp, n_imp, edges, ts):
    """Carry the orthonormal frame Q (4x4, first tp[TP_K] columns active) along the
    recorded segments seg[:n_seg] (rows t0, z_m, z_m', z_b, z_b', mode as recorded by
    ``kernel.run_kernel``) and the impacts imp[:n_imp] (from index tp[TP_IMP] on) of the run
    with ``kernel.KernelParams`` kp. ts = (Q, tp, sums): the tangent state, updated in place
    (frame, slots TP_*, sums of log |R_ii| per batch).

    Segment i < n_seg - 1 ends where segment i + 1 starts, with the event found from the
    modes and the impact records (``_event_matrix``); the last one ends at t_last (no event;
    NaN: it is not complete and is left for the next call). Benettin: after every piece of
    flow (plus event) the active columns are re-orthonormalised and log |R_ii| is added to
    sums[b] for the batch b of ``edges`` (ascending times) that holds the piece; nothing is
    added before edges[0]. Pieces end at every batch edge. Returns how many segments were
    completed.
    """
    Q, tp, sums = ts
    osc_f, osc_s = kp.osc_f, kp.osc_s
    Y = np.empty((4, 4))
    M = np.empty((4, 4))
    S = np.empty((4, 4))
    rdiag = np.zeros(4)
    nb = edges.shape[0] - 1
    t_acc = edges[0]
    n_done = n_seg - 1
    if not math.isnan(t_last):
        n_done = n_seg
    for k in range(n_done):
        t0 = seg[k, 0]
        t1 = seg[k + 1, 0] if k + 1 < n_seg else t_last
        mode = int(seg[k, 5])
        ta = t0
        while True:
            # next batch edge inside (ta, t1)
            b = -1
            tb = t1
            for j in range(nb + 1):
                if edges[j] > ta:
                    if edges[j] < t1:
                        tb = edges[j]
                    b = j - 1
                    break
            _piece(osc_f, osc_s, mode, tb - ta, Q, tp, Y, M)
            if tb < t1:
                _accumulate(Y, Q, tp, rdiag, sums, b, False)
                ta = tb
                continue
            kind = 0
            if k + 1 < n_seg:
                kind = _event_matrix(kp, seg, k, imp, n_imp, tp, t_acc, S)
            if kind == 1 or kind == 2:
                for j in range(int(tp[TP_K])):
                    for i in range(4):
                        M[i, j] = Y[i, j]
                _matmul_cols(S, M, int(tp[TP_K]), Y)
            if kind == 2 and t1 >= t_acc:
                tp[TP_NSTICK] += 1
            _accumulate(Y, Q, tp, rdiag, sums, b, kind == 2)
            if kind == 3 and int(tp[TP_K]) < 4:
                complete_frame(Q, int(tp[TP_K]))
                tp[TP_K] = 4
            break
    return n_done


# ------------------------------------------------------------------ driver

#: the kernel pauses every CHUNK_PERIODS forcing periods so that its records are consumed
#: (and their buffers reused); pausing never changes the trajectory
CHUNK_PERIODS = 256


def initial_frame() -> np.ndarray:
    """A fixed generic orthonormal 4x4 frame (no column in an invariant subspace, so that
    Benettin's columns order themselves by growth rate)."""
    a = np.random.default_rng(20240531).standard_normal((4, 4))
    return np.linalg.qr(a)[0]


class TangentRun:
    """The trajectory of ``exact.run_exact(params, settings, state0=..., t0=...)`` (the same
    segments, bit for bit: pauses never change it) with the Benettin frame carried along.

    ``edges``: ascending batch edges; log |R_ii| is summed per batch (``sums``, shape
    (len(edges) - 1, 4)). ``on_chunk(seg, n_done, t_done)`` (optional) sees every chunk of
    completed segments, valid up to time t_done. After ``run()``: ``sums``, ``n_impacts``
    and ``n_sticks`` inside [edges[0], edges[-1]], ``status`` and the KernelRun ``run``.
    """

    def __init__(self, params, settings, oscs, state0, t0: float, edges, mode: int = 0,
                 frame=None):
        from .exact import KernelRun, Span
        self.p, self.oscs = params, oscs
        self.edges = np.ascontiguousarray(edges, dtype=float)
        self.run_ = KernelRun(params, settings, oscs, np.asarray(state0, float), t0,
                              Span(settings.t_end, settings.t_transient, t0), mode)
        self.Q = initial_frame() if frame is None else np.array(frame, float)
        self.tp = np.zeros(N_TP)
        self.tp[TP_K] = 4
        self.sums = np.zeros((self.edges.size - 1, 4))
        self.status = None

    def run(self, on_chunk=None) -> TangentRun:
        from . import kernel as eng
        run, p = self.run_, self.p
        sec = np.full(eng.N_SEC, math.nan)
        chunk = CHUNK_PERIODS * p.period
        t_pause = float(run.cur[eng.CUR_T]) + chunk
        while True:
            rc = run.run(eng.run_kernel_until, t_pause, sec)
            done = rc != eng.RC_PAUSED
            n_seg, n_imp = int(run.cnt[eng.C_NSEG_REC]), int(run.cnt[eng.C_NIMP_REC])
            t_last = float(run.cur[eng.CUR_T]) if done else math.nan
            n_done = tangent_pass(run.kp, run.seg, n_seg, t_last, run.imp, n_imp, self.edges,
                                  (self.Q, self.tp, self.sums))
            if on_chunk is not None and n_done > 0:
                on_chunk(run.seg, n_done, t_last if done else float(run.seg[n_done, 0]))
            self._compact(n_seg, n_done, n_imp)
            if done:
                self.status = eng.STATUS_TEXT.get(rc, str(rc))
                return self
            progress.advance(chunk)
            t_pause += chunk

    def _compact(self, n_seg: int, n_done: int, n_imp: int) -> None:
        """Move the unprocessed records (the open segment, impacts not yet matched) to the
        front of the kernel's buffers."""
        from . import kernel as eng
        run = self.run_
        keep = n_seg - n_done
        run.seg[:keep] = run.seg[n_done:n_seg]
        ip = int(self.tp[TP_IMP])
        run.imp[:n_imp - ip] = run.imp[ip:n_imp]
        run.cnt[eng.C_NSEG_REC] = keep
        run.cnt[eng.C_NIMP_REC] = n_imp - ip
        self.tp[TP_IMP] = 0

    @property
    def n_impacts(self) -> int:
        return int(self.tp[TP_NIMP])

    @property
    def n_sticks(self) -> int:
        return int(self.tp[TP_NSTICK])


def monodromy(params, settings, oscs, state0, t0: float, P: float, mode: int = 0):
    """Product of the state-transition and saltation matrices over [t0, t0 + P] along the
    trajectory from ``state0`` (segment ``mode``; ``settings`` gives v_stick, max_impacts,
    root_tol): for a periodic orbit of period P its monodromy matrix, whose eigenvalues are
    the Floquet multipliers (two of them 0 when the orbit sticks)."""
    from .params import SolverSettings
    st = SolverSettings(t_end=t0 + P, t_transient=t0, v_stick=settings.v_stick,
                        max_impacts=settings.max_impacts, root_tol=settings.root_tol)
    tr = TangentRun(params, st, oscs, state0, t0, [t0, t0 + P], mode, frame=np.eye(4))
    tr.tp[TP_PLAIN] = 1.0
    tr.run()
    return tr.Q.copy(), tr
