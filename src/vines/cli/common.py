"""What every command shares: the argument parser, the model arguments, the error messages
and the JSON-or-text output.

Every number is read as a string and validated by the same code the Python API uses
(``vines.core.params``), so the CLI and the API accept exactly the same values.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
from typing import NoReturn

from ..core.params import (
    C_DAMP_NS_PER_M,
    D_DEFAULT,
    K_SPRING_N_PER_M,
    M_LO_KG,
    PARAM_BOUNDS,
    R_DEFAULT,
    ModelParams,
)

PROG = "vines"


class VinesArgumentParser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit status 2."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        # flag -> short description of the allowed values (used in error messages)
        self.allowed_values: dict[str, str] = {}

    def error(self, message: str) -> NoReturn:  # noqa: D401 - argparse API
        prefix = "the following arguments are required: "
        if message.startswith(prefix):
            flags = [f.strip() for f in message[len(prefix):].split(",")]
            parts = []
            for flag in flags:
                allowed = self.allowed_values.get(flag)
                parts.append(f"{flag} ({allowed})" if allowed else flag)
            message = "missing required option " + ", ".join(parts)
        message = " ".join(str(message).split())  # exactly one line
        self.exit(2, f"{self.prog}: error: {message}\n")


def param_allowed(name: str) -> str:
    """Allowed values of a model parameter, from ``PARAM_BOUNDS`` (e.g. 'a number > 0 and <= 1000')."""
    lo, lo_open, hi = PARAM_BOUNDS[name]
    if name == "phi":
        return f"a number with |phi| <= {hi:g}"
    if lo == 0.0 and hi == 1.0 and not lo_open:
        return "a number in [0, 1]"
    return f"a number {'>' if lo_open else '>='} {lo:g} and <= {hi:g}"


def flag_for(name: str) -> str:
    """Command-line flag of a parameter name used by ``vines.params`` (t_end -> --t-end)."""
    return "--" + name.replace("_", "-")


def add_value(parser: VinesArgumentParser, flag: str, allowed: str, help: str, **kwargs):
    """Add an option taking one value (parsed as a string and validated later)."""
    parser.allowed_values[flag] = allowed
    metavar = kwargs.pop("metavar", flag.lstrip("-").upper().replace("-", "_"))
    parser.add_argument(flag, metavar=metavar, help=f"{help} [{allowed}]", **kwargs)


def add_model_args(parser: VinesArgumentParser, *, phi: bool = False,
                   optional_group: str | None = None):
    """The model parameters eta, omega, F (required) and r, d (and phi) (optional).

    With ``optional_group`` (a group title) eta, omega and F default to None and are listed
    with r and d in that group; the command then checks which ones it needs.
    """
    required = optional_group is None
    req = parser.add_argument_group(optional_group or "model parameters (required)")
    for flag, allowed, help in (
        ("--eta", param_allowed("eta"), "ball-to-LO mass ratio m/M"),
        ("--omega", param_allowed("omega"), "forcing frequency ratio omega = w/w0"),
        ("--F", param_allowed("F"), "forcing amplitude A/L"),
    ):
        parser.allowed_values[flag] = allowed
        kw = {"required": True} if required else {"default": None}
        req.add_argument(flag, metavar=flag.lstrip("-").upper(), help=f"{help} [{allowed}]",
                         **kw)
    opt = parser.add_argument_group("model parameters (optional)") if required else req
    parser.allowed_values["--r"] = param_allowed("r")
    opt.add_argument("--r", metavar="R", default=R_DEFAULT,
                     help=f"coefficient of restitution [0 <= r <= 1; default {R_DEFAULT:g}]")
    parser.allowed_values["--d"] = param_allowed("d")
    opt.add_argument("--d", metavar="D", default=D_DEFAULT,
                     help=f"LO damping c/(M w0), fixed for every eta "
                          f"[{param_allowed('d')}; default {D_DEFAULT:.6f}]")
    if phi:
        parser.allowed_values["--phi"] = param_allowed("phi")
        opt.add_argument("--phi", metavar="P", default=0.0,
                         help=f"forcing phase at t = 0 in rad [{param_allowed('phi')}; default 0]")


def add_structure_args(parser: VinesArgumentParser) -> None:
    """The structure of ``vines design`` and ``vines shock``: the LO's --M, --k, --c or --d
    and the restitution --r (strings, validated by ``studies.design_checks``)."""
    lo = parser.add_argument_group("structure (Table 1 by default)")
    lo.add_argument("--M", metavar="KG", default=None,
                    help=f"LO mass in kg [> 0; default {M_LO_KG:g}]")
    lo.add_argument("--k", metavar="N_PER_M", default=None,
                    help=f"LO stiffness in N/m [> 0; default {K_SPRING_N_PER_M:g}]")
    damp = lo.add_mutually_exclusive_group()
    damp.add_argument("--c", metavar="NS_PER_M", default=None,
                      help=f"LO damping in N s/m [>= 0; default {C_DAMP_NS_PER_M:g}]")
    damp.add_argument("--d", metavar="D", default=None,
                      help="dimensionless LO damping c/(M w0) instead of --c [>= 0]")
    lo.add_argument("--r", metavar="R", default=R_DEFAULT,
                    help=f"coefficient of restitution [0 <= r <= 1; default {R_DEFAULT:g}]")


def add_json_flag(parser: VinesArgumentParser, keys: str):
    """The ``--json`` flag; ``keys`` says what the object holds."""
    parser.add_argument("--json", action="store_true",
                        help=f"print one JSON object on stdout ({keys})")


def model_params(args: argparse.Namespace) -> ModelParams:
    """The validated model of a command's eta, omega, F, r, d (and phi) arguments."""
    return ModelParams(eta=args.eta, omega=args.omega, F=args.F, r=args.r, d=args.d,
                       phi=getattr(args, "phi", 0.0))


def quiet_stdout():
    """Stray prints of the numerics go to stderr: stdout carries the command's output only."""
    return contextlib.redirect_stdout(sys.stderr)


def emit(as_json: bool, d: dict, text) -> int:
    """Print ``d`` as one JSON object, or ``text(d)`` for a reader; exit status 0."""
    sys.stdout.write((json.dumps(jsonable(d), allow_nan=False) if as_json else text(d)) + "\n")
    sys.stdout.flush()
    return 0


def jsonable(x):
    """Plain JSON types only; NaN and +-inf become None (null)."""
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if hasattr(x, "tolist") and not isinstance(x, (str, bytes)):  # numpy arrays and scalars
        return jsonable(x.tolist())
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return x
    if isinstance(x, int):
        return int(x)
    if isinstance(x, float):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, complex):
        return [jsonable(x.real), jsonable(x.imag)]
    return str(x)
