"""``vines lyapunov``: the Lyapunov spectrum at one parameter point (``vines.lyapunov``).

    vines lyapunov --eta E --omega W --F F [--r R] [--d D] [--phi P]
                   [--state0 Z_M V_M Z_B V_B] [--t-end T] [--t-transient T0] [--json]

JSON keys (``LyapunovResult.to_dict``): exponents (four, descending, per unit dimensionless
time; null for a direction removed by sticking, i.e. -inf), ci (four [low, high] 95 %
batch-means intervals), regime, period, n_impacts and n_sticks (in the window), status,
n_batches, ci_method, params and settings (every input actually used, state0 included).

Wiring: the CLI package calls ``add_parser(subparsers)`` (it sets ``handler=run``), and
emits ``run(args)`` as JSON (NaN/inf -> null) or through ``text``. Every value is read as a
string and validated by ``vines.lyapunov`` itself (ModelParams, SolverSettings), which
raises ParameterError naming the argument: the CLI's exit-2 one-line message.
"""
from __future__ import annotations

import argparse
import math

from ..core.params import (
    D_DEFAULT,
    PARAM_BOUNDS,
    R_DEFAULT,
    T_END_DEFAULT,
    T_END_MAX,
    T_TRANSIENT_DEFAULT,
)

#: flag -> allowed values (for the CLI's error messages)
ALLOWED = {
    "--eta": "a number > 0 and <= {:g}".format(PARAM_BOUNDS["eta"][2]),
    "--omega": "a number > 0 and <= {:g}".format(PARAM_BOUNDS["omega"][2]),
    "--F": "a number >= 0 and <= {:g}".format(PARAM_BOUNDS["F"][2]),
    "--r": "a number in [0, 1]",
    "--d": "a number >= 0 and <= {:g}".format(PARAM_BOUNDS["d"][2]),
    "--phi": "a number with |phi| <= {:g}".format(PARAM_BOUNDS["phi"][2]),
    "--state0": "4 numbers z_m z_m' z_b z_b' with |z_m - z_b| <= 1",
    "--t-end": f"a number > 0 and <= {T_END_MAX:g}",
    "--t-transient": "a number >= 0 and < t-end",
}


def add_parser(subparsers) -> argparse.ArgumentParser:
    """The ``lyapunov`` sub-parser (values as strings, validated by ``run``)."""
    p = subparsers.add_parser(
        "lyapunov",
        help="Lyapunov spectrum (saltation matrices, Benettin QR) at one parameter point",
        description="The four Lyapunov exponents of the exact trajectory from STATE0 (default: "
                    "rest) over the window [t-transient, t-end], per unit dimensionless time, "
                    "with 95 %% batch-means intervals. A window containing a stick has "
                    "lambda_3 = lambda_4 = -inf (null in JSON): sticking removes two "
                    "dimensions. A finite-time answer: the motion in the window may be a "
                    "transient (vines attractors --t-max).")
    req = p.add_argument_group("model parameters (required)")
    for flag, help_ in (("--eta", "ball-to-LO mass ratio m/M"),
                        ("--omega", "forcing frequency ratio omega = w/w0"),
                        ("--F", "forcing amplitude A/L")):
        req.add_argument(flag, metavar=flag.lstrip("-").upper(), required=True,
                         help=f"{help_} [{ALLOWED[flag]}]")
    opt = p.add_argument_group("model parameters (optional)")
    opt.add_argument("--r", metavar="R", default=R_DEFAULT,
                     help=f"coefficient of restitution [{ALLOWED['--r']}; default {R_DEFAULT:g}]")
    opt.add_argument("--d", metavar="D", default=D_DEFAULT,
                     help=f"LO damping c/(M w0) [{ALLOWED['--d']}; default {D_DEFAULT:.6f}]")
    opt.add_argument("--phi", metavar="P", default=0.0,
                     help=f"forcing phase at t = 0 in rad [{ALLOWED['--phi']}; default 0]")
    run_ = p.add_argument_group("run")
    run_.add_argument("--state0", metavar=("Z_M", "V_M", "Z_B", "V_B"), nargs=4, default=None,
                      help=f"initial state at t = 0 [{ALLOWED['--state0']}; default rest]")
    run_.add_argument("--t-end", metavar="T", default=T_END_DEFAULT,
                      help=f"end of the window [{ALLOWED['--t-end']}; default {T_END_DEFAULT:g}]")
    run_.add_argument("--t-transient", metavar="T0", default=T_TRANSIENT_DEFAULT,
                      help=f"start of the window [{ALLOWED['--t-transient']}; default "
                           f"{T_TRANSIENT_DEFAULT:g}]")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: exponents, ci, regime, "
                        "n_impacts, n_sticks, params, settings)")
    p.set_defaults(handler=run)
    return p


def run(args: argparse.Namespace) -> dict:
    """Validate and compute; the JSON object (``LyapunovResult.to_dict``). Raises
    ParameterError naming the bad argument."""
    from ..attractors.lyapunov import lyapunov
    res = lyapunov(eta=args.eta, omega=args.omega, F=args.F, r=args.r, d=args.d,
                   phi=args.phi, state0=args.state0, t_end=args.t_end,
                   t_transient=args.t_transient)
    return res.to_dict()


def text(d: dict) -> str:
    """The text output: one line of inputs, the four exponents with their intervals."""
    p = d["params"]

    def num(x):
        return "-inf" if x is None or (isinstance(x, float) and math.isinf(x)) else f"{x:+.5f}"

    lines = [f"eta = {p['eta']:g}, omega = {p['omega']:g}, F = {p['F']:g}: {d['regime']} over "
             f"[{d['settings']['t_transient']:g}, {d['settings']['t_end']:g}], "
             f"{d['n_impacts']} impacts, {d['n_sticks']} sticks"]
    for i, (lam, (lo, hi)) in enumerate(zip(d["exponents"], d["ci"], strict=True), 1):
        lines.append(f"  lambda_{i} = {num(lam)}  [{num(lo)}, {num(hi)}]")
    return "\n".join(lines)
