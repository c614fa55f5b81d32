"""The engines of the families of periodic orbits: one contract, ``Engine``, and a registry,
``ENGINES`` (as scipy's ``solve_ivp`` methods). ``family.Family.engine`` picks one per
family, the one place that decides anything by "is this the 1:1 family"; the code that
differs per family asks the engine, never compares it:

* ``JETS`` (``JetsEngine``), the 1:1 orbit (LR/1): seeds of ``periodic`` (symmetric closed
  form, the two-flight scan carrying the first flight's end into the second, the
  simulation from rest through the 1:1 solver); curves on shooting systems with exact
  Taylor jets (``orbits.jets``), also seeded from the class changes of a stability map;
  outputs in the form they always had (no walls or periods in the curves' JSON and dataset);
* ``MAPS`` (``MapsEngine``), every other family: affine-form seeds of the sequence and
  simulations from several states; curves on the composed impact maps; outputs that name
  the family.

The curve tracer of each engine is ``curves.boundaries.TRACERS`` (it lives above the
family layer). Numba-free: an operation that needs compiled code imports it when called.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ...core.params import ModelParams

#: the registry's keys (``Engine.name``)
JETS, MAPS = "jets", "maps"


class Engine:
    """What differs between the families' engines (one instance per engine, ``ENGINES``)."""

    name = ""
    #: boundary curves may also be seeded from a stability map's class changes (``class_map``)
    class_map_seeds = False
    #: its boundary curves are drawn on the orbit atlas (the 1:1 curves have Fig 16)
    on_atlas = False

    def affine_seeds(self, p: ModelParams, mdl: np.ndarray, walls: str,
                     periods: int) -> list:
        """Seeds (x_0, flight times) from the affine forms (``family.seeds``)."""
        raise NotImplementedError

    def simulation_seeds(self, p: ModelParams, mdl: np.ndarray, walls: str,
                         states: Sequence) -> list:
        """Seeds (x_0, flight times) from short exact simulations from ``states``."""
        raise NotImplementedError

    def output_keys(self, family) -> dict:
        """The keys that name the family in the boundaries' JSON and dataset attributes."""
        return {"walls": family.walls, "periods": family.periods}


class JetsEngine(Engine):
    """The 1:1 orbit (module docstring)."""

    name = JETS
    class_map_seeds = True

    def affine_seeds(self, p, mdl, walls, periods) -> list:
        from .seeds import seeds_1to1
        return seeds_1to1(p, mdl)

    def simulation_seeds(self, p, mdl, walls, states) -> list:
        """From rest only, through the 1:1 solver (as ``find_1to1``); ``states`` unused."""
        from .seeds import simulation_seeds_1to1
        return simulation_seeds_1to1(p, mdl)

    def output_keys(self, family) -> dict:
        return {}


class MapsEngine(Engine):
    """Every family other than 1:1 (module docstring)."""

    name = MAPS
    on_atlas = True

    def affine_seeds(self, p, mdl, walls, periods) -> list:
        from .seeds import family_seeds
        return family_seeds(p, mdl, walls, periods)

    def simulation_seeds(self, p, mdl, walls, states) -> list:
        from .seeds import simulation_seeds
        return simulation_seeds(p, walls, states)


#: every engine by name
ENGINES = {e.name: e for e in (JetsEngine(), MapsEngine())}
