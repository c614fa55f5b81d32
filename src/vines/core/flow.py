"""Closed-form flow of the forced, damped linear oscillator in *local* time.

One oscillator covers both phases of the VINES motion:

    m z'' + d z' + z = F sin(theta) + d omega F cos(theta),   theta = theta0 + omega s,

with m = 1 for the LO in free flight and m = 1 + eta for the stuck body (paper Eq. 28).
``s`` is the local time since the start of the segment (s = t - t0) and theta0 = omega t0 + phi
the forcing phase at that start: nothing grows like exp(d t / 2), unlike the paper's Eq. 12.

The solution is z(s) = z_p(s) + x_h C(s) + v_h S(s) with the fundamental solutions C, S of
the homogeneous equation (C(0)=1, C'(0)=0, S(0)=0, S'(0)=1) and x_h, v_h the initial
homogeneous parts. Every damping regime is covered by one expression (kappa = 1/m - sigma^2,
sigma = d/(2m)): underdamped (kappa > 0), critically damped (kappa = 0) and overdamped
(kappa < 0), and the undamped resonance d = 0, m omega^2 = 1 (to within RESONANCE_SNAP) with its
secular particular solution z_p = A s cos(theta), A = -F/(2 m omega).

Bounds used by the event search: the homogeneous energy E_h = (z_h'^2 + z_h^2/m)/2 never
increases (d >= 0), so for every later time |z_h'| <= b1 = sqrt(2 E_h), |z_h| <= b1/omega and
|z_h^(n)| <= b_n with b_n = 2 sigma b_(n-1) + omega^2 b_(n-2); the particular part adds
P omega^n (P its amplitude), or the secular growth in the resonant case.

Undamped and near resonance (d = 0, 1 < |1 - m omega^2|/RESONANCE_SNAP, gain 1/|1 - m omega^2| >
NRES_GAIN) z_p and z_h are both ~F/|1 - m omega^2| and cancel: there the flow is written instead
as z = x0 C + v0 S + R(s) with the zero-initial-condition response
    R(s) = K [2 sin(th0) sin(Sg s/2) Q(s) + cos(th0) (sin(om s)/om - 2 cos(Sg s/2) Q(s))],
K = F/(m Sg), Sg = om + omega, Dl = om - omega, Q(s) = sin(Dl s/2)/Dl (-> s/2 as Dl -> 0), which has
no cancellation (it tends to the secular solution); the bounds then use the energy of the
whole state and |R^(n)| <= bounds growing like K Sg s (see ``deriv_bound``).

The oscillator constants are packed in a float64 array (``make_osc``) so that numba kernels
can take them as plain arguments.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit
from .params import RESONANCE_SNAP

# Indices into the packed oscillator array.
I_SIGMA, I_OM2, I_OM, I_KAPPA, I_SQ, I_KIND, I_W, I_PS, I_PC, I_RES, I_ARES, I_PAMP, I_M, \
    I_RATE, I_D, I_F, I_NRES, I_SUM, I_DIFF, I_K, I_FAMP = range(21)
N_OSC = 21

KIND_UNDER, KIND_CRIT, KIND_OVER = 1.0, 0.0, -1.0

# d = 0 and |1 - m omega^2| <= RESONANCE_SNAP: exact resonance (secular particular solution).
# omega cannot be typed more exactly (omega = 1/sqrt(1 + eta) rounds to |1 - m omega^2| ~ 2e-16), and
# the non-resonant form would have a particular amplitude F/|1 - m omega^2| ~ 1e15 F.
# d = 0 and gain 1/|1 - m omega^2| above NRES_GAIN: the cancellation-free near-resonant form.
NRES_GAIN = 1e3


def make_osc(m: float, d: float, omega: float, F: float) -> np.ndarray:
    """Pack the constants of m z'' + d z' + z = F sin(th) + d omega F cos(th), th = th0 + omega s.

    Weakly damped near-resonant parameters (d > 0, gain 1/|1 - m omega^2 + i d omega| above
    ``params.MAX_GAIN``) are refused by ``exact.oscillators`` (``check_conditioning``);
    undamped ones use the exact resonance or the near-resonant form (module docstring).
    """
    osc = [0.0] * N_OSC                 # filled as a list (cheaper), returned as an array
    sigma = d / (2.0 * m)
    om2 = 1.0 / m
    kappa = om2 - sigma * sigma
    osc[I_SIGMA], osc[I_OM2], osc[I_OM] = sigma, om2, math.sqrt(om2)
    osc[I_KAPPA], osc[I_SQ] = kappa, math.sqrt(abs(kappa))
    osc[I_KIND] = KIND_UNDER if kappa > 0 else (KIND_CRIT if kappa == 0 else KIND_OVER)
    osc[I_W], osc[I_M], osc[I_D], osc[I_F] = omega, m, d, F
    osc[I_FAMP] = abs(F) * math.hypot(1.0, d * omega)    # amplitude of the forcing
    det = 1.0 - m * omega * omega
    den = det * det + (d * omega) ** 2
    if d == 0.0 and abs(det) <= RESONANCE_SNAP:     # exact resonance (to round-off)
        osc[I_RES] = 1.0
        osc[I_ARES] = -F / (2.0 * m * omega)
    elif d == 0.0 and abs(det) * NRES_GAIN < 1.0:     # undamped, near resonance
        om = osc[I_OM]
        osc[I_NRES] = 1.0
        osc[I_SUM] = om + omega
        osc[I_DIFF] = det / (m * (om + omega))            # om - omega without cancellation
        osc[I_K] = F / (m * (om + omega))
    else:                                # H = (1 + i d omega)/(1 - m omega^2 + i d omega), z_p = F Im(H e^{i th})
        osc[I_PS] = F * (det + (d * omega) ** 2) / den
        osc[I_PC] = -F * m * d * omega ** 3 / den
        osc[I_PAMP] = math.hypot(osc[I_PS], osc[I_PC])
    osc[I_RATE] = max(osc[I_OM], omega, sigma + (osc[I_SQ] if kappa < 0 else 0.0))
    return np.array(osc)


@njit(cache=True, nogil=True)
def fundamentals(osc, s):
    """(C, C', S, S') of the homogeneous equation at local time s >= 0."""
    sigma = osc[I_SIGMA]
    sq = osc[I_SQ]
    kind = osc[I_KIND]
    if kind > 0.5:
        e = math.exp(-sigma * s)
        x = sq * s
        ecs = e * math.cos(x)
        esn = e * math.sin(x) / sq
    elif kind < -0.5:
        x = sq * s
        if x < 20.0:
            e = math.exp(-sigma * s)
            ecs = e * math.cosh(x)
            esn = e * math.sinh(x) / sq
        else:                            # avoid exp underflow times cosh overflow
            ep = math.exp((sq - sigma) * s)
            em = math.exp((-sq - sigma) * s)
            ecs = 0.5 * (ep + em)
            esn = 0.5 * (ep - em) / sq
    else:
        e = math.exp(-sigma * s)
        ecs = e
        esn = e * s
    return _fundamentals_from(osc, ecs, esn)


@njit(cache=True, nogil=True, inline="always")
def _fundamentals_from(osc, ecs, esn):
    """(C, C', S, S') from ecs = e^(-sigma s) cos|cosh(sq s) and esn = e^(-sigma s)
    sin|sinh(sq s)/sq (e^(-sigma s) s when critically damped): ``fundamentals``."""
    sigma = osc[I_SIGMA]
    S = esn
    C = ecs + sigma * esn
    dS = ecs - sigma * esn
    dC = -osc[I_OM2] * esn
    return C, dC, S, dS


@njit(cache=True, nogil=True)
def particular(osc, sth0, cth0, s):
    """Particular solution z_p and its first three derivatives at local time s.

    sth0, cth0 are sin and cos of the forcing phase theta0 at s = 0.
    """
    omega = osc[I_W]
    return _particular_from(osc, sth0, cth0, s, math.sin(omega * s), math.cos(omega * s))


@njit(cache=True, nogil=True, inline="always")
def _particular_from(osc, sth0, cth0, s, sw, cw):
    """``particular`` given sw, cw = sin, cos of omega s."""
    omega = osc[I_W]
    sth = sth0 * cw + cth0 * sw
    cth = cth0 * cw - sth0 * sw
    if osc[I_RES] > 0.5:
        A = osc[I_ARES]
        zp = A * s * cth
        zp1 = A * cth - A * omega * s * sth
        zp2 = -2.0 * A * omega * sth - A * omega * omega * s * cth
        zp3 = -3.0 * A * omega * omega * cth + A * omega * omega * omega * s * sth
    else:
        ps = osc[I_PS]
        pc = osc[I_PC]
        zp = ps * sth + pc * cth
        zp1 = omega * (ps * cth - pc * sth)
        zp2 = -omega * omega * zp
        zp3 = -omega * omega * zp1
    return zp, zp1, zp2, zp3


@njit(cache=True, nogil=True)
def particular0(osc, sth0, cth0):
    """z_p(0) and z_p'(0)."""
    if osc[I_RES] > 0.5:
        return 0.0, osc[I_ARES] * cth0
    ps = osc[I_PS]
    pc = osc[I_PC]
    return ps * sth0 + pc * cth0, osc[I_W] * (ps * cth0 - pc * sth0)


