"""``vines periodic``: the 1:1 orbits of the map P2 o P1 at one parameter point, or with
``--walls SEQ --periods N`` the periodic orbits of any wall sequence (``--walls LR
--periods 1`` gives the same orbits as the 1:1 solver)."""
from __future__ import annotations

import argparse

from ..core.params import ModelParams
from .common import VinesArgumentParser, add_model_args, emit, model_params, quiet_stdout
from .orbit_json import ONE_TO_ONE, periodic_json

NAME = "periodic"


#: limits of ``vines.orbits.family.sequence`` (repeated so that parsing loads no numba; a test
#: checks that they agree)
MAX_IMPACTS_PER_ORBIT, MAX_PERIODS = 64, 64
WALLS_ALLOWED = f"1 to {MAX_IMPACTS_PER_ORBIT} letters L or R, e.g. LR, LLRR, LLR, RLRL"
PERIODS_ALLOWED = f"an integer 1 <= N <= {MAX_PERIODS}"


def add_walls_args(parser: VinesArgumentParser, what: str) -> None:
    """--walls and --periods (default: the 1:1 orbits); ``what`` ends the help of --walls."""
    parser.allowed_values.update({"--walls": WALLS_ALLOWED, "--periods": PERIODS_ALLOWED})
    g = parser.add_argument_group("wall sequence (default: the 1:1 orbits)")
    g.add_argument("--walls", metavar="SEQ", default=None, help=f"{what} [{WALLS_ALLOWED}]")
    g.add_argument("--periods", metavar="N", default=1,
                   help=f"forcing periods of the orbit [{PERIODS_ALLOWED}; default 1]")


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="1:1 periodic orbits from the impact maps (or any wall sequence with --walls), "
             "with admissibility and stability",
        description="Solve P2(P1(x_L)) = x_L + (0, 0, 0, T) for every 1:1 orbit reachable from "
                    "the built-in seeds (symmetric closed form, flight-time scan, short "
                    "simulation) and report admissibility and the eigenvalues of J_P2 J_P1. "
                    "With --walls SEQ --periods N: every orbit of that wall sequence over N "
                    "forcing periods (Newton on the composed maps).",
    )
    add_model_args(p)
    add_walls_args(p, "wall sequence of the orbit, impact by impact")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: walls, periods, family, "
                        "solutions, params)")
    return p


def run(args: argparse.Namespace) -> int:
    if args.walls is not None:
        return emit(args.json, run_walls(args), text_walls)
    params = model_params(args)
    from ..orbits.family.periodic import orbits_1to1

    with quiet_stdout():
        orbits = orbits_1to1(params)
    d = periodic_json([o.to_dict() for o in orbits], *ONE_TO_ONE, params.as_dict())
    return emit(args.json, d, _text)


def run_walls(args: argparse.Namespace) -> dict:
    """Every orbit of the sequence found: {"walls", "periods", "family", "solutions",
    "params"}. Raises ParameterError (naming the option) on bad input."""
    from ..orbits.family.family import check_periods, check_walls
    from ..orbits.family.sequence import find_sequence

    walls = check_walls(args.walls)
    periods = check_periods(args.periods)
    params = ModelParams(eta=args.eta, omega=args.omega, F=args.F, r=args.r, d=args.d,
                         phi=getattr(args, "phi", 0.0))
    with quiet_stdout():
        orbits = find_sequence(params, walls, periods)
    return periodic_json([o.to_dict() for o in orbits], walls, periods, params.as_dict())


#: what the columns of the text output are (dimensionless, docs/model.md)
LEGEND_1TO1 = ("  dw_L, dw_R: relative velocity z_m' - z_b' just before the impact at L, at R; "
               "phase_L: forcing phase omega t + phi (mod 2 pi, rad) at the L impact; flights: "
               "L -> R and R -> L; |lambda_max|: largest Floquet multiplier (< 1: stable)")
IMPACT_LEGEND = ("  dw: relative velocity z_m' - z_b' just before each impact; phases: forcing "
                 "phase omega t + phi (mod 2 pi, rad) at each; |lambda_max|: largest Floquet "
                 "multiplier (< 1: stable)")


def _text(d: dict) -> str:
    p, sols = d["params"], d["solutions"]
    lines = [f"eta = {p['eta']:g}, omega = {p['omega']:g}, F = {p['F']:g}: "
             f"{len(sols)} 1:1 solution(s)"]
    for s in sols:
        family = "symmetric" if s["symmetric"] else "asymmetric"
        adm = "admissible" if s["admissible"] else "NOT admissible"
        st = "stable" if s["stable"] else "unstable"
        lines.append(f"  {family:10s} {adm:14s} {st:8s} |lambda_max| = {s['lambda_max']:.6g}  "
                     f"dw_L = {s['dw'][0]:.6g}  dw_R = {s['dw'][1]:.6g}  "
                     f"phase_L = {s['phases'][0]:.6g}  flights = "
                     f"{s['flight_times'][0]:.6g}, {s['flight_times'][1]:.6g}")
    if sols:
        lines.append(LEGEND_1TO1)
    return "\n".join(lines)


def text_walls(d: dict) -> str:
    """A reader's form of ``run_walls``'s object."""
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
    if sols:
        lines.append(IMPACT_LEGEND)
    return "\n".join(lines)
