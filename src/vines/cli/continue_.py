"""``vines continue``: a 1:1 branch (or, with ``--walls SEQ --periods N``, a branch of any
wall sequence) followed in eta, omega or F, with its events.

(The module has a trailing underscore: ``continue`` is a Python keyword.)
"""
from __future__ import annotations

import argparse
import dataclasses

from ..core.params import (
    BRANCH_KINDS,
    CONTINUATION_METHODS,
    MAX_INADMISSIBLE_DEFAULT,
    MAX_POINTS_DEFAULT,
    MAX_POINTS_MAX,
    PARAM_NAMES,
    ModelParams,
    ParameterError,
    check_int,
    check_real,
    check_step_points,
)
from .common import VinesArgumentParser, add_model_args, emit, quiet_stdout
from .orbit_json import branch_json, family_keys
from .periodic import add_walls_args

NAME = "continue"


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="continue a 1:1 orbit in eta, omega or F and report bifurcation events",
        description="Pseudo-arclength continuation (through folds) of the preferred 1:1 "
                    "orbit of the chosen --branch at --start, until the parameter leaves "
                    "[start, stop]; events (fold, flip, neimark-sacker, admissibility-loss, "
                    "symmetry-breaking) are located along the arclength. --method natural: "
                    "natural-parameter continuation from --start to --stop (ends at a fold).",
    )
    p.add_argument("--param", choices=PARAM_NAMES, required=True,
                   help="the parameter to vary")
    p.allowed_values["--param"] = "one of eta, omega, F"
    for flag, allowed, help in (
        ("--start", "a number in the parameter's range", "first parameter value"),
        ("--stop", "a number in the parameter's range", "last parameter value"),
    ):
        p.allowed_values[flag] = allowed
        p.add_argument(flag, metavar=flag.lstrip("-").upper(), required=True,
                       help=f"{help} [{allowed}]")
    p.allowed_values["--step"] = "a number > 0 with |stop - start|/step <= max-points"
    p.add_argument("--step", metavar="H", default=None,
                   help="parameter step (natural) or largest arclength step (arclength) "
                        "[> 0 and >= |stop - start|/max-points; default (stop - start)/100]")
    p.add_argument("--method", choices=CONTINUATION_METHODS, default="arclength",
                   help="arclength (default: through folds) or natural")
    p.allowed_values["--method"] = "one of " + ", ".join(CONTINUATION_METHODS)
    p.add_argument("--branch", choices=BRANCH_KINDS, default="symmetric",
                   help="the orbit to start from: symmetric (default) or asymmetric")
    p.allowed_values["--branch"] = "one of " + ", ".join(BRANCH_KINDS)
    p.add_argument("--switch", action="store_true",
                   help="also continue the asymmetric branch born at every symmetry-breaking "
                        "point of the symmetric branch (with --walls: also the "
                        "period-doubled branch born at every flip point) (JSON key switched; "
                        "arclength only)")
    p.allowed_values["--max-inadmissible"] = f"an integer >= 1 and <= {MAX_POINTS_MAX}"
    p.add_argument("--max-inadmissible", metavar="N", default=MAX_INADMISSIBLE_DEFAULT,
                   help="end the branch after N consecutive non-admissible points "
                        f"(arclength) [integer >= 1 and <= {MAX_POINTS_MAX}; default "
                        f"{MAX_INADMISSIBLE_DEFAULT}]")
    p.allowed_values["--max-points"] = f"an integer >= 1 and <= {MAX_POINTS_MAX}"
    p.add_argument("--max-points", metavar="N", default=MAX_POINTS_DEFAULT,
                   help="refuse a step that needs more than N continuation points "
                        f"[integer >= 1 and <= {MAX_POINTS_MAX}; default {MAX_POINTS_DEFAULT}]")
    add_model_args(p, optional_group="model parameters (the two not continued are required)")
    add_walls_args(p, "continue an orbit of this wall sequence")
    p.add_argument("--all", action="store_true",
                   help="text output: every point of every branch (default: a summary with "
                        f"the events and {N_SAMPLES} points per branch)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: walls, periods, family, "
                        "param, branch, events, stopped, switched, born_at)")
    p.set_defaults(_parser=p)
    return p


def _fixed_params(args: argparse.Namespace) -> list[str]:
    """The two parameters not continued; refuse the continued one and missing ones."""
    sub = args._parser
    given = getattr(args, args.param)
    if given is not None:
        others = " and ".join(f"--{q}" for q in PARAM_NAMES if q != args.param)
        sub.error(f"argument --{args.param}: invalid {args.param} = {given!r}: not allowed "
                  f"with --param {args.param} (the continued parameter runs from --start to "
                  f"--stop); give only {others}")
    others = [q for q in PARAM_NAMES if q != args.param]
    missing = [f"--{q}" for q in others if getattr(args, q) is None]
    if missing:
        sub.error("missing required option " + ", ".join(
            f"{m} ({sub.allowed_values[m]})" for m in missing) + f" when --param is {args.param}")
    return others


def _end_points(args: argparse.Namespace, others: list[str]) -> tuple[dict, ModelParams]:
    """Validated start and stop values (named after their flags), and the model at stop."""
    fixed = {q: getattr(args, q) for q in others}
    values = {}
    for name in ("start", "stop"):
        raw = getattr(args, name)
        kw = dict(fixed, **{args.param: raw})
        try:
            params = ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"], r=args.r,
                                 d=args.d)
        except ParameterError as err:
            if err.name == args.param:
                raise ParameterError(name, raw, f"{err.allowed} ({args.param})") from None
            raise
        values[name] = getattr(params, args.param)
    return values, params