@njit(cache=True, nogil=True)
def _flow_nres(osc, x0, v0, sth0, cth0, s):
    """``flow`` of the undamped near-resonant oscillator (module docstring)."""
    om = osc[I_OM]
    om2 = osc[I_OM2]
    omega = osc[I_W]
    sg = osc[I_SUM]
    dl = osc[I_DIFF]
    K = osc[I_K]
    F = osc[I_F]
    so = math.sin(om * s)
    co = math.cos(om * s)
    hs = 0.5 * sg * s
    sh = math.sin(hs)
    ch = math.cos(hs)
    q = 0.5 * dl * s
    Q = math.sin(q) / dl if dl != 0.0 else 0.5 * s
    cq = math.cos(q)
    R = K * (2.0 * sth0 * sh * Q + cth0 * (so / om - 2.0 * ch * Q))
    R1 = K * (sth0 * (sg * ch * Q + sh * cq) + cth0 * (sg * sh * Q - ch * cq + co))
    z = x0 * co + v0 * so / om + R
    z1 = -x0 * om * so + v0 * co + R1
    sw = math.sin(omega * s)
    cw = math.cos(omega * s)
    sth = sth0 * cw + cth0 * sw
    cth = cth0 * cw - sth0 * sw
    z2 = om2 * (F * sth - z)
    z3 = om2 * (F * omega * cth - z1)
    b1 = math.sqrt(z1 * z1 + om2 * z * z)
    return z, z1, z2, z3, b1


