"""The model file (YAML): a host, its absorbers and the forcing, read and validated once.

    host:                       # by matrices ...
      mass: [[1, 0], [0, 1]]
      stiffness: [[2, -1], [-1, 2]]
      damping: [[0.02, -0.01], [-0.01, 0.02]]
      influence: [1, 1]         # optional, default ones
    # ... or by modes: host: {modes: {frequencies: [...], damping_ratios: [...],
    #                                 shapes: [[...], ...], modal_masses: [...]}}
    absorbers:
      - {dof: 0, mass: 0.05, gap: 1.0, restitution: 0.65}                 # VI NES
      - {dof: 1, mass: 0.05, stiffness: 0.04, damping: 0.002}             # TMD (gap .inf)
    forcing: {kind: harmonic, amplitude: 0.05, frequency: 1.0, phase: 0}

Every error is a ``ParameterError`` naming the key (``absorbers[1].gap``), the value and
what is allowed (one line).
"""
from __future__ import annotations

import math
from pathlib import Path

from ..core.params import ParameterError
from .model import FORCINGS, Absorber, Host, HostModel

HOST_KEYS = {"mass", "stiffness", "damping", "influence", "modes"}
MODE_KEYS = {"frequencies", "damping_ratios", "shapes", "modal_masses"}
ABSORBER_KEYS = {"dof", "mass", "stiffness", "damping", "gap", "restitution"}
TOP_KEYS = {"host", "absorbers", "forcing"}


def _mapping(name: str, value, allowed: set, required: set = frozenset()) -> dict:
    if not isinstance(value, dict):
        raise ParameterError(name, value, f"must be a mapping with keys {sorted(allowed)}")
    extra = sorted(set(value) - allowed)
    if extra:
        raise ParameterError(f"{name}.{extra[0]}", value[extra[0]],
                             f"unknown key (allowed: {', '.join(sorted(allowed))})")
    missing = sorted(required - set(value))
    if missing:
        raise ParameterError(f"{name}.{missing[0]}", None, "is required")
    return value


def _renamed(err: ParameterError, name: str) -> ParameterError:
    return ParameterError(name, err.value, err.allowed)


def host_from(d) -> Host:
    d = _mapping("host", d, HOST_KEYS)
    if "modes" in d:
        if set(d) - {"modes", "influence"}:
            raise ParameterError("host", sorted(d), "give either modes or mass, stiffness, "
                                 "damping matrices, not both")
        m = _mapping("host.modes", d["modes"], MODE_KEYS, {"frequencies", "damping_ratios", "shapes"})
        return Host.from_modes(m["frequencies"], m["damping_ratios"], m["shapes"],
                               m.get("modal_masses"), d.get("influence"))
    _mapping("host", d, HOST_KEYS, {"mass", "stiffness", "damping"})
    infl = d.get("influence")
    if infl is None:
        try:
            n = len(d["mass"])
        except TypeError:
            n = 1
        infl = [1.0] * n
    return Host(d["mass"], d["stiffness"], d["damping"], infl)


def absorber_from(i: int, d) -> Absorber:
    name = f"absorbers[{i}]"
    d = _mapping(name, d, ABSORBER_KEYS, {"dof", "mass"})
    gap = d.get("gap", math.inf)
    try:
        return Absorber(d["dof"], d["mass"], d.get("stiffness", 0.0), d.get("damping", 0.0),
                        gap, d.get("restitution", 0.65))
    except ParameterError as err:
        raise _renamed(err, err.name.replace("absorber", name, 1)) from None


def forcing_from(d):
    d = _mapping("forcing", d, {"kind", "amplitude", "frequency", "phase"},
                 {"amplitude", "frequency"})
    kind = d.get("kind", "harmonic")
    if kind not in FORCINGS:
        raise ParameterError("forcing.kind", kind, f"must be one of {', '.join(FORCINGS)}")
    return FORCINGS[kind](d["amplitude"], d["frequency"], d.get("phase", 0.0))


def model_from_dict(d) -> HostModel:
    """A validated HostModel from the mapping of a model file."""
    d = _mapping("model", d, TOP_KEYS, {"host", "forcing"})
    host = host_from(d["host"])
    ab = d.get("absorbers") or []
    if not isinstance(ab, list):
        raise ParameterError("absorbers", ab, "must be a list of absorbers")
    absorbers = tuple(absorber_from(i, a) for i, a in enumerate(ab))
    model = HostModel(host, absorbers, forcing_from(d["forcing"]))
    from .system import check_system  # the engine's own conditions (defective, resonant)
    check_system(model)
    return model


def read_model(path) -> HostModel:
    """Read and validate a model file (YAML)."""
    import yaml

    p = Path(path)
    try:
        text = p.read_text()
    except OSError as err:
        raise ParameterError("model", str(path), f"must be a readable file ({err.strerror})") from None
    try:
        d = yaml.safe_load(text)
    except yaml.YAMLError as err:
        where = getattr(err, "problem_mark", None)
        line = f" (line {where.line + 1})" if where is not None else ""
        raise ParameterError("model", str(path), f"must be valid YAML{line}") from None
    return model_from_dict(d)