def _limits(args: argparse.Namespace, values: dict) -> tuple[float | None, int, int]:
    """Validated step (None: the default), max_points and max_inadmissible."""
    max_points = check_int("max_points", args.max_points, lo=1, hi=MAX_POINTS_MAX)
    step = None
    if args.step is not None:
        step = check_real("step", args.step, lo=0.0, lo_open=True)
        check_step_points(args.step, abs(values["stop"] - values["start"]), step, max_points,
                          "--max-points")
    max_inadmissible = check_int("max_inadmissible", args.max_inadmissible, lo=1,
                                 hi=MAX_POINTS_MAX)
    return step, max_points, max_inadmissible


def run(args: argparse.Namespace) -> int:
    others = _fixed_params(args)
    values, params = _end_points(args, others)
    if args.walls is not None:
        return emit(args.json, _run_walls(args, values, params),
                    lambda d: _text(d, values, every=args.all))
    step, max_points, max_inadmissible = _limits(args, values)
    if args.switch and (args.method != "arclength" or args.branch != "symmetric"):
        args._parser.error(f"argument --switch: not allowed with --method {args.method} "
                           f"--branch {args.branch} (only with --method arclength --branch "
                           "symmetric)")
    fixed = {q: getattr(params, q) for q in others}
    from ..orbits.continuation.one_to_one import continue_branch

    with quiet_stdout():
        br = continue_branch(args.param, values["start"], values["stop"], step, fixed,
                             r=params.r, d=params.d, max_points=max_points,
                             method=args.method, branch=args.branch, switch=args.switch,
                             max_inadmissible=max_inadmissible)
    return emit(args.json, branch_json(br), lambda d: _text(d, values, every=args.all))


def _run_walls(args: argparse.Namespace, values: dict, stop: ModelParams) -> dict:
    """The continued branch of a wall sequence (``orbit_json.branch_json``)."""
    from ..orbits.continuation.sequence import ContinueSettings, continue_sequence
    from ..orbits.family.family import check_periods, check_walls
    from ..orbits.family.sequence import find_sequence

    walls = check_walls(args.walls)
    periods = check_periods(args.periods)
    if args.switch and args.method != "arclength":
        args._parser.error(f"argument --switch: not allowed with --method {args.method} "
                           "(only with --method arclength)")
    step, max_points, max_inadmissible = _limits(args, values)
    start = dataclasses.replace(stop, **{args.param: values["start"]})
    symmetric = args.branch == "symmetric"
    with quiet_stdout():
        found = find_sequence(start, walls, periods)
        cands = [o for o in found if o.symmetric == symmetric] or found
        if not cands:
            return branch_json(dict(family_keys(walls, periods), param=args.param, branch=[],
                                    events=[], stopped=f"no {walls}/{periods} orbit at start",
                                    switched=[]))
        settings = ContinueSettings(step=step, switch=bool(args.switch),
                                    max_points=max_points, max_inadmissible=max_inadmissible,
                                    method=args.method)
        br = continue_sequence(start, walls, periods, args.param, values["stop"],
                               orbit=cands[0], settings=settings)
    return branch_json(br)


def _dw(pt: dict) -> str:
    """The impact velocities of a point, one per impact in sequence order."""
    return "dw = [" + ", ".join(f"{v:.6g}" for v in pt["dw"]) + "]"


#: points shown per branch in the default summary (first, last, evenly spaced between)
N_SAMPLES = 5


def _samples(points: list) -> list:
    """At most N_SAMPLES points: the first, the last and evenly spaced ones between."""
    if len(points) <= N_SAMPLES:
        return points
    idx = sorted({round(k * (len(points) - 1) / (N_SAMPLES - 1)) for k in range(N_SAMPLES)})
    return [points[i] for i in idx]


def _text(d: dict, values: dict, indent: str = "", every: bool = False) -> str:
    """Summary of a ``branch_json`` object (and of the branches switched to): its ends, its
    events and N_SAMPLES points; every point with ``every``."""
    param = d["param"]
    name = d["family"]
    if indent and d["branch"]:
        # a switched branch starts where it is born, not at --start, and runs either way
        first, last = d["branch"][0][param], d["branch"][-1][param]
        head = (f"born at {param} = {first:.7g}, followed "
                f"{'up' if last >= first else 'down'} to {last:.7g}")
    else:
        head = f"from {values['start']:g} towards {values['stop']:g}"
    lines = [f"{indent}{name} branch in {param} {head}: {len(d['branch'])} points; "
             f"ended: {d['stopped']}"]
    pts = d["branch"] if every else _samples(d["branch"])
    if len(pts) < len(d["branch"]):
        lines.append(f"{indent}  {len(pts)} of the points (--all: every point, --json: "
                     "everything)")
    for pt in pts:
        lines.append(f"{indent}  {param} = {pt[param]:.6g}  |lambda_max| = "
                     f"{pt['lambda_max']:.6g}  stable = {pt['stable']}  symmetric = "
                     f"{pt['symmetric']}  admissible = {pt['admissible']}  {_dw(pt)}")
    for ev in d["events"]:
        con = f" (meets the {ev['meets']} branch)" if ev["meets"] else ""
        lines.append(f"{indent}  event {ev['type']} at {param} = {ev['at']:.7g}{con}")
    for sw in d["switched"]:
        lines.append(_text(sw, values, indent + "  ", every))
    return "\n".join(lines)