@njit(cache=True, nogil=True, inline="always")
def flow_start(osc, x0, v0, sth0, cth0):
    """The start of ``flow_from``: (x0, v0, sin, cos of theta0, x_h, v_h), x_h and v_h the
    homogeneous parts of (x0, v0) (what ``flow`` computes from the start at every s; unused
    by the near-resonant undamped form)."""
    if osc[I_NRES] > 0.5:
        return x0, v0, sth0, cth0, 0.0, 0.0
    zp0, zp10 = particular0(osc, sth0, cth0)
    return x0, v0, sth0, cth0, x0 - zp0, v0 - zp10


@njit(cache=True, nogil=True, inline="always")
def flow_from(osc, start, s):
    """``flow`` at local time s from start = ``flow_start(osc, x0, v0, sin, cos)``, bit for
    bit: flows of one start at many s (the kernel's steps) compute the start once."""
    x0, v0, sth0, cth0, _, _ = start
    if osc[I_NRES] > 0.5:
        return _flow_nres(osc, x0, v0, sth0, cth0, s)
    return _flow_sum(osc, start, fundamentals(osc, s), particular(osc, sth0, cth0, s))


@njit(cache=True, nogil=True, inline="always")
def flow_at_zero(osc, start):
    """``flow_from(osc, start, 0.0)`` bit for bit without its exp, sin and cos calls. Their
    arguments are then +-0 (sigma, sq, omega finite; sq > 0 unless critically damped), where
    exp and cos are 1 and sin is its argument: ecs = 1 and esn = +0 in ``fundamentals``,
    sin(omega s) = omega 0 (+0) and cos(omega s) = 1 in ``particular``, exactly."""
    x0, v0, sth0, cth0, _, _ = start
    if osc[I_NRES] > 0.5:
        return _flow_nres(osc, x0, v0, sth0, cth0, 0.0)
    part = _particular_from(osc, sth0, cth0, 0.0, osc[I_W] * 0.0, 1.0)
    return _flow_sum(osc, start, _fundamentals_from(osc, 1.0, 0.0), part)


