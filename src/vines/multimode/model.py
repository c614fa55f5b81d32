"""A linear host of N degrees of freedom carrying absorbers, and its base forcing.

Conventions (docs/model.md, "General model"): any consistent units (SI, or dimensionless as
the 1-DOF model); absolute coordinates. Host displacements x (N), absorber displacements y
(one each). Between impacts

    M x'' + C (x' - iota u') + K (x - iota u) = sum_i e_{j_i} (k_i s_i + c_i s_i'),
    m_i y_i'' = -(k_i s_i + c_i s_i'),            s_i = y_i - x_{j_i},

u(t) the base displacement, iota the influence vector (the host's displacement under a
rigid unit motion of the base: ones for a chain on the ground). The gap coordinate of
absorber i is w_i = x_{j_i} - y_i (as the 1-DOF model's w = z_m - z_b): walls at
w_i = +L_i (wall code +1, "L") and w_i = -L_i (wall code -1, "R"); L_i = inf is no stop.
Kinds: VI NES (k = c = 0, L finite), TMD (L = inf), TMD with end stops (all finite).
The 1-DOF model is N = 1, M = 1, K = 1, C = d, iota = 1, one absorber of mass eta with
k = c = 0 and L = 1, u = F sin(omega t + phi).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core.params import D_DEFAULT, R_DEFAULT, ParameterError, check_int, check_real

#: at most this many absorbers (the engine precomputes one linear system per set of
#: absorbers stuck at a wall: 2^n of them)
MAX_ABSORBERS = 6
#: at most this many host degrees of freedom
MAX_DOF = 24
#: relative tolerance of the symmetry of M, C, K
SYMMETRY_TOL = 1e-10
ABSORBER_KINDS = ("vi_nes", "tmd", "tmd_stops")


def _matrix(name: str, value, n: int | None = None) -> np.ndarray:
    """A finite square float matrix (of size n when given), or ParameterError."""
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a square matrix of numbers") from None
    if a.ndim == 0 and n in (None, 1):
        a = a.reshape(1, 1)
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] == 0:
        raise ParameterError(name, value, "must be a square matrix of numbers (a list of rows)")
    if n is not None and a.shape[0] != n:
        raise ParameterError(name, value, f"must be {n} x {n} (the host's degrees of freedom)")
    if not np.all(np.isfinite(a)):
        raise ParameterError(name, value, "must hold finite numbers only (no NaN, no inf)")
    return a


def _vector(name: str, value, n: int, lo=None, lo_open=False) -> np.ndarray:
    try:
        a = np.array(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ParameterError(name, value, f"must be a list of {n} numbers") from None
    if a.size != n:
        raise ParameterError(name, value, f"must be a list of {n} numbers")
    for v in a:
        check_real(name, v, lo=lo, lo_open=lo_open)
    return a


def _symmetric(name: str, a: np.ndarray, definite: bool) -> np.ndarray:
    """a, checked symmetric and positive definite (or semi-definite)."""
    scale = max(1.0, float(np.abs(a).max()))
    if np.abs(a - a.T).max() > SYMMETRY_TOL * scale:
        i, j = np.unravel_index(np.argmax(np.abs(a - a.T)), a.shape)
        raise ParameterError(name, a.tolist(), f"must be symmetric (entry [{i}][{j}] = {a[i, j]:g} "
                                               f"but [{j}][{i}] = {a[j, i]:g})")
    a = 0.5 * (a + a.T)
    lo = float(np.linalg.eigvalsh(a).min())
    if definite and lo <= 1e-12 * scale:
        raise ParameterError(name, a.tolist(), f"must be positive definite (smallest eigenvalue "
                                               f"{lo:.3g})")
    if not definite and lo < -1e-12 * scale:
        raise ParameterError(name, a.tolist(), f"must be positive semi-definite (smallest "
                                               f"eigenvalue {lo:.3g})")
    return a


@dataclass(frozen=True)
class Host:
    """The linear host: mass, damping and stiffness matrices (N x N) and influence vector.

    Validated when built: M and K symmetric positive definite, C symmetric positive
    semi-definite, all finite; influence default ones. ``Host.from_modes`` builds one from modal data.
    """

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    influence: np.ndarray = None

    def __post_init__(self):
        M = _matrix("host.mass", self.mass)
        n = M.shape[0]
        if n > MAX_DOF:
            raise ParameterError("host.mass", f"{n} x {n}", f"at most {MAX_DOF} degrees of freedom")
        object.__setattr__(self, "mass", _symmetric("host.mass", M, True))
        object.__setattr__(self, "stiffness",
                           _symmetric("host.stiffness", _matrix("host.stiffness", self.stiffness, n), True))
        object.__setattr__(self, "damping",
                           _symmetric("host.damping", _matrix("host.damping", self.damping, n), False))
        infl = np.ones(n) if self.influence is None else self.influence
        object.__setattr__(self, "influence", _vector("host.influence", infl, n))

    @property
    def n_dof(self) -> int:
        return self.mass.shape[0]

    @classmethod
    def from_modes(cls, frequencies, damping_ratios, shapes, modal_masses=None,
                   influence=None) -> Host:
        """The host of the given modes: natural frequencies omega_k > 0 [rad per time unit],
        damping ratios zeta_k >= 0, shapes (one row per mode, N rows of N entries) and modal
        masses mu_k > 0 (default 1): M = S^-T diag(mu) S^-1, K = S^-T diag(mu omega^2) S^-1,
        C = S^-T diag(2 zeta mu omega) S^-1 with S the shapes as columns (classical damping)."""
        S = _matrix("host.modes.shapes", shapes).T
        n = S.shape[0]
        w = _vector("host.modes.frequencies", frequencies, n, lo=0.0, lo_open=True)
        z = _vector("host.modes.damping_ratios", damping_ratios, n, lo=0.0)
        mu = (np.ones(n) if modal_masses is None
              else _vector("host.modes.modal_masses", modal_masses, n, lo=0.0, lo_open=True))
        if np.linalg.cond(S) > 1e10:
            raise ParameterError("host.modes.shapes", S.T.tolist(), "must be linearly independent")
        Si = np.linalg.inv(S)
        M = Si.T @ np.diag(mu) @ Si
        K = Si.T @ np.diag(mu * w ** 2) @ Si
        C = Si.T @ np.diag(2.0 * z * mu * w) @ Si
        sym = [0.5 * (a + a.T) for a in (M, K, C)]
        return cls(sym[0], sym[1], sym[2], np.ones(n) if influence is None else influence)


@dataclass(frozen=True)
class Absorber:
    """One absorber on host degree of freedom ``dof`` (0-based): mass > 0, stiffness >= 0,
    damping >= 0 of its link to the host, gap L in (0, inf] (inf: no end stops) and
    restitution r in [0, 1] of its impacts on the stops."""

    dof: int
    mass: float
    stiffness: float = 0.0
    damping: float = 0.0
    gap: float = math.inf
    restitution: float = 0.65

    def __post_init__(self):
        object.__setattr__(self, "dof", check_int("absorber.dof", self.dof, lo=0))
        object.__setattr__(self, "mass", check_real("absorber.mass", self.mass, lo=0.0, lo_open=True))
        object.__setattr__(self, "stiffness", check_real("absorber.stiffness", self.stiffness, lo=0.0))
        object.__setattr__(self, "damping", check_real("absorber.damping", self.damping, lo=0.0))
        gap = self.gap
        if gap is None or (isinstance(gap, str) and gap.strip().lower() in ("inf", ".inf", "none")):
            gap = math.inf
        if not (isinstance(gap, float) and gap == math.inf):
            gap = check_real("absorber.gap", gap, lo=0.0, lo_open=True)
        object.__setattr__(self, "gap", gap)
        object.__setattr__(self, "restitution",
                           check_real("absorber.restitution", self.restitution, lo=0.0, hi=1.0))
        if math.isinf(gap) and self.stiffness == 0.0:
            raise ParameterError("absorber.stiffness", 0.0, "must be > 0 when the absorber has "
                                 "no end stops (gap inf): it would drift away from its host")

    @property
    def kind(self) -> str:
        """'vi_nes' (no link), 'tmd' (no stops) or 'tmd_stops'."""
        if math.isinf(self.gap):
            return "tmd"
        return "vi_nes" if self.stiffness == 0.0 and self.damping == 0.0 else "tmd_stops"


@dataclass(frozen=True)
class HarmonicBase:
    """Harmonic base displacement u(t) = amplitude sin(frequency t + phase).

    One forcing description (``kind``); the engine evaluates its particular solution. The
    sampled base acceleration of the random-excitation issue is a second kind: piecewise
    linear acceleration, a polynomial particular solution per sample interval."""

    amplitude: float
    frequency: float
    phase: float = 0.0
    kind: str = field(default="harmonic", init=False)

    def __post_init__(self):
        object.__setattr__(self, "amplitude", check_real("forcing.amplitude", self.amplitude, lo=0.0))
        object.__setattr__(self, "frequency",
                           check_real("forcing.frequency", self.frequency, lo=0.0, lo_open=True))
        object.__setattr__(self, "phase", check_real("forcing.phase", self.phase, lo=-1e3, hi=1e3))

    def displacement(self, t):
        return self.amplitude * np.sin(self.frequency * np.asarray(t) + self.phase)

    def velocity(self, t):
        return self.amplitude * self.frequency * np.cos(self.frequency * np.asarray(t) + self.phase)


FORCINGS = {"harmonic": HarmonicBase}


@dataclass(frozen=True)
class HostModel:
    """A host, its absorbers and its base forcing, validated together (indices in range)."""

    host: Host
    absorbers: tuple
    forcing: HarmonicBase

    def __post_init__(self):
        if not isinstance(self.host, Host):
            raise ParameterError("host", self.host, "must be a vines.multimode.Host")
        ab = tuple(self.absorbers)
        if len(ab) > MAX_ABSORBERS:
            raise ParameterError("absorbers", len(ab), f"at most {MAX_ABSORBERS} absorbers")
        for i, a in enumerate(ab):
            if not isinstance(a, Absorber):
                raise ParameterError(f"absorbers[{i}]", a, "must be a vines.multimode.Absorber")
            if a.dof >= self.host.n_dof:
                raise ParameterError(f"absorbers[{i}].dof", a.dof,
                                     f"must be a host degree of freedom, 0 ... {self.host.n_dof - 1}")
        object.__setattr__(self, "absorbers", ab)
        if not isinstance(self.forcing, HarmonicBase):
            raise ParameterError("forcing", self.forcing, f"must be one of {sorted(FORCINGS)}")

    @property
    def n_dof(self) -> int:
        return self.host.n_dof

    @property
    def n_absorbers(self) -> int:
        return len(self.absorbers)

    @classmethod
    def one_dof(cls, eta, omega, F, r=R_DEFAULT, d=D_DEFAULT, phi=0.0) -> HostModel:
        """The 1-DOF model of ``vines.simulate`` (LO of unit mass and stiffness, damping d,
        one ball of mass eta in a cavity of half length 1) as a HostModel."""
        host = Host([[1.0]], [[1.0]], [[d]], [1.0])
        return cls(host, (Absorber(0, eta, 0.0, 0.0, 1.0, r),), HarmonicBase(F, omega, phi))

    def to_dict(self) -> dict:
        """The model as the plain mapping of a model file."""
        h = self.host
        return {"host": {"mass": h.mass.tolist(), "stiffness": h.stiffness.tolist(),
                         "damping": h.damping.tolist(), "influence": h.influence.tolist()},
                "absorbers": [{"dof": a.dof, "mass": a.mass, "stiffness": a.stiffness,
                               "damping": a.damping, "gap": a.gap, "restitution": a.restitution,
                               "kind": a.kind} for a in self.absorbers],
                "forcing": {"kind": self.forcing.kind, "amplitude": self.forcing.amplitude,
                            "frequency": self.forcing.frequency, "phase": self.forcing.phase}}
