"""Coexisting attractors: which motions a VINES can end up in, and how likely each is.

``census`` samples initial states at one parameter point, runs each until it settles and
groups the end states into attractors with basin fractions (``census``, ``endstate``,
``orbit``, ``sampling``). Numerics only: datasets are built in ``vines.data``.
"""
from .census import Attractor, Census, census
from .sampling import BOX_NAMES, DEFAULT_BOX, sample_states

__all__ = ["Attractor", "Census", "census", "BOX_NAMES", "DEFAULT_BOX", "sample_states"]
