"""Periodic orbits on the exact impact maps, one family at a time (docs/architecture.md):

* ``maps``: one flight and impact with its Jacobian (``impact``), the one Newton on composed
  maps (``newton``), the affine-form seeds (``affine``), the compiled eigenvalues (``lapack``);
* ``jets``: the flight as closed-form shooting conditions with exact derivatives by Taylor
  jets (``taylor``, recorded as a ``tape``, run compiled by ``kernels``; ``shooting`` for
  1:1, ``chain`` composing the flights of any wall sequence);
* ``family``: the family object (``family``: walls, periods, symmetric; the 1:1 orbit is
  the value LR/1 of it; its names in ``names``), its engine (``engine``: a registry behind
  one contract; ``Family.engine``, the one place that tells 1:1 apart, picks one), the one
  orbit type of every family (``orbit.PeriodicOrbit``), found by ``periodic`` for 1:1 and
  ``sequence`` for any wall sequence from the engines' ``seeds``, and its augmented systems
  (``augmented`` on jets, ``map_systems`` on the maps);
* ``continuation``: the arclength tracer, one settings object (``settings``), one loop of
  branches and their events for every family (``loop``) on each family's problem
  (``follower`` for 1:1, entry ``one_to_one``; ``sequence``); the one result type
  ``Branch`` in ``branch``;
* ``curves``: codimension-one curves in (eta, omega) on one tracer (``tracer``), seeded per
  family (``one_to_one``, ``sequence``), entry point ``boundaries``;
* ``atlas``: which families exist at a point (``atlas``), stability maps (``stability_map``).

The public entry points below load their modules (numba) on first access.
"""
from .._lazy import lazy_attributes

#: public names loaded on first access, and their modules
_LAZY = {
    "Family": ".family.family",
    "find_1to1": ".family.periodic",
    "PeriodicOrbit": ".family.orbit",
    "find_sequence": ".family.sequence",
    "SequenceOrbit": ".family.orbit",
    "continue_branch": ".continuation.one_to_one",
    "ContinuationSettings": ".continuation.settings",
    "Branch": ".continuation.branch",
    "continue_sequence": ".continuation.sequence",
    "ContinueSettings": ".continuation.sequence",
    "SequenceBranch": ".continuation.branch",
    "boundaries": ".curves.boundaries",
    "atlas_point": ".atlas.atlas",
    "stability_map": ".atlas.stability_map",
}

__all__ = sorted(_LAZY)

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY)
