"""``vines attractors``: the attractors that coexist at one point and their basins."""
from __future__ import annotations

import argparse

from ..attractors.asymptotic import T_MAX_DEFAULT
from ..attractors.sampling import N_MAX, SEED_MAX
from ..core.params import T_END_DEFAULT, T_END_MAX, T_TRANSIENT_DEFAULT, ModelParams, check_int
from .common import (
    VinesArgumentParser,
    add_model_args,
    add_value,
    emit,
    model_params,
    quiet_stdout,
)

NAME = "attractors"


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="attractor census at one point: coexisting attractors and their basin fractions",
        description="Run N scrambled-Sobol initial states (z_m, z_m' in [-1.5, 1.5], "
                    "w = z_m - z_b in [-1, 1], z_b' in [-1.5, 1.5], forcing phase 0) until "
                    "they settle on a periodic orbit or reach t-end, group the end states "
                    "into attractors and report each one's basin fraction with a 95 % "
                    "Wilson interval, and which one the start from rest reaches.",
    )
    add_model_args(p)
    add_value(p, "--n", f"an integer >= 1 and <= {N_MAX}", "number of initial states "
              "(default 256)", default=256)
    add_value(p, "--seed", f"an integer >= 0 and <= {SEED_MAX}", "scramble seed of the Sobol points "
              "(default 0)", default=0)
    add_value(p, "--t-end", f"a number > 0 and <= {T_END_MAX:g}",
              f"longest run (default {T_END_DEFAULT:g})", default=T_END_DEFAULT)
    add_value(p, "--t-transient", "a number >= 0 and < t-end", "start of the window of "
              f"the non-periodic measures (default {T_TRANSIENT_DEFAULT:g})",
              default=T_TRANSIENT_DEFAULT)
    add_value(p, "--t-max", f"a number > t-end and <= {T_END_MAX:g}", "also the asymptotic "
              "view: states not settled at t-end run on until they settle on a periodic orbit "
              f"or reach T_MAX (default without a value: {T_MAX_DEFAULT:g})", nargs="?",
              const=T_MAX_DEFAULT, default=None)
    add_value(p, "--threads", "an integer >= 1", "threads (default: all cores)",
              default=None)
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout "
                   "(keys: attractors, from_rest, unsettled_fraction; with --t-max also "
                   "t_max, from_rest_asymptotic and per attractor basin_fraction_asymptotic, "
                   "ci_asymptotic, status, regime_asymptotic, lyapunov_max, lifetime, "
                   "escape_to; modulation where a lasting motion was tested for "
                   "quasi-periodicity)")
    return p


def run(args: argparse.Namespace) -> int:
    params = model_params(args)
    n = check_int("n", args.n, lo=1, hi=N_MAX)
    seed = check_int("seed", args.seed, lo=0, hi=SEED_MAX)
    threads = None if args.threads is None else check_int("threads", args.threads, lo=1)
    from ..attractors import census
    with quiet_stdout():
        res = census(params.eta, params.omega, params.F, r=params.r, d=params.d, n=n,
                     seed=seed, t_end=args.t_end, t_transient=args.t_transient,
                     n_threads=threads, t_max=args.t_max)
    return emit(args.json, res.to_dict(), lambda d: _text(d, params))


def _text(d: dict, params: ModelParams) -> str:
    lines = [f"eta = {params.eta:g}, omega = {params.omega:g}, F = {params.F:g}: "
             f"{len(d['attractors'])} attractor(s) from {d['n']} initial states, "
             f"unsettled {d['unsettled_fraction']:.3g}"]
    for i, a in enumerate(d["attractors"]):
        rest = "  <- from rest" if i == d["from_rest"] else ""
        lines.append(f"  {i}: {a['regime']:10s} basin {a['basin_fraction']:.3f} "
                     f"[{a['ci'][0]:.3f}, {a['ci'][1]:.3f}]  KE ratio {a['ke_ratio']:.4f}"
                     f"  x_max {1e3 * a['xmax_m']:.4g} mm{rest}"
                     f"{_asymptotic_text(a, d['attractors'])}")
    if d.get("t_max") is not None:
        lines.append(f"asymptotic view to t = {d['t_max']:g}; from rest at t_max: "
                     f"{_attractor_name(d['from_rest_asymptotic'], d['attractors'])}")
    return "\n".join(lines)


def _attractor_name(index, attractors: list) -> str:
    """'attractor 0 (1:1)' for an index into ``attractors``; 'none' for None."""
    if index is None:
        return "none"
    return f"attractor {index} ({attractors[int(index)]['regime']})"


def _asymptotic_text(a: dict, attractors: list) -> str:
    """The asymptotic columns of one attractor (empty without --t-max)."""
    if "status" not in a:
        return ""
    ci = a["ci_asymptotic"]
    out = (f"  -> {a['status']}, asymptotic basin {a['basin_fraction_asymptotic']:.3f} "
           f"[{ci[0]:.3f}, {ci[1]:.3f}]")
    if a.get("regime_asymptotic") == "quasi-periodic":
        amp = a["modulation"]["amplitude"]
        out += f", quasi-periodic (LO amplitude {amp[0]:.4g} to {amp[1]:.4g} L)"
    life = a.get("lifetime")
    if life:
        g = _fmt
        out += (f", mean lifetime {g(life['mean'])} [{g(life['ci'][0])}, "
                f"{g(life['ci'][1])}] time units")
    if a.get("escape_to"):
        went = [f"{n} to {_attractor_name(j, attractors)}" for j, n in a["escape_to"].items()]
        out += f"; states escaped: {', '.join(went)}"
    return out


def _fmt(x) -> str:
    return "inf" if x is None or x == float("inf") else f"{x:.3g}"
