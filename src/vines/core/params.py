"""Model parameters, solver settings and their validation.

Conventions (see docs/model.md and the spec):

* Everything is dimensionless: lengths in units of the half cavity length L, time
  t = w0 * t_dim with w0 = sqrt(k/M), velocities in units of L*w0.
* d = c/(M w0) is the LO damping coefficient in the dimensionless equation
  z_m'' + d z_m' + z_m = F sin(omega t + phi) + d omega F cos(omega t + phi). It is held fixed
  when the ball mass ratio eta changes (c and M are fixed). Keeping the paper's
  xi = c/(m w0) fixed instead is offered explicitly through ``ModelParams.from_xi``.
* Walls: w = z_m - z_b. Wall L is w = +1, wall R is w = -1.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import asdict, dataclass, field

#: the parameters a study varies, in the order of grid dimensions
PARAM_NAMES = ("eta", "omega", "F")

# Table 1 of the paper (SI units).
M_LO_KG = 3.807          # mass of the linear oscillator M [kg]
L_HALF_M = 0.015         #: half cavity length L [m] (2L = 0.03 m), Table 1
R_DEFAULT = 0.65         # coefficient of restitution r [-]
K_SPRING_N_PER_M = 11680.0   # spring stiffness k [N/m]
C_DAMP_NS_PER_M = 2.53       # damping coefficient c [N s/m]

W0_RAD_S = math.sqrt(K_SPRING_N_PER_M / M_LO_KG)                 # 55.390 rad/s
D_DEFAULT = C_DAMP_NS_PER_M / (M_LO_KG * W0_RAD_S)                #: d = c/(M w0) of Table 1, 0.011998

T_END_DEFAULT = 7000.0
T_TRANSIENT_DEFAULT = 4000.0
V_STICK_DEFAULT = 1e-6
MAX_IMPACTS_DEFAULT = 2_000_000
ROOT_TOL_DEFAULT = 1e-13
RTOL_DEFAULT = 1e-12          # rtol of the RK reference solver
# Bifurcation sweeps (``core.sweep.SweepLine``): the first point's run from rest, each next
# point's run (dimensionless time), forcing periods recorded at the end of each run, and
# the impact budget per forcing period of a run
T_SETTLE_DEFAULT = 4000.0
T_STEP_DEFAULT = 1000.0
N_RECORD_DEFAULT = 50
MAX_IMPACTS_PER_PERIOD_DEFAULT = 400

# Upper bounds of every numeric input (API and CLI alike). Each is far beyond any legitimate
# use (the solver is tested at eta 1e-6..50, omega 0.05..8, F 0..20, d 0..3, runs to 1e5) and
# small enough that no intermediate of the closed form can overflow: the largest denominator
# (1 - (1 + eta) omega^2)^2 + (d omega)^2 stays below 1e19, forcing-frequency products
# F omega^2 below 1e10.
ETA_MAX = 1e3                 # ball-to-LO mass ratio m/M
OMEGA_MAX = 1e3               # forcing frequency ratio w/w0
F_MAX = 1e4                   # forcing amplitude A/L
D_MAX = 1e3                   # LO damping c/(M w0) (d = 2 is already critical damping)
PHI_MAX = 1e3                 # |phi| in rad (a phase: reduce it mod 2 pi)
T_END_MAX = 1e9               # dimensionless time (1.6e8 forcing periods at omega = 1)
V_STICK_MAX = 1.0             # chatter threshold, in units of L w0
MAX_IMPACTS_MAX = 100_000_000  # impact records cost ~150 bytes each
STATE_MAX = 1e12              # |z_m0|, |v_m0|, |z_b0|, |v_b0| of the initial state
RTOL_MIN, RTOL_MAX = 1e-14, 1e-2   # rtol of the RK reference solver
MAX_POINTS_DEFAULT = 100_000  # continuation points a step may need (``continue_branch``) ...
MAX_POINTS_MAX = 10_000_000   # ... and the largest max_points allowed
CONTINUATION_METHODS = ("arclength", "natural")   # ``continue_branch(method=...)``
BRANCH_KINDS = ("symmetric", "asymmetric")        # the 1:1 orbit families
MAX_INADMISSIBLE_DEFAULT = 1000   # consecutive non-admissible points that end a branch

#: (lo, lo_open, hi) of each model parameter: lo < x (lo_open) or lo <= x, and x <= hi;
#: phi is bounded in absolute value
PARAM_BOUNDS = {
    "eta": (0.0, True, ETA_MAX),
    "omega": (0.0, True, OMEGA_MAX),
    "F": (0.0, False, F_MAX),
    "r": (0.0, False, 1.0),
    "d": (0.0, False, D_MAX),
    "phi": (-PHI_MAX, False, PHI_MAX),
}

# Conditioning of the exact solver's closed form (see ``check_conditioning``).
RESONANCE_SNAP = 16.0 * 2.220446049250313e-16   # d = 0, |1 - m omega^2| <= this: exact resonance
MAX_GAIN = 1e4                                   # largest 1/|1 - m omega^2 + i d omega| for d > 0


class ParameterError(ValueError):
    """A user-supplied value is outside its allowed range.

    ``str(err)`` is one line naming the parameter, the value and what is allowed.
    """

    def __init__(self, name: str, value, allowed: str):
        self.name = name
        self.value = value
        self.allowed = allowed
        super().__init__(f"invalid {name} = {value!r}: {allowed}")


def _as_float(name, value) -> float:
    if isinstance(value, bool):
        raise ParameterError(name, value, "must be a number")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a number") from None
    if not math.isfinite(x):
        raise ParameterError(name, value, "must be a finite number")
    return x


def _allowed(lo, hi, lo_open, hi_open) -> str:
    """The range ``check_real`` allows, in words (for its error message)."""
    parts = []
    if lo is not None:
        parts.append(f"> {lo:g}" if lo_open else f">= {lo:g}")
    if hi is not None:
        parts.append(f"< {hi:g}" if hi_open else f"<= {hi:g}")
    return "must be a finite number" + (" " + " and ".join(parts) if parts else "")


def check_real(name, value, *, lo=None, hi=None, lo_open=False, hi_open=False) -> float:
    """Return ``value`` as a float or raise ParameterError naming ``name``."""
    x = value if type(value) is float and math.isfinite(value) else _as_float(name, value)
    if (lo is not None and (x < lo or (lo_open and x == lo))) \
            or (hi is not None and (x > hi or (hi_open and x == hi))):
        raise ParameterError(name, value, _allowed(lo, hi, lo_open, hi_open))
    return x


def check_param(name: str, value) -> float:
    """Validate one model parameter (a key of PARAM_BOUNDS) and return it as a float."""
    lo, lo_open, hi = PARAM_BOUNDS[name]
    return check_real(name, value, lo=lo, lo_open=lo_open, hi=hi)


def check_int(name, value, *, lo=None, hi=None) -> int:
    """Return ``value`` as an int (also '10', 2e6 or '2e6') or raise ParameterError naming ``name``."""
    if isinstance(value, bool):
        raise ParameterError(name, value, "must be an integer")
    try:
        x = int(value)
        if x != float(value):
            raise ValueError
    except (TypeError, ValueError, OverflowError):
        try:                                    # a float with an integral value ('2e6')
            f = float(value)
        except (TypeError, ValueError):
            raise ParameterError(name, value, "must be an integer") from None
        if not (math.isfinite(f) and f.is_integer()):
            raise ParameterError(name, value, "must be an integer") from None
        x = int(f)
    if (lo is not None and x < lo) or (hi is not None and x > hi):
        parts = ([f">= {lo}"] if lo is not None else []) + ([f"<= {hi}"] if hi is not None else [])
        raise ParameterError(name, value, "must be an integer " + " and ".join(parts))
    return x


def check_step_points(step_given, span: float, step: float, max_points: int,
                      max_points_name: str = "max_points") -> None:
    """Refuse a continuation step that needs more than ``max_points`` points.

    ``span`` = |stop - start| and ``step`` > 0 (validated); ``step_given`` is the value as the
    user wrote it (for the message). A relative slack of 1e-9 absorbs the round-off of
    span/step (0.02/0.005 = 4.000000000000001).
    """
    n = span / step
    if n > max_points * (1.0 + 1e-9):
        raise ParameterError(
            "step", step_given,
            f"needs |stop - start|/step = {n:.3g} points > {max_points_name} = {max_points}: "
            f"use a step >= {span / max_points:.6g} (or raise {max_points_name}, at most "
            f"{MAX_POINTS_MAX})")


def check_bool(name, value) -> bool:
    """True or False (also numpy booleans and the integers 0 and 1); else ParameterError."""
    if isinstance(value, bool):       # the usual case, without the lookups below
        return value
    numpy_bool = getattr(getattr(value, "dtype", None), "kind", "") == "b" \
        and getattr(value, "ndim", 1) == 0
    if isinstance(value, bool) or numpy_bool or (
            isinstance(value, numbers.Integral) and value in (0, 1)):
        return bool(value)
    raise ParameterError(name, value, "must be true or false")


def check_choice(name, value, choices) -> str:
    """``value`` if it is one of the strings ``choices``; else ParameterError naming ``name``."""
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(name, value, f"must be one of {', '.join(choices)}")
    return value


def as_float_array(name, values):
    """``values`` (a number or an array-like of numbers, any shape) as a float array, else
    ParameterError naming ``name``; the values themselves are checked by the caller."""
    import numpy as np  # here: ``import vines`` loads the parameter containers only

    if isinstance(values, (str, bytes, dict, set)) or values is None:
        raise ParameterError(name, values, "must be a number or an array of numbers")
    try:
        return np.asarray(values, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(name, values, "must be a number or an array of numbers") from None


def check_reals(name, values, *, lo=None, hi=None, lo_open=False, min_size=1,
                max_size=None):
    """A scalar or sequence of finite numbers in [lo, hi] as a flat float array, else ParameterError.

    At least ``min_size`` and at most ``max_size`` values; the first bad value is named.
    """
    import numpy as np

    arr = as_float_array(name, values).ravel()
    if arr.size < min_size or (max_size is not None and arr.size > max_size):
        what = f"at least {min_size}" + (f" and at most {max_size}" if max_size is not None else "")
        raise ParameterError(name, values, f"must hold {what} values")
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(arr)
        if lo is not None:
            bad |= (arr <= lo) if lo_open else (arr < lo)
        if hi is not None:
            bad |= arr > hi
    if bad.any():
        check_real(name, float(arr[bad][0]), lo=lo, hi=hi, lo_open=lo_open)
    return arr


def check_callable(name, value):
    """``value`` if it is None or callable; else ParameterError naming ``name``."""
    if value is not None and not callable(value):
        raise ParameterError(name, value, "must be a function or None")
    return value


def check_params_arg(name, value) -> ModelParams:
    """``value`` if it is a ``ModelParams``; else ParameterError naming ``name``."""
    if not isinstance(value, ModelParams):
        raise ParameterError(name, value, "must be a vines.ModelParams")
    return value


def check_conditioning(eta: float, omega: float, F: float, d: float) -> None:
    """Refuse weakly damped near-resonant points that the exact solver cannot resolve.

    The closed form writes the motion of the free LO (mass m = 1) and of the stuck body
    (m = 1 + eta) as homogeneous + particular parts whose amplitudes reach F * gain,
    gain = 1/|1 - m omega^2 + i d omega|, while the motion itself stays of order F or the cavity
    size; the round-off of the sum grows like 1e-16 F gain. Undamped points (d = 0) are
    always accepted: exact resonance (|1 - m omega^2| <= RESONANCE_SNAP) has the secular
    solution and near resonance a cancellation-free form (``vines.flow``). With d > 0,
    points with gain > MAX_GAIN (only possible for d < 1e-4 within 1e-4 of a natural
    frequency 1/sqrt(m)) raise ParameterError on omega. F = 0 is always accepted. The RK
    reference solver does not need this check.
    """
    if F == 0.0 or d == 0.0:
        return
    for m, body in ((1.0, "free LO"), (1.0 + eta, "stuck body (mass 1 + eta)")):
        det = 1.0 - m * omega * omega
        gain = 1.0 / math.hypot(det, d * omega)
        if gain > MAX_GAIN:
            wn = 1.0 / math.sqrt(m)
            raise ParameterError(
                "omega", omega,
                f"too close to the natural frequency {wn!r} of the {body} for d = {d:g} "
                f"(gain 1/|1 - m omega^2 + i d omega| = {gain:.3g} > {MAX_GAIN:g}: the exact solver's "
                f"closed form would lose too many digits); detune omega, use d >= "
                f"{1.0 / (MAX_GAIN * omega):.3g} or d = 0; the rk solver is not affected")


@dataclass(frozen=True)
class ModelParams:
    """Dimensionless VINES parameters (validated on construction).

    ::

        eta   ball-to-LO mass ratio m/M (0 < eta <= ETA_MAX = 1e3)
        omega forcing frequency ratio omega = w/w0 (0 < omega <= OMEGA_MAX = 1e3)
        F     forcing amplitude A/L (0 <= F <= F_MAX = 1e4)
        r     coefficient of restitution (0 <= r <= 1)
        d     LO damping c/(M w0) (0 <= d <= D_MAX = 1e3), fixed for every eta by default
        phi   forcing phase at t = 0 [rad] (|phi| <= PHI_MAX = 1e3)
    """

    eta: float
    omega: float
    F: float
    r: float = R_DEFAULT
    d: float = D_DEFAULT
    phi: float = 0.0

    def __post_init__(self):
        set_ = object.__setattr__
        for name in PARAM_BOUNDS:
            set_(self, name, check_param(name, getattr(self, name)))

    @classmethod
    def from_xi(cls, eta, omega, F, xi, r=R_DEFAULT, phi=0.0) -> ModelParams:
        """Paper's parameterisation with xi = c/(m w0) held fixed: d = eta * xi."""
        eta = check_param("eta", eta)
        xi = check_real("xi", xi, lo=0.0, hi=D_MAX / eta)     # d = eta xi <= D_MAX
        return cls(eta=eta, omega=omega, F=F, r=r, d=eta * xi, phi=phi)

    @classmethod
    def from_dimensional(cls, *, m_ball_kg, omega_rad_s, A_m, M_kg=M_LO_KG, L_m=L_HALF_M,
                         k_N_per_m=K_SPRING_N_PER_M, c_Ns_per_m=C_DAMP_NS_PER_M,
                         r=R_DEFAULT, phi=0.0) -> ModelParams:
        """Build the dimensionless set from SI quantities (paper Eq. 7)."""
        M = check_real("M_kg", M_kg, lo=0.0, lo_open=True)
        k = check_real("k_N_per_m", k_N_per_m, lo=0.0, lo_open=True)
        L = check_real("L_m", L_m, lo=0.0, lo_open=True)
        c = check_real("c_Ns_per_m", c_Ns_per_m, lo=0.0)
        m = check_real("m_ball_kg", m_ball_kg, lo=0.0, lo_open=True)
        w = check_real("omega_rad_s", omega_rad_s, lo=0.0, lo_open=True)
        A = check_real("A_m", A_m, lo=0.0)
        w0 = math.sqrt(k / M)
        return cls(eta=m / M, omega=w / w0, F=A / L, r=r, d=c / (M * w0), phi=phi)

    @property
    def period(self) -> float:
        """Forcing period T = 2 pi / omega (dimensionless time)."""
        return 2.0 * math.pi / self.omega

    @property
    def omega_s(self) -> float:
        """Natural frequency of the stuck system, w_s/w0 = 1/sqrt(1 + eta)."""
        return 1.0 / math.sqrt(1.0 + self.eta)

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class SolverSettings:
    """Settings of one simulation run (validated on construction).

    ::

        t_end        end of the run (dimensionless time, 0 < t_end <= T_END_MAX = 1e9)
        t_transient  start of the measurement window [t_transient, t_end]
                     (0 <= t_transient < t_end)
        v_stick      chatter threshold (0 <= v_stick <= V_STICK_MAX = 1): after an impact
                     with |w'+| <= v_stick while the relative acceleration presses the
                     ball on the wall, ball and LO stick
                     (the exact solver also sticks below the speed of a bounce only a few
                     round-off units high, see ``vines._engine``)
        max_impacts  guard: the run stops with status "max_impacts" after this many impacts
                     (1 <= max_impacts <= MAX_IMPACTS_MAX = 1e8)
        root_tol     distance to the wall (in units of L) at which contact is declared (or
                     the round-off level of w when larger)
        state0       initial (z_m, z_m', z_b, z_b') at t = 0, |z_m - z_b| <= 1,
                     each |.| <= 1e12
    """

    t_end: float = T_END_DEFAULT
    t_transient: float = T_TRANSIENT_DEFAULT
    v_stick: float = V_STICK_DEFAULT
    max_impacts: int = MAX_IMPACTS_DEFAULT
    root_tol: float = ROOT_TOL_DEFAULT
    state0: tuple = field(default=(0.0, 0.0, 0.0, 0.0))

    def __post_init__(self):
        set_ = object.__setattr__
        t_end = check_real("t_end", self.t_end, lo=0.0, lo_open=True, hi=T_END_MAX)
        set_(self, "t_end", t_end)
        tt = check_real("t_transient", self.t_transient, lo=0.0)
        if tt >= t_end:
            raise ParameterError("t_transient", self.t_transient,
                                 f"must be >= 0 and < t_end = {t_end:g}")
        set_(self, "t_transient", tt)
        set_(self, "v_stick", check_real("v_stick", self.v_stick, lo=0.0, hi=V_STICK_MAX))
        set_(self, "max_impacts", check_int("max_impacts", self.max_impacts, lo=1,
                                            hi=MAX_IMPACTS_MAX))
        set_(self, "root_tol", check_real("root_tol", self.root_tol, lo=0.0, lo_open=True,
                                          hi=1e-3))
        try:
            s0 = tuple(self.state0)
        except TypeError:
            raise ParameterError("state0", self.state0, "must be 4 numbers (z_m, z_m', z_b, z_b')") from None
        if len(s0) != 4:
            raise ParameterError("state0", self.state0, "must be 4 numbers (z_m, z_m', z_b, z_b')")
        names = ("z_m0", "v_m0", "z_b0", "v_b0")
        s0 = tuple(check_real(n, v, lo=-STATE_MAX, hi=STATE_MAX) for n, v in zip(names, s0, strict=False))
        if abs(s0[0] - s0[2]) > 1.0:
            raise ParameterError("state0", self.state0, "needs |z_m0 - z_b0| <= 1 (ball inside the cavity)")
        set_(self, "state0", s0)

    def as_dict(self) -> dict:
        d = asdict(self)
        d["state0"] = list(self.state0)
        return d