@njit(cache=True, nogil=True, inline="always")
def _flow_sum(osc, start, fund, part):
    """(z, z', z'', z''', b1) of ``flow_from`` from the start's homogeneous parts, the
    fundamentals fund = (C, C', S, S') and the particular solution's part = (z_p, z_p',
    z_p'', z_p''') at the same local time."""
    _, _, _, _, xh, vh = start
    C, dC, S, dS = fund
    zh = xh * C + vh * S
    zh1 = xh * dC + vh * dS
    om2 = osc[I_OM2]
    two_sigma = 2.0 * osc[I_SIGMA]
    zh2 = -two_sigma * zh1 - om2 * zh
    zh3 = -two_sigma * zh2 - om2 * zh1
    zp, zp1, zp2, zp3 = part
    b1 = math.sqrt(zh1 * zh1 + om2 * zh * zh)
    return zp + zh, zp1 + zh1, zp2 + zh2, zp3 + zh3, b1


@njit(cache=True, nogil=True)
def flow(osc, x0, v0, sth0, cth0, s):
    """State at local time s from (x0, v0) at s = 0.

    Returns (z, z', z'', z''', b1) where b1 = sqrt(2 E_h(s)) bounds |z_h'| from s on (for
    the near-resonant undamped form: the energy of the whole state at s).
    """
    return flow_from(osc, flow_start(osc, x0, v0, sth0, cth0), s)


@njit(cache=True, nogil=True)
def part_bounds(osc, b1, s_hi):
    """Upper bounds (B0, ..., B4) of |z^(n)|, n = 0..4, on [s, s_hi] given b1 = sqrt(2 E_h(s)).

    Each is the homogeneous part's bound b_n (module docstring) plus the particular part's
    (or, near resonance and undamped, the zero-initial-condition response's). They also
    measure the size of the parts the closed form adds, hence its round-off.
    """
    om = osc[I_OM]
    om2 = osc[I_OM2]
    two_sigma = 2.0 * osc[I_SIGMA]
    h0 = b1 / om
    h2 = two_sigma * b1 + om2 * h0
    h3 = two_sigma * h2 + om2 * b1
    h4 = two_sigma * h3 + om2 * h2
    omega = osc[I_W]
    if osc[I_NRES] > 0.5:
        # z(s + t) = free motion from the state at s (energy b1) + R_s(t), t <= s_hi, with
        # |R| <= K (2 t + 1/om), |R'| <= K (Sg t + 3), R^(n+2) = om2 (F omega^n sin|cos - R^(n))
        K = osc[I_K]
        F = osc[I_F]
        p0 = K * (2.0 * s_hi + 1.0 / om)
        p1 = K * (osc[I_SUM] * s_hi + 3.0)
        p2 = om2 * (F + p0)
        p3 = om2 * (F * omega + p1)
        p4 = om2 * (F * omega * omega + p2)
    elif osc[I_RES] > 0.5:
        # z_p^(n) = A omega^(n-1) (n trig + omega s trig): |A| omega^(n-1) (n + omega s_hi)
        A = abs(osc[I_ARES])
        ws = omega * s_hi
        p0 = A * s_hi
        p1 = A * (1.0 + ws)
        p2 = A * omega * (2.0 + ws)
        p3 = A * omega * omega * (3.0 + ws)
        p4 = A * omega * omega * omega * (4.0 + ws)
    else:
        p0 = osc[I_PAMP]
        p1 = p0 * omega
        p2 = p1 * omega
        p3 = p2 * omega
        p4 = p3 * omega
    return h0 + p0, b1 + p1, h2 + p2, h3 + p3, h4 + p4


