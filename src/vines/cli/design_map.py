"""``vines design-map``: who wins where, the best VI NES against the TMD of the same mass,
free and at equal travel, over mass ratio, band and amplitude span
(``studies.design_map``, docs/design.md "Who wins where").

Every value is read as a string and validated by ``studies.design_map.check_map``; a
ParameterError names its flag through ``FLAG_OF``.
"""
from __future__ import annotations

import argparse

from ..core.params import D_DEFAULT, ParameterError
from ..studies import design_map as dm
from .common import VinesArgumentParser, emit, quiet_stdout

NAME = "design-map"

#: name of the ParameterError raised by studies.design_map -> its flag
FLAG_OF = {"eta": "--eta-range", "half_width": "--half-width", "span": "--span",
           "restitution": "--restitution", "n_amplitudes": "--n-amplitudes",
           "amplitude_max_m": "--amplitude-max", "d": "--d", "n_omega": "--n-omega",
           "n_clearance": "--n-clearance", "n_omega_exact": "--n-omega-exact",
           "frontier_factor": "--frontier-factor", "exact_sample": "--exact-sample",
           "seed": "--seed", "t_end": "--t-end", "t_transient": "--t-transient",
           "n_workers": "--workers"}
MODELS = ("both", "slowflow")


def _nums(values) -> str:
    return " ".join(f"{v:g}" for v in values)


def add_parser(subparsers) -> VinesArgumentParser:
    """The ``design-map`` sub-parser."""
    p = subparsers.add_parser(
        NAME,
        help="who wins where: the best VI NES against the equal-mass TMD (free and at "
             "equal travel) over mass ratio, band and amplitude span",
        description="Per cell (eta, band half width h, amplitude span A_max/A_min): the "
                    "slow flow's best VI NES (clearance and restitution optimised), the "
                    "band-optimal TMD of the same mass, free and with its travel limited "
                    "to the VI NES's clearance at A_max, and the ratios of their worst "
                    "x_max/A over the band [1 - h, 1 + h] (> 1: the TMD wins). With --model "
                    "both the exact solver checks every cell near the frontier (a ratio "
                    "within --frontier-factor of 1) and a seeded sample of the others.")
    g = p.add_argument_group("the map's axes")
    lo, hi, n = dm.ETA_DEFAULT
    g.add_argument("--eta-range", nargs=3, metavar=("A", "B", "N"), default=[lo, hi, n],
                   help=f"N mass ratios log-spaced from A to B [0 < A < B <= 0.5, integer "
                        f"N >= 1; default {lo:g} {hi:g} {n}]")
    g.add_argument("--half-width", nargs="+", metavar="H",
                   default=list(dm.HALF_WIDTH_DEFAULT),
                   help=f"band half widths: omega in [1 - H, 1 + H] [0 < H < "
                        f"{dm.HALF_WIDTH_MAX:g}; default {_nums(dm.HALF_WIDTH_DEFAULT)}]")
    g.add_argument("--span", nargs="+", metavar="S", default=list(dm.SPAN_DEFAULT),
                   help=f"amplitude spans A_max/A_min [1 <= S <= 1000; default "
                        f"{_nums(dm.SPAN_DEFAULT)}]")
    g.add_argument("--restitution", nargs="+", metavar="R",
                   default=list(dm.RESTITUTION_DEFAULT),
                   help=f"restitutions searched [0 <= R <= 0.99; default "
                        f"{_nums(dm.RESTITUTION_DEFAULT)}]")
    s = p.add_argument_group("structure and amplitudes")
    s.add_argument("--d", metavar="D", default=D_DEFAULT,
                   help=f"LO damping c/(M w0) [>= 0; default {D_DEFAULT:.6f}]")
    s.add_argument("--n-amplitudes", metavar="N", default=dm.N_AMPLITUDES_DEFAULT,
                   help=f"amplitudes of a span > 1, log-spaced [2..20; default "
                        f"{dm.N_AMPLITUDES_DEFAULT}]")
    s.add_argument("--amplitude-max", metavar="M", default=dm.AMPLITUDE_MAX_M_DEFAULT,
                   help=f"largest base amplitude in m (scale only) [0 < M <= 1; default "
                        f"{dm.AMPLITUDE_MAX_M_DEFAULT:g}]")
    m = p.add_argument_group("models and resolution")
    m.add_argument("--model", choices=MODELS, default="both",
                   help="slowflow: the slow flow alone; both: also the exact check "
                        "[default both]")
    m.add_argument("--n-omega", metavar="N", default=dm.N_OMEGA_DEFAULT,
                   help=f"slow flow's band grid [default {dm.N_OMEGA_DEFAULT}]")
    m.add_argument("--n-clearance", metavar="N", default=dm.N_CLEARANCE_DEFAULT,
                   help=f"slow flow's clearance grid [default {dm.N_CLEARANCE_DEFAULT}]")
    m.add_argument("--n-omega-exact", metavar="N", default=dm.N_OMEGA_EXACT_DEFAULT,
                   help=f"exact check's band grid [default {dm.N_OMEGA_EXACT_DEFAULT}]")
    m.add_argument("--frontier-factor", metavar="X", default=dm.FRONTIER_FACTOR_DEFAULT,
                   help=f"cells with a ratio within this factor of 1 are checked [>= 1; "
                        f"default {dm.FRONTIER_FACTOR_DEFAULT:g}]")
    m.add_argument("--exact-sample", metavar="P", default=dm.EXACT_SAMPLE_DEFAULT,
                   help=f"probability that another cell is checked [0..1; default "
                        f"{dm.EXACT_SAMPLE_DEFAULT:g}]")
    m.add_argument("--seed", metavar="S", default=0, help="seed of the sample [default 0]")
    m.add_argument("--no-refine", action="store_true",
                   help="no local search of the clearance in the exact check")
    m.add_argument("--t-end", metavar="T", default=dm.T_END_DEFAULT,
                   help=f"exact runs' end time [default {dm.T_END_DEFAULT:g}]")
    m.add_argument("--t-transient", metavar="T", default=dm.T_TRANSIENT_DEFAULT,
                   help=f"exact runs' window start [default {dm.T_TRANSIENT_DEFAULT:g}]")
    p.add_argument("--workers", metavar="N", default=1,
                   help="processes computing cells (the numbers do not depend on it) "
                        "[1..4096; default 1]")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: model, inputs, axes, cells, "
                        "summary)")
    return p


