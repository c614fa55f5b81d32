"""``vines periodic --walls SEQ --periods N``: periodic orbits of any wall sequence.

To be wired into the ``periodic`` command of ``vines.cli``: ``add_arguments(parser)`` on
its parser, and when ``args.walls`` is given its handler returns ``run(args)`` through the
CLI's JSON/text output (``text`` formats it). Without ``--walls`` the command is unchanged
(the 1:1 solver); ``--walls LR --periods 1`` gives the same orbits as it.
"""
from __future__ import annotations

import argparse
import contextlib
import sys

from ..core.params import ModelParams
from ..orbits.sequence import MAX_IMPACTS_PER_ORBIT, MAX_PERIODS, check_periods, check_walls

WALLS_ALLOWED = f"1 to {MAX_IMPACTS_PER_ORBIT} letters L or R, e.g. LR, LLRR, LLR, RLRL"
PERIODS_ALLOWED = f"an integer 1 <= N <= {MAX_PERIODS}"
#: keys of each solution in the JSON output
SOLUTION_KEYS = ("walls", "periods", "family", "paper_label", "symmetric", "admissible",
                 "stable", "lambda_max", "eigenvalues", "dw", "phases", "flight_times")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add --walls and --periods to the ``periodic`` parser."""
    allowed = getattr(parser, "allowed_values", None)
    if allowed is not None:             # vines.cli.VinesArgumentParser names them on errors
        allowed["--walls"] = WALLS_ALLOWED
        allowed["--periods"] = PERIODS_ALLOWED
    g = parser.add_argument_group("wall sequence (default: the 1:1 orbits)")
    g.add_argument("--walls", metavar="SEQ", default=None,
                   help=f"wall sequence of the orbit, impact by impact [{WALLS_ALLOWED}]")
    g.add_argument("--periods", metavar="N", default=1,
                   help=f"forcing periods of the orbit [{PERIODS_ALLOWED}; default 1]")


def run(args: argparse.Namespace) -> dict:
    """Every orbit of the sequence found: {"walls", "periods", "family", "solutions",
    "params"}. Raises ParameterError (naming the option) on bad input."""
    from ..orbits.sequence import family_name, find_sequence

    walls = check_walls(args.walls)
    periods = check_periods(args.periods)
    params = ModelParams(eta=args.eta, omega=args.omega, F=args.F, r=args.r, d=args.d,
                         phi=getattr(args, "phi", 0.0))
    with contextlib.redirect_stdout(sys.stderr):
        orbits = find_sequence(params, walls, periods)
    sols = [{k: o.to_dict()[k] for k in SOLUTION_KEYS} for o in orbits]
    return {"walls": walls, "periods": periods, "family": family_name(walls, periods),
            "solutions": sols, "params": params.as_dict()}


def text(d: dict) -> str:
    """Human-readable form of ``run``'s result."""
    p, sols = d["params"], d["solutions"]
    lines = [(f"eta = {p['eta']:g}, omega = {p['omega']:g}, F = {p['F']:g}: "
             f"{len(sols)} solution(s) of {d['walls']} over {d['periods']} period(s) "
             f"(family {d['family']})")]
    for s in sols:
        sym = "symmetric" if s["symmetric"] else "asymmetric"
        adm = "admissible" if s["admissible"] else "NOT admissible"
        st = "stable" if s["stable"] else "unstable"
        dw = ", ".join(f"{v:.6g}" for v in s["dw"])
        ph = ", ".join(f"{v:.4g}" for v in s["phases"])
        lines.append(f"  {sym:10s} {adm:14s} {st:8s} |lambda_max| = {s['lambda_max']:.6g}  "
                     f"dw = [{dw}]  phases = [{ph}]")
    return "\n".join(lines)