@njit(cache=True, nogil=True)
def deriv_bound(osc, b1, n, s_hi):
    """Upper bound of |z^(n)| (n = 0..4) on [s, s_hi] given b1 = sqrt(2 E_h(s))
    (``part_bounds``)."""
    return part_bounds(osc, b1, s_hi)[n]


@njit(cache=True, nogil=True)
def state_bounds(osc, z, v, margin, H):
    """Bounds of |z''|, |z'''|, |z''''| on [s, s + H] from the whole state (z, z') at s.

    The energy of the whole motion, r = sqrt(z'^2 + z^2/m), grows at most like
    r' <= |f|/m <= FAMP/m (m z'' + d z' + z = f, |f^(n)| <= FAMP omega^n; the damping only
    takes energy out), so |z| <= r/om and |z'| <= r on [s, s + H] with r = r(s) + H FAMP/m,
    and the equation bounds the higher derivatives:
        |z^(n+2)| <= (FAMP omega^n + d |z^(n+1)| + |z^(n)|)/m.
    Unlike ``part_bounds`` this does not add the homogeneous and particular parts, which
    near resonance are each far larger than z (F/(d omega) against the orbit's size).
    ``margin`` (>= the round-off of the computed z and z') is added to r.
    """
    om2 = osc[I_OM2]
    d = osc[I_D]
    famp = osc[I_FAMP]
    omega = osc[I_W]
    r = math.sqrt(v * v + om2 * z * z) + margin + om2 * famp * H
    b2 = om2 * (famp + d * r + r / osc[I_OM])
    b3 = om2 * (famp * omega + d * b2 + r)
    b4 = om2 * (famp * omega * omega + d * b3 + b2)
    return b2, b3, b4


@njit(cache=True, nogil=True)
def forcing(osc, sth0, cth0, s):
    """Right-hand side F sin(theta) + d omega F cos(theta) at local time s."""
    omega = osc[I_W]
    sw = math.sin(omega * s)
    cw = math.cos(omega * s)
    sth = sth0 * cw + cth0 * sw
    cth = cth0 * cw - sth0 * sw
    F = osc[I_F]
    return F * sth + osc[I_D] * omega * F * cth


# ---------------------------------------------------------------------------------------------
# Exact integral of z'(s)^2 over [0, L].

@njit(cache=True, nogil=True)
def _phi1(x, ex):
    """(e^x - 1)/x for complex x, given ex = e^x; series near 0."""
    if abs(x) > 0.1:
        return (ex - 1.0) / x
    term = 1.0 + 0.0j
    acc = 1.0 + 0.0j
    for k in range(2, 14):
        term = term * x / k
        acc += term
    return acc


_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
# Underdamped, non-resonant oscillators: the integral of z'^2 over 2 to V2_GAUSS_PANELS
# panels by the Gauss rule on the exponential modes of z' (``_v2_modes_gauss``), whose
# factors at the panel centres follow by recurrence, afresh every V2_RESEED panels; longer
# intervals in closed form (``_v2_closed``) unless its terms cancel (near resonance).
V2_GAUSS_PANELS = 8
V2_RESEED = 8


