"""The linear systems between events, in the arrays the compiled engine reads.

A *configuration* is the set of absorbers stuck at a wall (a bit mask; 2^n of them). In
configuration c the coupled coordinates q are the host's N degrees of freedom and the
absorbers with a link (k > 0 or c > 0) that are not stuck; a stuck absorber moves with its
host degree of freedom (its mass lumped there; its link then carries a constant internal
force that cancels in the lumped body), an absorber without link that is not stuck flies
freely (y'' = 0: kept out of the eigenproblem, whose Jordan block it would be).

    M_q q'' + C_q q' + K_q q = Re(f_hat e^{i theta}),  theta = omega t + phi,
    f_hat = A (omega C iota - i K iota) on the host rows.

The first-order system z' = A_c z (z = (q, q')) is diagonalised once, A_c = V diag(lam) V^-1
(complex modes: exact for non-proportional damping), and the harmonic particular solution is
q_p = Re(Z e^{i theta}), Z = (K_q - omega^2 M_q + i omega C_q)^-1 f_hat. For any start
state z0 at local time 0: z(s) = V diag(e^{lam s}) V^-1 (z0 - z_p(0)) + z_p(s).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..core.params import ParameterError
from .model import HostModel

#: largest condition number of a configuration's eigenvector matrix: beyond, the system is
#: (nearly) defective (a critically damped mode) and its diagonal form loses accuracy
MAX_MODE_COND = 1e8
#: largest condition number of K - omega^2 M + i omega C (a resonance without damping)
MAX_GAIN = 1e6


class Packed(NamedTuple):
    """The arrays of ``kernel.run_model`` (c: configuration, P: full positions x then y)."""

    lam: np.ndarray      # (nc, ns) complex eigenvalues (padded with 0)
    ns: np.ndarray       # (nc,) 2 n_q
    phi: np.ndarray      # (nc, nP, ns) complex: position of each full coordinate per mode
    vinv: np.ndarray     # (nc, ns, ns) complex V^-1
    zq: np.ndarray       # (nc, ns) complex harmonic particular of z = (q, q')
    hp: np.ndarray       # (nc, nP) complex harmonic particular of the full positions
    qidx: np.ndarray     # (nc, nq) int: full index of each coupled coordinate
    minv: np.ndarray     # (nc, N, N) inverse of the lumped host mass matrix
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    iota: np.ndarray
    ab: np.ndarray       # (na, 6): dof, m, k, c, L, r
    forcing: np.ndarray  # (kind 0 = harmonic, A, omega, phi)
    omega_max: float     # the fastest rate of the flow (|lam| and omega)


def _linked(model: HostModel) -> np.ndarray:
    return np.array([a.stiffness > 0.0 or a.damping > 0.0 for a in model.absorbers], dtype=bool)


def _config(model: HostModel, mask: int):
    """(qidx, M_q, C_q, K_q, lumped host mass) of configuration ``mask``."""
    h, N = model.host, model.n_dof
    linked = _linked(model)
    stuck = [(mask >> i) & 1 == 1 for i in range(model.n_absorbers)]
    qidx = list(range(N)) + [N + i for i in range(model.n_absorbers) if linked[i] and not stuck[i]]
    nq = len(qidx)
    Mq, Cq, Kq = np.zeros((nq, nq)), np.zeros((nq, nq)), np.zeros((nq, nq))
    Mq[:N, :N], Cq[:N, :N], Kq[:N, :N] = h.mass, h.damping, h.stiffness
    Ml = h.mass.copy()
    for i, a in enumerate(model.absorbers):
        j = a.dof
        if stuck[i]:
            Mq[j, j] += a.mass
            Ml[j, j] += a.mass
        elif linked[i]:
            p = qidx.index(N + i)
            Mq[p, p] = a.mass
            for A, v in ((Cq, a.damping), (Kq, a.stiffness)):
                A[j, j] += v
                A[p, p] += v
                A[j, p] -= v
                A[p, j] -= v
    return qidx, Mq, Cq, Kq, Ml


def _modes(name: str, Mq, Cq, Kq):
    nq = Mq.shape[0]
    Mi = np.linalg.inv(Mq)
    A = np.zeros((2 * nq, 2 * nq))
    A[:nq, nq:] = np.eye(nq)
    A[nq:, :nq] = -Mi @ Kq
    A[nq:, nq:] = -Mi @ Cq
    lam, V = np.linalg.eig(A)
    cond = np.linalg.cond(V)
    if not np.isfinite(cond) or cond > MAX_MODE_COND:
        raise ParameterError(name, f"condition number {cond:.3g}",
                             "the linear system is (nearly) defective: a critically damped "
                             "mode; change a damping by a fraction of a percent")
    return lam, V, np.linalg.inv(V)


def pack(model: HostModel) -> Packed:
    """The arrays of every configuration (raises ParameterError where the closed form is
    ill-conditioned: a critically damped mode, forcing at an undamped resonance)."""
    N, na = model.n_dof, model.n_absorbers
    nP, nc = N + na, 1 << na
    nq_max = N + int(_linked(model).sum())
    f = model.forcing
    A_, W = f.amplitude, f.frequency
    fhat = A_ * (W * model.host.damping @ model.host.influence
                 - 1j * model.host.stiffness @ model.host.influence)
    lam_a = np.zeros((nc, 2 * nq_max), complex)
    ns = np.zeros(nc, np.int64)
    phi = np.zeros((nc, nP, 2 * nq_max), complex)
    vinv = np.zeros((nc, 2 * nq_max, 2 * nq_max), complex)
    zq = np.zeros((nc, 2 * nq_max), complex)
    hp = np.zeros((nc, nP), complex)
    qidx_a = np.full((nc, nq_max), -1, np.int64)
    minv = np.zeros((nc, N, N))
    omega_max = W
    for c in range(nc):
        qidx, Mq, Cq, Kq, Ml = _config(model, c)
        nq = len(qidx)
        lam, V, Vi = _modes("model", Mq, Cq, Kq)
        D = Kq - W * W * Mq + 1j * W * Cq
        F = np.zeros(nq, complex)
        F[:N] = fhat
        gain = np.linalg.cond(D)
        if not np.isfinite(gain) or gain > MAX_GAIN:
            raise ParameterError("forcing.frequency", W, "is at (or within a part in 1e6 of) an "
                                 "undamped resonance of the model: detune it or add damping")
        Z = np.linalg.solve(D, F)
        ns[c] = 2 * nq
        lam_a[c, :2 * nq] = lam
        vinv[c, :2 * nq, :2 * nq] = Vi
        zq[c, :nq], zq[c, nq:2 * nq] = Z, 1j * W * Z
        qidx_a[c, :nq] = qidx
        minv[c] = np.linalg.inv(Ml)
        rows = np.zeros((nP, nq), complex)   # full positions from q
        for p, g in enumerate(qidx):
            rows[g, p] = 1.0
        for i, a in enumerate(model.absorbers):
            if (c >> i) & 1:
                rows[N + i, a.dof] = 1.0
        phi[c, :, :2 * nq] = rows @ V[:nq, :]
        hp[c] = rows @ Z
        omega_max = max(omega_max, float(np.abs(lam).max()))
    ab = np.array([[a.dof, a.mass, a.stiffness, a.damping, a.gap, a.restitution]
                   for a in model.absorbers], dtype=float).reshape(na, 6)
    h = model.host
    return Packed(lam_a, ns, phi, vinv, zq, hp, qidx_a, minv, h.mass.copy(), h.damping.copy(),
                  h.stiffness.copy(), h.influence.copy(), ab,
                  np.array([0.0, A_, W, f.phase]), omega_max)


def check_system(model: HostModel) -> None:
    """Raise ParameterError where the engine's closed form would be ill-conditioned."""
    pack(model)
