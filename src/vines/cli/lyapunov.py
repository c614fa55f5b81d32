"""``vines lyapunov``: the Lyapunov spectrum at one parameter point (``vines.lyapunov``).

JSON keys (``LyapunovResult.to_dict``): exponents (four, descending, per unit dimensionless
time; null for a direction removed by sticking, i.e. -inf), ci (four [low, high] 95 %
batch-means intervals), regime, period, n_impacts and n_sticks (in the window), status,
n_batches, ci_method, params and settings (every input actually used, state0 included).
Every value is read as a string and validated by ``vines.lyapunov`` itself.
"""
from __future__ import annotations

import argparse
import contextlib
import math

from ..core.params import T_END_DEFAULT, T_END_MAX, T_TRANSIENT_DEFAULT, ParameterError
from .common import (
    VinesArgumentParser,
    add_json_flag,
    add_model_args,
    add_value,
    emit,
    quiet_stdout,
)

NAME = "lyapunov"
#: the names ``vines.lyapunov`` gives the components of state0
STATE0_NAMES = {"z_m0", "v_m0", "z_b0", "v_b0"}


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="Lyapunov spectrum (saltation matrices, Benettin QR) at one parameter point",
        description="The four Lyapunov exponents of the exact trajectory from STATE0 (default: "
                    "rest) over the window [t-transient, t-end], per unit dimensionless time, "
                    "with 95 % batch-means intervals. A window containing a stick has "
                    "lambda_3 = lambda_4 = -inf (null in JSON): sticking removes two "
                    "dimensions. A finite-time answer: the motion in the window may be a "
                    "transient (vines attractors --t-max).")
    add_model_args(p, phi=True)
    state0_allowed = "4 numbers z_m z_m' z_b z_b' with |z_m - z_b| <= 1"
    p.allowed_values["--state0"] = state0_allowed
    p.add_argument("--state0", metavar=("Z_M", "V_M", "Z_B", "V_B"), nargs=4, default=None,
                   help=f"initial state at t = 0 [{state0_allowed}; default rest]")
    add_value(p, "--t-end", f"a number > 0 and <= {T_END_MAX:g}",
              f"end of the window (default {T_END_DEFAULT:g})", default=T_END_DEFAULT)
    add_value(p, "--t-transient", "a number >= 0 and < t-end",
              f"start of the window (default {T_TRANSIENT_DEFAULT:g})",
              default=T_TRANSIENT_DEFAULT)
    add_json_flag(p, "keys: exponents, ci, regime, n_impacts, n_sticks, params, settings")
    return p


def run(args: argparse.Namespace) -> int:
    """Validate and compute (``vines.lyapunov`` raises ParameterError naming the argument)."""
    from ..attractors.lyapunov import lyapunov
    with quiet_stdout(), _state0_named():
        res = lyapunov(eta=args.eta, omega=args.omega, F=args.F, r=args.r, d=args.d,
                       phi=args.phi, state0=args.state0, t_end=args.t_end,
                       t_transient=args.t_transient)
    return emit(args.json, res.to_dict(), _text)


@contextlib.contextmanager
def _state0_named():
    """A bad component of --state0 (z_m0, v_m0, ...) is reported as --state0."""
    try:
        yield
    except ParameterError as err:
        if err.name in STATE0_NAMES:
            raise ParameterError("state0", err.value, f"{err.name} {err.allowed}") from None
        raise


def _num(x) -> str:
    return "-inf" if x is None or (isinstance(x, float) and math.isinf(x)) else f"{x:+.5f}"


def _text(d: dict) -> str:
    """One line of inputs, then the four exponents with their intervals."""
    p, st = d["params"], d["settings"]
    lines = [f"eta = {p['eta']:g}, omega = {p['omega']:g}, F = {p['F']:g}: {d['regime']} over "
             f"[{st['t_transient']:g}, {st['t_end']:g}], {d['n_impacts']} impacts, "
             f"{d['n_sticks']} sticks"]
    for i, (lam, (lo, hi)) in enumerate(zip(d["exponents"], d["ci"], strict=True), 1):
        lines.append(f"  lambda_{i} = {_num(lam)}  [{_num(lo)}, {_num(hi)}]")
    return "\n".join(lines)