@njit(cache=True, nogil=True)
def _n_panels(osc, L):
    """Panels of the Gauss rule on [0, L]: length <= 1/rate (finer when secular)."""
    rate = osc[I_RATE]
    npan = int(math.ceil(L * rate)) if L * rate > 1.0 else 1
    if osc[I_RES] > 0.5 or osc[I_NRES] > 0.5:     # secular growth: finer panels
        npan = max(npan, int(math.ceil(L * osc[I_W] * (1.0 + 0.05 * L))))
    return npan


@njit(cache=True, nogil=True)
def _v2_gauss(osc, x0, v0, sth0, cth0, L, gx, gw):
    """Gauss-Legendre rule (nodes gx, weights gw on [-1, 1]) for the integral of z'^2 over
    [0, L] on ``_n_panels`` panels, z' from ``flow``: any oscillator."""
    npan = _n_panels(osc, L)
    h = L / npan
    acc = 0.0
    for p in range(npan):
        a = p * h
        part = 0.0
        for k in range(gx.shape[0]):
            s = a + 0.5 * h * (gx[k] + 1.0)
            z, v, _, _, _ = flow(osc, x0, v0, sth0, cth0, s)
            part += gw[k] * v * v
        acc += 0.5 * h * part
    return acc


@njit(cache=True, nogil=True)
def _em1_pair(x):
    """(e^x - 1, e^-x - 1) for complex x, without cancellation for small |x| (the second
    without dividing by 1 + (e^x - 1) = 0 once e^Re(x) rounds it to 0: long decays)."""
    em = math.expm1(x.real)
    sh = math.sin(0.5 * x.imag)
    ch = math.cos(0.5 * x.imag)
    sb = 2.0 * sh * ch                      # sin(Im x)
    cm1 = -2.0 * sh * sh                    # cos(Im x) - 1
    if em > -1.0:
        em_neg = -em / (1.0 + em)           # e^-Re(x) - 1
    elif x.real > -709.0:                   # e^Re(x) < 2^-54 (em = -1): e^-Re(x) - 1
        em_neg = math.exp(-x.real)          # rounds to e^-Re(x)
    else:                                   # e^-Re(x) overflows
        em_neg = math.inf
    return (complex(em * (1.0 + cm1) + cm1, (1.0 + em) * sb),
            complex(em_neg * (1.0 + cm1) + cm1, -(1.0 + em_neg) * sb))


@njit(cache=True, nogil=True)
def _modes_at(omega, mu, s):
    """(e^(i omega s), e^(mu s) - 1, e^(-i omega s), e^(-mu s) - 1)."""
    ew = complex(math.cos(omega * s), math.sin(omega * s))
    m_p, m_m = _em1_pair(mu * s)
    return ew, m_p, ew.conjugate(), m_m


@njit(cache=True, nogil=True, inline="always")
def _node_modes(omega, mu, u):
    """The factors of the node pair c +- u of a panel centred at c (``_v2_modes_gauss``):
    (e^(i omega u), e^(mu u) - 1, e^(lam u), and the same at -u), lam = mu + i omega."""
    ew_p, m_p, ew_m, m_m = _modes_at(omega, mu, u)
    return ew_p, m_p, ew_p * (1.0 + m_p), ew_m, m_m, ew_m * (1.0 + m_m)


@njit(cache=True, nogil=True, inline="always")
def _pair_v2(DE, BE, Mc, node):
    """z'^2 at the node pair ``node`` (``_node_modes``) of a panel whose factors are
    DE = D e^(lam c), BE = Bp e^(i omega c), Mc = e^(mu c) - 1 (``_v2_modes_gauss``)."""
    ew_p, m_p, el_p, ew_m, m_m, el_m = node
    vp = (DE * el_p).real - (BE * ew_p * (Mc + m_p * (1.0 + Mc))).real
    vm = (DE * el_m).real - (BE * ew_m * (Mc + m_m * (1.0 + Mc))).real
    return vp * vp + vm * vm


