"""``vines continue --walls SEQ --periods N``: continuation of any wall sequence.

To be wired into the ``continue`` command of ``vines.cli``: ``add_arguments(parser)`` on its
parser; when ``args.walls`` is given, after the command's own checks of --param, --start,
--stop and the fixed parameters, its handler returns ``run(args)`` through the CLI's output.
--branch picks the starting orbit's symmetry (symmetric / asymmetric), --switch continues
the period-doubled branches born at flip points (JSON key ``switched``); --method natural
is not offered for sequences (arclength only). Without --walls the command is unchanged.
"""
from __future__ import annotations

import argparse
import contextlib
import sys

from ..core.params import (
    MAX_POINTS_MAX,
    ModelParams,
    ParameterError,
    check_int,
    check_real,
    check_step_points,
)
from ..orbits.sequence import check_periods, check_walls
from .periodic_walls import PERIODS_ALLOWED, WALLS_ALLOWED


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add --walls and --periods to the ``continue`` parser."""
    allowed = getattr(parser, "allowed_values", None)
    if allowed is not None:
        allowed["--walls"] = WALLS_ALLOWED
        allowed["--periods"] = PERIODS_ALLOWED
    g = parser.add_argument_group("wall sequence (default: the 1:1 orbits)")
    g.add_argument("--walls", metavar="SEQ", default=None,
                   help=f"continue an orbit of this wall sequence [{WALLS_ALLOWED}]")
    g.add_argument("--periods", metavar="N", default=1,
                   help=f"forcing periods of the orbit [{PERIODS_ALLOWED}; default 1]")


def _params(args, value) -> ModelParams:
    kw = {q: getattr(args, q) for q in ("eta", "omega", "F")}
    kw[args.param] = value
    return ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"], r=args.r, d=args.d,
                       phi=getattr(args, "phi", 0.0))


def run(args: argparse.Namespace) -> dict:
    """The continued branch as a dict (keys of ``SequenceBranch.to_dict``: walls, periods,
    family, param, branch, events, stopped, switched). Raises ParameterError naming the
    option on bad input."""
    from ..orbits.sequence import find_sequence
    from ..orbits.sequence_branches import continue_sequence

    walls = check_walls(args.walls)
    periods = check_periods(args.periods)
    if getattr(args, "method", "arclength") != "arclength":
        raise ParameterError("method", args.method, "must be arclength with --walls")
    try:
        start = _params(args, args.start)
    except ParameterError as err:
        if err.name == args.param:
            raise ParameterError("start", args.start, f"{err.allowed} ({args.param})") from None
        raise
    try:
        stop = getattr(_params(args, args.stop), args.param)
    except ParameterError as err:
        if err.name == args.param:
            raise ParameterError("stop", args.stop, f"{err.allowed} ({args.param})") from None
        raise
    max_points = check_int("max_points", args.max_points, lo=1, hi=MAX_POINTS_MAX)
    span = abs(stop - getattr(start, args.param))
    step = None
    if args.step is not None:
        step = check_real("step", args.step, lo=0.0, lo_open=True)
        check_step_points(args.step, span, step, max_points, "--max-points")
    symmetric = getattr(args, "branch", "symmetric") == "symmetric"
    with contextlib.redirect_stdout(sys.stderr):
        found = find_sequence(start, walls, periods)
        cands = [o for o in found if o.symmetric == symmetric] or found
        if not cands:
            return {"walls": walls, "periods": periods, "param": args.param, "branch": [],
                    "events": [], "stopped": f"no {walls}/{periods} orbit at start",
                    "switched": []}
        br = continue_sequence(start, walls, periods, args.param, stop, step=step,
                               orbit=cands[0], switch=bool(args.switch),
                               max_points=max_points,
                               max_inadmissible=args.max_inadmissible)
    return br.to_dict()
