"""``vines periodic``: the 1:1 orbits of the map P2 o P1 at one parameter point."""
from __future__ import annotations

import argparse

from .common import VinesArgumentParser, add_model_args, emit, model_params, quiet_stdout

NAME = "periodic"

#: keys of each orbit in the JSON output
ORBIT_KEYS = ("symmetric", "admissible", "stable", "lambda_max", "eigenvalues", "dw_L", "dw_R",
              "phase_L", "phase_R", "flight_times")


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="1:1 periodic orbits from the impact maps, with admissibility and stability",
        description="Solve P2(P1(x_L)) = x_L + (0, 0, 0, T) for every 1:1 orbit reachable from "
                    "the built-in seeds (symmetric closed form, flight-time scan, short "
                    "simulation) and report admissibility and the eigenvalues of J_P2 J_P1.",
    )
    add_model_args(p)
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (key: solutions)")
    return p


def run(args: argparse.Namespace) -> int:
    params = model_params(args)
    from ..orbits.periodic import orbits_1to1

    with quiet_stdout():
        orbits = orbits_1to1(params)
    sols = [{k: o.to_dict()[k] for k in ORBIT_KEYS} for o in orbits]
    return emit(args.json, {"solutions": sols, "params": params.as_dict()}, _text)


def _text(d: dict) -> str:
    p, sols = d["params"], d["solutions"]
    lines = [f"eta = {p['eta']:g}, omega = {p['omega']:g}, F = {p['F']:g}: "
             f"{len(sols)} 1:1 solution(s)"]
    for s in sols:
        family = "symmetric" if s["symmetric"] else "asymmetric"
        adm = "admissible" if s["admissible"] else "NOT admissible"
        st = "stable" if s["stable"] else "unstable"
        lines.append(f"  {family:10s} {adm:14s} {st:8s} |lambda_max| = {s['lambda_max']:.6g}  "
                     f"dw_L = {s['dw_L']:.6g}  dw_R = {s['dw_R']:.6g}  "
                     f"phase_L = {s['phase_L']:.6g}  flights = "
                     f"{s['flight_times'][0]:.6g}, {s['flight_times'][1]:.6g}")
    return "\n".join(lines)