def spec_of(args: argparse.Namespace) -> dm.MapSpec:
    """The validated map of the arguments; ParameterError naming a flag's name."""
    a, b, n = args.eta_range
    return dm.check_map(
        eta=dm.log_axis("eta", a, b, n), half_width=args.half_width, span=args.span,
        restitution=args.restitution, n_amplitudes=args.n_amplitudes,
        amplitude_max_m=args.amplitude_max, d=args.d, n_omega=args.n_omega,
        n_clearance=args.n_clearance, n_omega_exact=args.n_omega_exact,
        frontier_factor=args.frontier_factor, exact_sample=args.exact_sample,
        seed=args.seed, exact_refine=not args.no_refine, exact_check=args.model == "both",
        t_end=args.t_end, t_transient=args.t_transient)


def compute(args: argparse.Namespace) -> dict:
    """The JSON object; ParameterError on bad input."""
    try:
        spec = spec_of(args)
    except ParameterError as err:
        if err.name == "half_width":
            raise ParameterError("half_width", " ".join(map(str, args.half_width)),
                                 f"must be distinct numbers 0 < H < {dm.HALF_WIDTH_MAX:g}: "
                                 "the band [1 - H, 1 + H] holds the host frequency 1 and "
                                 "stays above 0") from None
        raise
    with quiet_stdout():
        cells = dm.map_cells(spec, n_workers=args.workers)
    arrays = dm.assemble(spec, cells)
    return dict(model=args.model, inputs=spec.to_dict(),
                axes=dict(eta=list(spec.eta), half_width=list(spec.half_width),
                          span=list(spec.span)),
                cells=[_cell_json(c) for c in cells], summary=dm.summary(spec, arrays))


def _cell_json(c: dict) -> dict:
    out = {k: c[k] for k in ("eta", "half_width", "span", "ratio", "ratio_equal_travel",
                             "max_travel")}
    out["vines"] = {k: v for k, v in c["vines"].items()}
    out["tmd"], out["tmd_equal_travel"] = c["tmd"], c["tmd_equal_travel"]
    out["checked"] = {0: None, 1: "frontier", 2: "sample"}[c["confirm"]]
    out["exact"] = c["exact"]
    return out


def run(args: argparse.Namespace) -> int:
    return emit(args.json, compute(args), text)


def text(d: dict) -> str:
    """One line per cell and the summary, for a reader."""
    lines = [f"design map ({d['model']}): VI NES / TMD worst x_max/A (> 1: TMD wins); "
             "exact where checked"]
    lines.append(f"{'eta':>8} {'h':>5} {'span':>5} {'L/A_max':>8} {'r':>5} {'VI NES':>8} "
                 f"{'TMD':>7} {'TMD(L)':>7} {'ratio':>6} {'ratio(L)':>8} {'exact':>8}")
    for c in d["cells"]:
        v, ex = c["vines"], c["exact"]
        L = v["clearance_m"] / d["inputs"]["amplitude_max_m"]
        lines.append(f"{c['eta']:8.4g} {c['half_width']:5.3g} {c['span']:5.3g} {L:8.3g} "
                     f"{v['restitution']:5.2g} {v['worst_ratio']:8.4g} "
                     f"{c['tmd']['worst_ratio']:7.4g} "
                     f"{c['tmd_equal_travel']['worst_ratio']:7.4g} {c['ratio']:6.3g} "
                     f"{c['ratio_equal_travel']:8.3g} "
                     f"{'-' if ex is None else format(ex['worst_ratio_refined'], '8.4g'):>8}")
    s = d["summary"]
    lines.append(f"{s['n_cells']} cells; exact checks: {s['n_frontier']} near the frontier, "
                 f"{s['n_sample']} sampled; VI NES wins (by > 5 %) {s['vines_wins']} against "
                 f"the free TMD, {s['vines_wins_equal_travel']} at equal travel; the models "
                 f"name opposite winners at {s['verdict_differs']} and "
                 f"{s['verdict_differs_equal_travel']}")
    return "\n".join(lines)
