"""``vines boundaries``: curves of codimension-one points of 1:1 orbits (or of the orbits of
any wall sequence, ``--walls``/``--periods``) in (eta, omega)."""
from __future__ import annotations

import argparse

from ..core.params import D_DEFAULT, R_DEFAULT, ModelParams
from .common import VinesArgumentParser, emit, param_allowed, quiet_stdout
from .orbit_json import ONE_TO_ONE, boundaries_json
from .periodic import add_walls_args

NAME = "boundaries"


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="curves of fold, flip, neimark-sacker, symmetry-breaking and grazing points of "
             "1:1 orbits (or of any wall sequence) in the (eta, omega) plane at fixed F",
        description="Seed from one-parameter continuations along lines of the box, then "
                    "continue every codimension-one point of the 1:1 orbits (augmented "
                    "systems, exact Jacobians) in (eta, omega) at fixed F: the edges of the "
                    "classes of the stability map (Fig 16). With --walls SEQ --periods N the "
                    "same curves of that family (docs/bifurcation.md).",
    )
    p.allowed_values["--F"] = param_allowed("F")
    p.add_argument("--F", metavar="F", required=True,
                   help=f"forcing amplitude A/L [{param_allowed('F')}]")
    for name, default in (("eta", (0.05, 1.0)), ("omega", (0.7, 1.4))):
        flag = f"--{name}-range"
        p.allowed_values[flag] = f"two numbers lo < hi, each {param_allowed(name)}"
        p.add_argument(flag, nargs=2, metavar=("LO", "HI"), default=list(default),
                       help=f"{name} interval of the box [{p.allowed_values[flag]}; default "
                            f"{default[0]:g} {default[1]:g}]")
    opt = p.add_argument_group("model parameters (optional)")
    for flag, default, help in (("--r", R_DEFAULT, "coefficient of restitution"),
                                ("--d", D_DEFAULT, "LO damping c/(M w0)")):
        p.allowed_values[flag] = param_allowed(flag[2:])
        opt.add_argument(flag, metavar=flag[2:].upper(), default=default,
                         help=f"{help} [{param_allowed(flag[2:])}; default {default:g}]")
    add_walls_args(p, "wall sequence of the family whose curves are traced (default LR: the "
                      "1:1 orbits; other families are seeded on the n_scan x n_scan crossings "
                      "of the scan lines)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: F, eta_range, omega_range, "
                        "walls, periods, family, curves)")
    return p


def run(args: argparse.Namespace) -> int:
    params = ModelParams(eta=0.1, omega=1.0, F=args.F, r=args.r, d=args.d)
    from ..orbits.curves.boundaries import boundaries

    walls = ONE_TO_ONE[0] if args.walls is None else args.walls
    with quiet_stdout():
        res = boundaries(params.F, args.eta_range, args.omega_range, r=params.r, d=params.d,
                         walls=walls, periods=args.periods)
    d = boundaries_json(res.to_dict(), res.walls, res.periods)
    return emit(args.json, d, lambda d: _text(d, params.F))


def _text(d: dict, F: float) -> str:
    lines = [f"F = {F:g}, eta in {d['eta_range']}, omega in {d['omega_range']}: "
             f"{len(d['curves'])} curve(s)"]
    for c in d["curves"]:
        (e0, w0), (e1, w1) = c["points"][0], c["points"][-1]
        where = f" (flight {c['flight']}, {c['wall']})" if "wall" in c else ""
        lines.append(f"  {c['type']}{where} of {c['family']} orbits: {len(c['points'])} "
                     f"points from (eta, omega) = ({e0:.4g}, {w0:.4g}) to ({e1:.4g}, "
                     f"{w1:.4g})")
    lines[0] += f" (family {d['family']})"
    return "\n".join(lines)
