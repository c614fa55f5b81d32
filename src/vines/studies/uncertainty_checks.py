"""Uncertain parts of a design (``studies.uncertainty``): the parameters, their
distributions and the checks of their specifications; each check raises ParameterError
naming the argument, the value and what is allowed. Numbers only; no numpy, no simulation
(the CLI's --help and the config checks read this module)."""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from ..core.params import ETA_MAX, F_MAX, ParameterError, check_int

#: uncertain parameters -> what their numbers are (relative deviation or the value)
PARAMETERS = {"frequency": "relative", "clearance": "relative", "mass": "relative",
              "r": "value"}
DISTRIBUTIONS = ("uniform", "normal")
#: a normal distribution is truncated at +- this many standard deviations
NORMAL_TRUNCATION = 3.0
N_SAMPLES_DEFAULT = 128
N_SAMPLES_MAX = 2 ** 16


@dataclass(frozen=True)
class Uncertain:
    """One uncertain parameter: ``name`` (a key of PARAMETERS), ``distribution``
    ('uniform': a = LO, b = HI; 'normal': a = MEAN, b = SD, truncated at
    +-NORMAL_TRUNCATION SD)."""

    name: str
    distribution: str
    a: float
    b: float

    @property
    def support(self) -> tuple[float, float]:
        if self.distribution == "uniform":
            return self.a, self.b
        return self.a - NORMAL_TRUNCATION * self.b, self.a + NORMAL_TRUNCATION * self.b

    def ppf(self, u):
        """Values at the unit-interval points u (inverse of the distribution function)."""
        if self.distribution == "uniform":
            return self.a + (self.b - self.a) * u
        from scipy.stats import truncnorm
        t = NORMAL_TRUNCATION
        return self.a + self.b * truncnorm.ppf(u, -t, t)

    def to_dict(self) -> dict:
        keys = ("lo", "hi") if self.distribution == "uniform" else ("mean", "sd")
        return {"name": self.name, "kind": PARAMETERS[self.name],
                "distribution": self.distribution, keys[0]: self.a, keys[1]: self.b,
                "support": list(self.support)}


def _spec_parts(name: str, spec) -> tuple:
    """(distribution, a, b) from 'DIST:A:B' or a sequence (DIST, A, B)."""
    parts = spec.split(":") if isinstance(spec, str) else spec
    try:
        dist, a, b = parts
    except (TypeError, ValueError):
        raise ParameterError("uncertainty", f"{name}={spec}", "must be NAME=uniform:LO:HI "
                             "or NAME=normal:MEAN:SD") from None
    if dist not in DISTRIBUTIONS:
        raise ParameterError("uncertainty", f"{name}={spec}",
                             f"distribution must be one of {', '.join(DISTRIBUTIONS)}")
    return dist, a, b


def check_uncertain(name, spec, *, amplitudes_m: Sequence[float] = (),
                    clearance_m: float | None = None, eta: float | None = None) -> Uncertain:
    """One parameter, validated: its name, distribution, numbers (LO <= HI, SD >= 0) and
    support (the frequency deviation within [-0.5, 1]; the clearance and mass deviations
    > -1, the clearance's keeping F = A/L <= F_MAX for the amplitudes, the mass's eta <=
    ETA_MAX; r within [0, 1])."""
    if not isinstance(name, str) or name not in PARAMETERS:
        raise ParameterError("uncertainty", f"{name}={spec}",
                             f"parameter must be one of {', '.join(PARAMETERS)}")
    dist, a, b = _spec_parts(name, spec)
    what = f"{name}={':'.join(map(str, (dist, a, b)))}"
    try:
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        a = b = math.nan
    if not (math.isfinite(a) and math.isfinite(b)):
        raise ParameterError("uncertainty", what, "the numbers must be finite")
    if dist == "uniform" and b < a:
        raise ParameterError("uncertainty", what, "the range is empty: give LO <= HI")
    if dist == "normal" and b < 0:
        raise ParameterError("uncertainty", what, "the standard deviation must be >= 0")
    u = Uncertain(name, dist, a, b)
    lo, hi = u.support
    for ok, allowed in _support_checks(name, lo, hi, amplitudes_m, clearance_m, eta):
        if not ok:
            raise ParameterError("uncertainty", what, f"support [{lo:g}, {hi:g}]: {allowed}")
    return u


def _support_checks(name, lo, hi, amplitudes_m, clearance_m, eta):
    if name == "r":
        yield lo >= 0.0 and hi <= 1.0, "must lie within [0, 1]"
    elif name == "frequency":
        yield lo >= -0.5 and hi <= 1.0, "the deviation must lie within [-0.5, 1]"
    elif name == "clearance":
        yield lo > -1.0, "the deviation must stay > -1"
        if clearance_m is not None and amplitudes_m:
            L_min = max(amplitudes_m) / F_MAX
            yield clearance_m * (1.0 + lo) >= L_min, (
                f"the clearance must stay >= A_max/{F_MAX:g} = {L_min:g} m")
    else:
        yield lo > -1.0, "the deviation must stay > -1"
        if eta is not None:
            yield eta * (1.0 + hi) <= ETA_MAX, f"eta (1 + e) must stay <= {ETA_MAX:g}"


def check_parameters(parameters, **context) -> tuple[Uncertain, ...]:
    """A mapping name -> spec (or 'NAME=SPEC' strings): at least one, each once."""
    if isinstance(parameters, Mapping):
        items = list(parameters.items())
    else:
        if isinstance(parameters, str):
            parameters = [parameters]
        items = []
        for s in parameters or []:
            name, eq, spec = str(s).partition("=")
            if not eq:
                raise ParameterError("uncertainty", s, "must be NAME=uniform:LO:HI or "
                                                       "NAME=normal:MEAN:SD")
            items.append((name, spec))
    if not items:
        raise ParameterError("uncertainty", parameters, "give at least one parameter "
                             f"({', '.join(PARAMETERS)})")
    names = [n for n, _ in items]
    dup = next((n for n in names if names.count(n) > 1), None)
    if dup is not None:
        raise ParameterError("uncertainty", dup, "is given twice")
    return tuple(check_uncertain(n, s, **context) for n, s in items)


def check_samples(n) -> int:
    """Sobol base sample size: a power of 2 in [2, N_SAMPLES_MAX]."""
    n = check_int("samples", n, lo=2, hi=N_SAMPLES_MAX)
    if n & (n - 1):
        raise ParameterError("samples", n, "must be a power of 2 (Sobol points)")
    return n
