"""Curves of codimension-one points of a family's orbits in the (eta, omega) plane at fixed
F: ``boundaries(F, eta_range, omega_range, walls=..., periods=...)``, the entry point.

Each engine of the family (``Family.engine``) has its curve seeding here, ``TRACERS``: the
1:1 orbits (``JETS``) by ``curves.one_to_one`` (shooting systems with exact jets, seeds from
scan lines and the class changes of a stability map), every other wall sequence (``MAPS``)
by ``curves.sequence`` (systems on the composed maps, seeds from continuations through the
crossings of the scan lines); both on the one tracer of ``curves.tracer``. These curves are
the edges of the classes of ``stability_map`` (Fig 16).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ...core.params import (
    D_DEFAULT,
    R_DEFAULT,
    ModelParams,
    ParameterError,
    as_float_array,
    check_int,
    check_param,
    check_real,
    check_reals,
)
from ..family.engine import JETS, MAPS
from ..family.family import Family
from .one_to_one import one_to_one_curves
from .sequence import sequence_boundaries
from .tracer import CurveSettings


@dataclass
class Boundaries:
    """The curves of one F and family (``boundaries``)."""

    F: float
    eta_range: tuple
    omega_range: tuple
    curves: list
    walls: str = "LR"
    periods: int = 1

    def to_dict(self) -> dict:
        out = {"F": self.F, "eta_range": list(self.eta_range),
               "omega_range": list(self.omega_range),
               "curves": [c.to_dict() for c in self.curves]}
        family = Family(self.walls, self.periods)
        out.update(family.engine.output_keys(family))
        return out


def boundaries(F: float, eta_range: Sequence[float], omega_range: Sequence[float],
               r: float = R_DEFAULT, d: float = D_DEFAULT, n_scan: int = 5,
               step: float = 0.01, max_points: int = 400, n_map: int = 25,
               class_map: tuple | None = None, walls: str = "LR",
               periods: int = 1) -> Boundaries:
    """Codimension-one curves of the orbits of ``walls``/``periods`` (default the 1:1
    family) in the box eta_range x omega_range at F.

    ``n_scan`` scan lines per parameter seed the curves. For the 1:1 family, class changes
    of an ``n_map`` x ``n_map`` stability map farther than 1.5 cells from every kept curve
    then seed more (module docstring, step 4; ``n_map = 0`` skips it); ``class_map`` =
    (eta, omega, cls): a stability map already computed at this F (``stability_map``),
    whose class changes are used instead of the n_map x n_map one. Other families
    (``curves.sequence``) are seeded by continuations through the n_scan x n_scan
    crossings of the scan lines and ignore n_map; ``class_map`` is for 1:1 only."""
    F = check_param("F", F)
    box = (check_range("eta_range", eta_range), check_range("omega_range", omega_range))
    n_scan = check_int("n_scan", n_scan, lo=1, hi=100)
    settings = CurveSettings(check_real("step", step, lo=1e-5, hi=1.0),
                             check_int("max_points", max_points, lo=1, hi=100_000))
    n_map = check_int("n_map", n_map, lo=0, hi=1000)
    class_map = check_class_map(class_map)
    family = Family.checked(walls, periods)
    p = ModelParams(eta=1.0, omega=1.0, F=F, r=r, d=d)     # validates r and d
    if class_map is not None and not family.engine.class_map_seeds:
        raise ParameterError("class_map", "(eta, omega, cls)", "must be None for a "
                             "family other than 1:1 (walls LR, periods 1)")
    curves = TRACERS[family.engine.name](p, family, box, (n_scan, n_map, class_map, settings))
    return Boundaries(F, box[0], box[1], curves, *family.key)


def _jets_curves(p: ModelParams, family: Family, box: tuple, seeding: tuple) -> list:
    n_scan, n_map, class_map, settings = seeding
    return one_to_one_curves(p, box, settings, (n_scan, n_map, class_map))


def _maps_curves(p: ModelParams, family: Family, box: tuple, seeding: tuple) -> list:
    n_scan, _, _, settings = seeding
    return sequence_boundaries(p, family.key, box, (n_scan, settings))


#: the curve seeding of each engine (``family.engine``): (model, family, box, (n_scan, n_map,
#: class_map, curve settings)) -> curves
TRACERS = {JETS: _jets_curves, MAPS: _maps_curves}


def check_class_map(class_map):
    """None or (eta, omega, cls): increasing axes of >= 2 values and integer classes of
    shape (len(eta), len(omega)), as ``stability_map`` returns them."""
    allowed = ("must be None or (eta, omega, cls) of a stability map: increasing axes of >= 2 "
               "values, classes of shape (len(eta), len(omega))")
    if class_map is None:
        return None
    if not isinstance(class_map, (list, tuple)) or len(class_map) != 3:
        raise ParameterError("class_map", class_map, allowed)
    try:
        eta = check_reals("class_map", class_map[0], min_size=2)
        omega = check_reals("class_map", class_map[1], min_size=2)
        cls = as_float_array("class_map", class_map[2])
    except ParameterError:
        raise ParameterError("class_map", class_map, allowed) from None
    if (np.any(np.diff(eta) <= 0) or np.any(np.diff(omega) <= 0)
            or cls.shape != (eta.size, omega.size) or not np.all(np.isfinite(cls))
            or np.any(cls != np.round(cls))):
        raise ParameterError("class_map", class_map, allowed)
    return class_map


def check_range(name, value) -> tuple:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be two numbers lo < hi") from None
    q = name.split("_")[0]
    try:
        lo, hi = check_param(q, lo), check_param(q, hi)
    except ParameterError as err:
        raise ParameterError(name, list(value), f"{err.allowed} (both ends)") from None
    if not lo < hi:
        raise ParameterError(name, value, "must be two numbers lo < hi")
    return lo, hi
