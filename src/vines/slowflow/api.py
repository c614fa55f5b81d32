"""The public slow flow: validated inputs, ``response`` at one point and ``frc`` over many
frequencies, with the regime and the warnings outside the expansion's assumptions."""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..core.params import (
    D_DEFAULT,
    PARAM_BOUNDS,
    R_DEFAULT,
    ParameterError,
    check_param,
    check_real,
    check_reals,
)
from . import manifold as sim
from .cycle import FromRest, SMRCycle, from_rest, smr_cycle
from .response import Model, Roots, fixed_points, linear_amplitude

#: above these the slow flow answers with a warning; above the maxima it refuses
ETA_WARN, ETA_MAX = 0.1, 0.5
D_WARN, D_MAX = 0.1, 0.5
F_WARN = 0.2
DETUNING_WARN = 0.2          # |Omega - 1|
#: at most this many frequencies in one FRC
N_OMEGA_MAX = 10_000_000

REGIMES = ("two-impact", "SMR", "no impact")


def model(eta, F, r, d) -> Model:
    """The validated scalars; ParameterError where the slow flow does not apply."""
    eta = _checked("eta", eta, "> 0 and <= 0.5 (a light ball)", lo_open=True, hi=ETA_MAX)
    d = _checked("d", d, ">= 0 and <= 0.5 (light damping)", hi=D_MAX)
    r = _checked("r", r, ">= 0 and < 1 (impacts that dissipate)", hi=1.0, hi_open=True)
    return Model(eta=eta, F=check_param("F", F), r=r, d=d)


def _checked(name: str, value, allowed: str, **bounds) -> float:
    """check_real with the slow flow's own bounds, the message saying why."""
    try:
        return check_real(name, value, lo=0.0, **bounds)
    except ParameterError:
        raise ParameterError(name, value, f"must be a finite number {allowed} for the slow "
                                          f"flow (otherwise use the exact solver)") from None


def warnings_for(m: Model, omegas: np.ndarray) -> list[str]:
    """One line per assumption of the slow flow that the inputs leave (docs/slowflow.md)."""
    out = []
    if m.eta > ETA_WARN:
        out.append(f"eta = {m.eta:g} is not small (> {ETA_WARN:g}): the slow flow's error "
                   f"is O(eta)")
    if m.d > D_WARN:
        out.append(f"d = {m.d:g} is not small (> {D_WARN:g}): the slow flow's error is O(d)")
    if m.F > F_WARN:
        out.append(f"F = {m.F:g} is not small (> {F_WARN:g}): the LO's motion is not "
                   f"near-harmonic")
    far = np.abs(omegas - 1.0) > DETUNING_WARN
    if far.any():
        w = omegas[far][np.argmax(np.abs(omegas[far] - 1.0))]
        out.append(f"omega = {w:g} is far from resonance (|omega - 1| > {DETUNING_WARN:g}): "
                   f"the detuning is not small")
    return out


@dataclass(frozen=True)
class SlowFlowOrbit:
    """One fixed point of the slow flow: a symmetric two-impact (1:1) orbit.

    amplitude: max |z_m| over a period (units of L); ball_amplitude: max |z_b|; phase:
    forcing phase mod(Omega t + phi, 2 pi) at the impact on wall L (as ``PeriodicOrbit``'s
    phase_L); stable: stable in the slow flow and on the SIM's stable branch; branch: the SIM
    branch ("stable", "unstable" between the fold and X = 1, "symmetry-breaking" beyond the
    symmetry-breaking point, where a 1:1 orbit with unequal flights takes over).
    """

    amplitude: float
    ball_amplitude: float
    phase: float
    stable: bool
    branch: str

    def to_dict(self) -> dict:
        return asdict(self)


def regimes(R: Roots, x_linear: np.ndarray) -> np.ndarray:
    """Per frequency: 'two-impact' where a fixed point attracts (slow-stable on the SIM's
    stable branch, or beyond its symmetry-breaking point); else 'no impact' where the LO without impacts stays
    inside the clearance (amplitude < 1); else 'SMR' (relaxation around the fold)."""
    attracts = np.zeros(x_linear.size, dtype=bool)
    attracts[R.index[R.attracting]] = True
    return np.where(attracts, "two-impact", np.where(x_linear < 1.0, "no impact", "SMR"))