@njit(cache=True, nogil=True)
def _v2_modes_gauss(Ah, lam, Bp, omega, L, npan, gx, gw):
    """``_v2_gauss`` for z'(s) = Re(Ah e^(lam s) + Bp e^(i omega s)), from the modes; the
    8-point rule (gx, gw: ``_GL_X``, ``_GL_W``).

    Written as z' = Re(D e^(lam s)) - Re(Bp e^(i omega s) (e^(mu s) - 1)), D = Ah + Bp,
    mu = lam - i omega: near resonance Ah ~ -Bp are each far larger than z', and this form
    does not add them (e^(lam s) = e^(i omega s) e^(mu s)). At the nodes c +- u of a panel
    centred at c the factors are products of the panel's (stepped from panel to panel,
    computed afresh every V2_RESEED panels) and the node's (once per node pair, gx being
    symmetric). Each node pair's sum runs over the panels in order and the pairs' sums are
    added from the outermost pair in; the panel's factors are computed once for all pairs.
    """
    h = L / npan
    mu = lam - complex(0.0, omega)
    D = Ah + Bp
    step_w, step_m, _, _ = _modes_at(omega, mu, h)
    Ew, Mc, _, _ = _modes_at(omega, mu, 0.5 * h)
    n0 = _node_modes(omega, mu, 0.5 * h * gx[7])
    n1 = _node_modes(omega, mu, 0.5 * h * gx[6])
    n2 = _node_modes(omega, mu, 0.5 * h * gx[5])
    n3 = _node_modes(omega, mu, 0.5 * h * gx[4])
    part0 = part1 = part2 = part3 = 0.0
    for p in range(npan):
        if p > 0 and p % V2_RESEED == 0:
            Ew, Mc, _, _ = _modes_at(omega, mu, (p + 0.5) * h)
        DE = D * (Ew * (1.0 + Mc))
        BE = Bp * Ew
        part0 += _pair_v2(DE, BE, Mc, n0)
        part1 += _pair_v2(DE, BE, Mc, n1)
        part2 += _pair_v2(DE, BE, Mc, n2)
        part3 += _pair_v2(DE, BE, Mc, n3)
        Ew *= step_w
        Mc += step_m * (1.0 + Mc)
    acc = 0.0
    acc += gw[7] * part0
    acc += gw[6] * part1
    acc += gw[5] * part2
    acc += gw[4] * part3
    return 0.5 * h * acc


@njit(cache=True, nogil=True)
def _v2_closed(Ah, lam, Bp, omega, L):
    """Integral over [0, L] of (Re(Ah e^(lam s) + Bp e^(i omega s)))^2 in closed form
    (lam = -sigma + i alpha). Returns (value, size of its largest terms)."""
    sigma = -lam.real
    alpha = lam.imag
    E = math.exp(-sigma * L) * complex(math.cos(alpha * L), math.sin(alpha * L))  # e^{lam L}
    G = complex(math.cos(omega * L), math.sin(omega * L))                         # e^{iWL}
    iW = complex(0.0, omega)
    J_m2s = L * _phi1(complex(-2.0 * sigma * L, 0.0), complex(abs(E) ** 2, 0.0))
    J_lmw = L * _phi1((lam - iW) * L, E * G.conjugate())
    J_2l = L * _phi1(2.0 * lam * L, E * E)
    J_2w = L * _phi1(2.0 * iW * L, G * G)
    J_lpw = L * _phi1((lam + iW) * L, E * G)
    mod2 = (abs(Ah) ** 2) * J_m2s.real + (abs(Bp) ** 2) * L \
        + 2.0 * (Ah * Bp.conjugate() * J_lmw).real
    sq2 = (Ah * Ah * J_2l + Bp * Bp * J_2w + 2.0 * Ah * Bp * J_lpw).real
    big = abs(Ah) + abs(Bp)
    return 0.5 * (mod2 + sq2), big * big * L


