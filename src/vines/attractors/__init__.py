"""Coexisting attractors: which motions a VINES can end up in, and how likely each is.

``census`` samples initial states at one parameter point, runs each until it settles and
groups the end states into attractors with basin fractions (``census``, ``endstate``,
``orbit``, ``sampling``); with ``t_max`` also the asymptotic view: lifetimes of transient
motions and which motions persist (``asymptotic``). ``lyapunov``: Lyapunov spectra by
saltation matrices (``lyapunov``, on ``core.variational``). Numerics only: datasets are
built in ``vines.data``.
"""
from .asymptotic import T_MAX_DEFAULT
from .census import Attractor, Census, census
from .lyapunov import LyapunovResult, lyapunov
from .sampling import BOX_NAMES, DEFAULT_BOX, sample_states

__all__ = ["Attractor", "Census", "census", "BOX_NAMES", "DEFAULT_BOX", "sample_states",
           "LyapunovResult", "lyapunov", "T_MAX_DEFAULT"]