def symmetry_breaking_warning(R: Roots) -> list[str]:
    """The warning where a regime rests on a fixed point beyond the symmetry-breaking
    point."""
    beyond = R.attracting & ~R.stable
    if not beyond.any():
        return []
    return [f"the two-impact fixed point at omega = {R.omega[beyond][0]:g} lies beyond the "
            f"symmetry-breaking point of the SIM (LO amplitude {R.X[beyond][0]:.4g} > "
            f"x_symmetry_breaking): the symmetric 1:1 orbit is unstable there (a "
            f"pitchfork: multiplier +1 of the full period), a 1:1 orbit with unequal "
            f"flights takes over at about this LO amplitude"]


def flip_warning(R: Roots) -> list[str]:
    """Deprecated name of ``symmetry_breaking_warning``."""
    _deprecated("flip_warning", "symmetry_breaking_warning")
    return symmetry_breaking_warning(R)


def _deprecated(old: str, new: str) -> None:
    import warnings
    warnings.warn(f"{old} is deprecated: use {new} (a symmetry-breaking pitchfork, not a "
                  "flip)", DeprecationWarning, stacklevel=3)


@dataclass(frozen=True)
class SlowFlowResponse:
    """The slow flow's answer at one (eta, omega, F, r, d); lengths in units of L.

    rho, xi_min (the SIM's fold: activation threshold), x_symmetry_breaking (the upper end of
    its stable branch; ``x_flip`` its deprecated name), orbits (every fixed point, stable first), regime, smr (None or the relaxation
    cycle's LO amplitude range (low, 1): low the cycle's smallest amplitude, xi_min or
    below), linear_amplitude (the LO without impacts), warnings (the assumptions the inputs
    leave), smr_cycle (None or the cycle: period, time impacting and free; ``cycle``),
    from_rest (how the regime was decided: ``cycle.FromRest``), fixed_point_regime (the
    regime the fixed points alone suggest, as ``regimes`` and the FRC report it: an
    attracting fixed point taken to be reached).
    """

    eta: float
    omega: float
    F: float
    r: float
    d: float
    rho: float
    xi_min: float
    x_symmetry_breaking: float
    orbits: list
    regime: str
    smr: tuple | None
    linear_amplitude: float
    warnings: list
    smr_cycle: SMRCycle | None = None
    from_rest: FromRest | None = None
    fixed_point_regime: str | None = None

    @property
    def x_flip(self) -> float:
        """Deprecated name of ``x_symmetry_breaking``."""
        _deprecated("x_flip", "x_symmetry_breaking")
        return self.x_symmetry_breaking

    def to_dict(self) -> dict:
        smr = None if self.smr is None else {"amplitude_low": self.smr[0],
                                             "amplitude_high": self.smr[1]}
        if self.smr_cycle is not None:
            c = self.smr_cycle
            smr |= {"period": c.period, "time_impacting": c.time_impacting,
                    "time_free": c.time_free}
        return {"model": "slowflow",
                "params": {"eta": self.eta, "omega": self.omega, "F": self.F, "r": self.r,
                           "d": self.d},
                "rho": self.rho, "xi_min": self.xi_min,
                "x_symmetry_breaking": self.x_symmetry_breaking,
                "x_flip": self.x_symmetry_breaking,    # deprecated key, for one release
                "orbits": [o.to_dict() for o in self.orbits], "regime": self.regime,
                "smr": smr,
                "from_rest": (None if self.from_rest is None else self.from_rest.to_dict()
                              | {"fixed_point_regime": self.fixed_point_regime}),
                "linear_amplitude": self.linear_amplitude, "warnings": list(self.warnings)}


def _orbits(R: Roots) -> list[SlowFlowOrbit]:
    out = [SlowFlowOrbit(amplitude=float(R.X[j]), ball_amplitude=float(R.ball_amplitude[j]),
                         phase=float(R.phase[j]), stable=bool(R.stable[j]),
                         branch=sim.BRANCH_NAMES[int(R.branch[j])])
           for j in range(R.X.size)]
    return sorted(out, key=lambda o: (not o.stable, o.amplitude))


def smr_range(m: Model, cycle: SMRCycle | None) -> tuple:
    """The relaxation cycle's LO amplitude range: from the fold xi_min (impacts stop; lower
    where the LO keeps losing amplitude after that) to X = 1 (a ball at rest in the centre is
    reached again: the jump back onto the SIM); (xi_min, 1) where the cycle was not found."""
    if cycle is None:
        return (sim.xi_min(m.rho), 1.0)
    return (cycle.amplitude_low, cycle.amplitude_high)