@njit(cache=True, nogil=True)
def v2_integral(osc, x0, v0, sth0, cth0, L):
    """Exact integral of z'(s)^2 over local time [0, L].

    Clearly underdamped, non-resonant oscillators: z' = Re(Ah e^(lam s) + Bp e^(i omega s)),
    integrated in closed form (sums of complex exponentials) on long intervals where its
    terms do not cancel heavily (they do near resonance), else by the Gauss rule on these
    modes (``_v2_modes_gauss``). Other oscillators, and intervals of one panel: the Gauss
    rule on ``flow`` (``_v2_gauss``). An 8-point Gauss-Legendre rule on panels of length
    <= 1/rate is exact to round-off for these smooth, band-limited integrands.
    """
    if L <= 0.0:
        return 0.0
    sigma = osc[I_SIGMA]
    om2 = osc[I_OM2]
    kappa = osc[I_KAPPA]
    npan = _n_panels(osc, L)
    if osc[I_KIND] < 0.5 or osc[I_RES] > 0.5 or osc[I_NRES] > 0.5 or kappa < 0.01 * om2 \
            or npan == 1:
        return _v2_gauss(osc, x0, v0, sth0, cth0, L, _GL_X, _GL_W)
    alpha = osc[I_SQ]
    omega = osc[I_W]
    zp0, zp10 = particular0(osc, sth0, cth0)
    xh = x0 - zp0
    vh = v0 - zp10
    # z_h'(s) = e^{-sigma s} (a cos(alpha s) + b sin(alpha s)) = Re(Ah e^{lam s}), a = vh
    b = -(om2 * xh + sigma * vh) / alpha
    Ah = complex(vh, -b)
    lam = complex(-sigma, alpha)
    # z_p'(s) = Re(Bp e^{i omega s})
    Bp = omega * complex(osc[I_PS], osc[I_PC]) * complex(cth0, sth0)
    if npan > V2_GAUSS_PANELS:
        res, big = _v2_closed(Ah, lam, Bp, omega, L)
        if big <= 1e3 * res:       # else the terms cancel (near resonance)
            return res
    return _v2_modes_gauss(Ah, lam, Bp, omega, L, npan, _GL_X, _GL_W)


@njit(cache=True, nogil=True)
def s_factors(osc, s):
    """The factors of ``flow`` that depend on s only: (C, C', S, S', sin, cos of omega s)."""
    C, dC, S, dS = fundamentals(osc, s)
    w = osc[I_W]
    return C, dC, S, dS, math.sin(w * s), math.cos(w * s)


@njit(cache=True, nogil=True)
def flow_zv(osc, start, s, fs):
    """(z, z') of ``flow`` from start = (x0, v0, sin, cos of theta0) given fs =
    ``s_factors(osc, s)``: flows of one length s from many starts (the affine seeds of
    ``orbits``) share fs. The arithmetic of ``flow`` (``particular0``, ``fundamentals``,
    ``particular``) for z and z' only, bit for bit (tests); not for the near-resonant
    undamped form (osc[I_NRES]: use ``flow``). Written out here because ``flow`` built from
    these pieces runs about 20 % slower."""
    x0, v0, sth0, cth0 = start
    C, dC, S, dS, sw, cw = fs
    omega = osc[I_W]
    zp0, zp10 = particular0(osc, sth0, cth0)
    xh = x0 - zp0
    vh = v0 - zp10
    zh = xh * C + vh * S
    zh1 = xh * dC + vh * dS
    sth = sth0 * cw + cth0 * sw
    cth = cth0 * cw - sth0 * sw
    if osc[I_RES] > 0.5:
        A = osc[I_ARES]
        zp = A * s * cth
        zp1 = A * cth - A * omega * s * sth
    else:
        ps = osc[I_PS]
        pc = osc[I_PC]
        zp = ps * sth + pc * cth
        zp1 = omega * (ps * cth - pc * sth)
    return zp + zh, zp1 + zh1
