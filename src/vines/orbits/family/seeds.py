"""Starting points (x_0, flight times) of the Newton iteration on a family's composed maps,
for the engines of ``engine`` (docs/bifurcation.md, "Families of periodic orbits"):

* the 1:1 orbit (``seeds_1to1``, ``simulation_seeds_1to1``): the seeds of ``periodic``
  (symmetric closed form, asymmetric flight-time scan, the simulation from rest), so that
  ``find_sequence(p, "LR", 1)`` finds the orbits of ``find_1to1``;
* any other sequence (``family_seeds``): half-period symmetry (n even, walls[k + n/2] =
  opposite of walls[k]): with the flight times fixed, the conditions for x_{n/2} =
  mirror(x_0) + (0, 0, 0, periods T / 2) are affine in (z_m', z_b', z_b, sin theta_0,
  cos theta_0) (``maps.affine``): closed form for n = 2, a scan of the first flight time for
  n = 4; the full two-flight scan for two impacts, the closed form for one;
  ``simulation_seeds``: the last occurrence of the sequence in the impact records of short
  exact simulations from a few initial states and in their mirror images (z -> -z,
  t -> t + T/2, a trajectory as well).
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ...core.params import ModelParams, ParameterError, SolverSettings
from ..maps.affine import closed_form_seeds, scan
from .names import WALL_NAMES, has_half_symmetry, wall_codes
from .periodic import asymmetric_seeds, simulation_seed, symmetric_seeds, theta_to_t

SIM_T_END = 600.0               # length of a seeding simulation
#: initial states (z_m, z_m', z_b, z_b') of the seeding simulations (rest first)
SIM_STATES = ((0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.9, 0.0), (0.0, 0.5, 0.0, -0.5),
              (0.5, 0.0, -0.4, 0.0))


# --------------------------------------------------------------------------- 1:1

def seeds_1to1(p: ModelParams, mdl: np.ndarray) -> list:
    """The built-in seeds of ``periodic.seed_orbits`` (same order), as (x_0, flights)."""
    T = p.period
    out = [([vm, vb, zb, theta_to_t(th, p)], [0.5 * T, 0.5 * T])
           for vm, vb, zb, th in symmetric_seeds(mdl)]
    out += [([vm, vb, zb, theta_to_t(th, p)], [s1, T - s1])
            for vm, vb, zb, th, s1 in asymmetric_seeds(mdl)]
    return out


def simulation_seeds_1to1(p: ModelParams, mdl: np.ndarray) -> list:
    """The orbit of ``periodic.simulation_seed`` (the simulation from rest), as (x_0,
    flights)."""
    return [(o.x_L, o.flight_times) for o in simulation_seed(p, mdl) if o is not None]


# --------------------------------------------------------------------------- any sequence

def family_seeds(p: ModelParams, mdl: np.ndarray, walls: str, periods: int) -> list:
    """Seeds (x_0, flight times) from the affine forms (module docstring): the symmetric
    ansatz when the sequence has the half symmetry and periods is odd (closed form for two
    impacts, a scan for four), the full two-flight scan for two impacts."""
    n = len(walls)
    NT = periods * p.period
    codes = wall_codes(walls)
    out = []
    if has_half_symmetry(walls) and periods % 2 == 1:
        h = n // 2
        S = 0.5 * NT
        if h == 1:
            for vm, vb, zb, th in closed_form_seeds(mdl, codes, S, -1):
                out.append(([vm, vb, zb, theta_to_t(th, p)], [S, S]))
        elif h == 2:
            out += _scan(p, mdl, (codes, S, -1), lambda s0: [s0, S - s0, s0, S - s0])
    if n == 2:
        out += _scan(p, mdl, (codes, NT, 1), lambda s0: [s0, NT - s0])
    elif n == 1:
        for vm, vb, zb, th in closed_form_seeds(mdl, codes, NT, 1):
            out.append(([vm, vb, zb, theta_to_t(th, p)], [NT]))
    return out


def _scan(p: ModelParams, mdl: np.ndarray, chain: tuple, flights) -> list:
    """Seeds (x_0, flights(s0)) of ``affine.scan`` of chain = (walls codes, S, sign)."""
    return [([vm, vb, zb, theta_to_t(th, p)], flights(s0))
            for vm, vb, zb, th, s0 in scan(mdl, *chain)]


def mirror_record(imp, T) -> dict:
    return {"wall": -imp["wall"], "v_m": -imp["v_m"], "v_b": -imp["v_b"],
            "z_b": -imp["z_b"], "t": imp["t"] + 0.5 * T}


def record_seed(imp: Mapping[str, np.ndarray], walls: str) -> tuple[list, list] | None:
    """(x_0, flight times) at the last occurrence of the sequence (and its first wall
    again) in an impact record (fields wall, v_m, v_b, z_b, t), or None."""
    n = len(walls)
    text = "".join(WALL_NAMES.get(int(w), "?") for w in imp["wall"])
    k = text.rfind(walls + walls[0])
    if k < 0:
        return None
    t = imp["t"]
    x0 = [imp["v_m"][k], imp["v_b"][k], imp["z_b"][k], t[k]]
    return x0, list(np.diff(t[k:k + n + 1]))


def simulation_seeds(p: ModelParams, walls: str, states: Sequence = SIM_STATES,
                     t_end: float = SIM_T_END) -> list:
    """Seeds from short exact simulations from ``states`` (and their mirror images)."""
    from ...core.simulation import simulate_exact
    out = []
    for state0 in states:
        try:
            st = SolverSettings(t_end=t_end, t_transient=0.5 * t_end, max_impacts=200_000,
                                state0=state0)
            res = simulate_exact(p, st)
        except (ParameterError, RuntimeError):     # pragma: no cover - a seed is optional
            continue
        for rec in (res.impacts, mirror_record(res.impacts, p.period)):
            sd = record_seed(rec, walls)
            if sd is not None:
                out.append(sd)
    return out