def response(eta, omega, F, *, r=R_DEFAULT, d=D_DEFAULT) -> SlowFlowResponse:
    """The slow flow at one point: its fixed points, their stability and the regime from
    rest, decided by following the slow flow from rest through the jump at X = 1 to its
    attractor (``cycle.from_rest``; the exact solver where the slow flow cannot decide).

    ParameterError for eta > 0.5, d > 0.5 or r = 1 (no impact dissipation: no SIM);
    ``warnings`` lists the assumptions the inputs leave (eta, d, F or |omega - 1| not small).
    """
    m = model(eta, F, r, d)
    W = np.array([check_param("omega", omega)])
    R = fixed_points(m, W)
    xl = linear_amplitude(m, W)
    rest = from_rest(m, float(W[0]), R.X[R.attracting].tolist(), float(xl[0]))
    regime = rest.regime
    cycle = smr_cycle(m, float(W[0])) if regime == "SMR" else None
    return SlowFlowResponse(eta=m.eta, omega=float(W[0]), F=m.F, r=m.r, d=m.d, rho=m.rho,
                            xi_min=sim.xi_min(m.rho),
                            x_symmetry_breaking=sim.x_symmetry_breaking(m.rho),
                            orbits=_orbits(R), regime=regime,
                            smr=smr_range(m, cycle) if regime == "SMR" else None,
                            linear_amplitude=float(xl[0]),
                            warnings=warnings_for(m, W) + symmetry_breaking_warning(R),
                            smr_cycle=cycle, from_rest=rest,
                            fixed_point_regime=str(regimes(R, xl)[0]))


@dataclass(frozen=True)
class FRC:
    """The slow flow's frequency-response curves: one row per fixed point (all branches).

    Rows: omega, amplitude (max |z_m|, units of L), ball_amplitude, phase (forcing phase at
    the L impact, rad), stable, branch (SIM branch code: 1 stable, 2 unstable, 3
    symmetry-breaking;
    ``manifold.BRANCH_*``), slow_stable (stable in the slow flow, whatever the branch).
    Per frequency of ``omega_grid``: linear_amplitude, regime.
    """

    omega: np.ndarray
    amplitude: np.ndarray
    ball_amplitude: np.ndarray
    phase: np.ndarray
    stable: np.ndarray
    branch: np.ndarray
    slow_stable: np.ndarray
    omega_grid: np.ndarray
    linear_amplitude: np.ndarray
    regime: np.ndarray
    rho: float
    xi_min: float
    x_symmetry_breaking: float
    warnings: list

    @property
    def x_flip(self) -> float:
        """Deprecated name of ``x_symmetry_breaking``."""
        _deprecated("x_flip", "x_symmetry_breaking")
        return self.x_symmetry_breaking

    def to_dict(self) -> dict:
        rows = [{"omega": w, "amplitude": a, "ball_amplitude": b, "phase": p,
                 "stable": bool(s), "branch": sim.BRANCH_NAMES[int(c)]}
                for w, a, b, p, s, c in zip(self.omega, self.amplitude, self.ball_amplitude,
                                            self.phase, self.stable, self.branch,
                                            strict=True)]
        regimes = [{"omega": w, "regime": str(g), "linear_amplitude": x}
                   for w, g, x in zip(self.omega_grid, self.regime, self.linear_amplitude,
                                      strict=True)]
        return {"model": "slowflow", "rho": self.rho, "xi_min": self.xi_min,
                "x_symmetry_breaking": self.x_symmetry_breaking,
                "x_flip": self.x_symmetry_breaking,    # deprecated key, for one release
                "frc": rows, "regimes": regimes,
                "warnings": list(self.warnings)}


def frc_of(m: Model, W: np.ndarray) -> FRC:
    """The FRC of a validated model over the frequencies W (no checks)."""
    R = fixed_points(m, W)
    xl = linear_amplitude(m, W)
    return FRC(omega=R.omega, amplitude=R.X, ball_amplitude=R.ball_amplitude,
               phase=R.phase, stable=R.stable, branch=R.branch,
               slow_stable=R.slow_stable, omega_grid=W, linear_amplitude=xl,
               regime=regimes(R, xl), rho=m.rho, xi_min=sim.xi_min(m.rho),
               x_symmetry_breaking=sim.x_symmetry_breaking(m.rho), warnings=warnings_for(m, W) + symmetry_breaking_warning(R))


def frc(eta, omegas, F, *, r=R_DEFAULT, d=D_DEFAULT) -> FRC:
    """The slow flow's FRC at the frequencies ``omegas`` (any order; all branches)."""
    m = model(eta, F, r, d)
    lo, lo_open, hi = PARAM_BOUNDS["omega"]
    W = check_reals("omegas", omegas, lo=lo, lo_open=lo_open, hi=hi, max_size=N_OMEGA_MAX)
    return frc_of(m, W)

