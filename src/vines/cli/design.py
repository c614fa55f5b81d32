"""``vines design``: choose (or judge) a VI NES for a frequency band and base amplitudes.

Every value is read as a string and validated by ``vines.design`` itself, so the CLI and the
API accept the same values; a ParameterError names its flag through ``FLAG_OF``.
"""
from __future__ import annotations

import argparse

from ..core.params import T_END_DEFAULT, T_TRANSIENT_DEFAULT
from ..studies.design_checks import (
    CENSUS_N_DEFAULT,
    DEFAULT_AMPLITUDES_M,
    DEFAULT_BAND,
    DEFAULT_N_OMEGA,
    N_CLEARANCE_DEFAULT,
    N_ETA_DEFAULT,
    VIEW_NAMES,
)
from . import design_uncertainty
from .common import VinesArgumentParser, add_structure_args, emit, quiet_stdout

NAME = "design"

#: name of the ParameterError raised by vines.design -> its flag (for the CLI's messages)
FLAG_OF = {"omega_band": "--omega-band", "n_omega": "--n-omega", "amplitude": "--amplitude",
           "M": "--M", "k": "--k", "c": "--c", "d": "--d", "r": "--r", "eta": "--eta",
           "clearance": "--clearance", "eta_max": "--eta-max",
           "clearance_range": "--clearance-range", "n_eta": "--n-eta",
           "n_clearance": "--n-clearance", "view": "--view", "census_n": "--census-n",
           "n_threads": "--threads", "t_end": "--t-end", "t_transient": "--t-transient"}


def add_parser(subparsers) -> VinesArgumentParser:
    """The ``design`` sub-parser."""
    p = subparsers.add_parser(
        NAME,
        help="choose a VI NES (ball mass ratio, clearance) for a frequency band and base "
             "amplitudes, against the LO alone and the optimal TMD of the same mass",
        description="Worst-case transmissibility x_max/A over the band omega = w/w0 and the "
                    "base amplitudes, from rest and over every attractor holding >= 1 % of "
                    "a census's states, for a given design (--eta, --clearance) or the best "
                    "one with eta <= --eta-max (grid over eta and log clearance, then a "
                    "compass search). References: the LO alone and the TMD of mass ratio "
                    "eta (eta-max) tuned for the same worst case (closed form).")
    band = p.add_argument_group("excitation")
    band.add_argument("--omega-band", nargs=2, metavar=("LO", "HI"),
                      default=list(DEFAULT_BAND),
                      help=f"band of omega = w/w0 [0 < LO < HI <= 1000; default "
                           f"{DEFAULT_BAND[0]:g} {DEFAULT_BAND[1]:g}]")
    band.add_argument("--n-omega", metavar="N", default=DEFAULT_N_OMEGA,
                      help="grid points over the band [an integer >= 2; default "
                           f"{DEFAULT_N_OMEGA}]")
    band.add_argument("--amplitude", nargs="+", metavar="A",
                      default=list(DEFAULT_AMPLITUDES_M),
                      help="base amplitudes in metres [numbers > 0; default "
                           + " ".join(f"{a:g}" for a in DEFAULT_AMPLITUDES_M) + "]")
    add_structure_args(p)
    des = p.add_argument_group("design: --eta with --clearance (evaluate) or --eta-max "
                               "(optimise)")
    des.add_argument("--eta", metavar="E", default=None, help="ball-to-LO mass ratio m/M")
    des.add_argument("--clearance", metavar="L", default=None,
                     help="clearance in metres: half the cavity length (Table 1: 0.015)")
    des.add_argument("--eta-max", metavar="E", default=None,
                     help="optimise with 0 < eta <= E; also the TMD's mass ratio")
    des.add_argument("--clearance-range", nargs=2, metavar=("LO", "HI"), default=None,
                     help="clearances searched, metres [default: A_max/2 .. 100 A_min]")
    des.add_argument("--n-eta", metavar="N", default=N_ETA_DEFAULT,
                     help=f"grid points in eta [default {N_ETA_DEFAULT}]")
    des.add_argument("--n-clearance", metavar="N", default=N_CLEARANCE_DEFAULT,
                     help=f"grid points in log clearance [default {N_CLEARANCE_DEFAULT}]")
    run = p.add_argument_group("attractor view and runs")
    run.add_argument("--view", choices=VIEW_NAMES, default="t_end",
                     help="census view of worst_ratio_any_attractor; the only one is "
                          "t_end: the attractor each state is on at t-end [default t_end]")
    run.add_argument("--census-n", metavar="N", default=CENSUS_N_DEFAULT,
                     help="initial states per census, 0 to skip the view [default "
                          f"{CENSUS_N_DEFAULT}]")
    run.add_argument("--t-end", metavar="T", default=T_END_DEFAULT,
                     help=f"length of every run [default {T_END_DEFAULT:g}]")
    run.add_argument("--t-transient", metavar="T0", default=T_TRANSIENT_DEFAULT,
                     help=f"start of the x_max window [default {T_TRANSIENT_DEFAULT:g}]")
    run.add_argument("--threads", metavar="N", default=None,
                     help="threads [an integer >= 1; default: all cores]")
    add_mistuning_args(p)
    design_uncertainty.add_args(p)
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: inputs, curves, lo_alone, "
                        "tmd, vines, search, worst_case, cost, mistuning; with "
                        "--uncertainty: uncertainty)")
    add_model_choice(p)
    return p


# --------------------------------------------------------------------------- --model
MODELS = ("exact", "slowflow", "both")


def add_model_choice(p: VinesArgumentParser) -> None:
    """--model: the exact answer (default), the slow flow's (docs/slowflow.md) or both."""
    p.add_argument("--model", choices=MODELS, default="exact",
                   help="exact: simulations (default); slowflow: the averaged slow flow, a "
                        "first pass in under a second (keys: model, inputs, vines, optimal "
                        "or search, lo_alone, cost); both: the exact object with keys "
                        "slowflow and difference (slow flow minus exact)")


def with_model(args: argparse.Namespace, exact) -> dict:
    """The answer of --model: ``exact()`` (the exact object), the slow flow's, or both."""
    if args.model == "exact":
        return exact()
    from ..studies.design_slowflow import difference, slowflow_design
    with quiet_stdout():
        slow = slowflow_design(omega_band=args.omega_band, amplitudes_m=args.amplitude,
                               M_kg=args.M, k_N_per_m=args.k, c_Ns_per_m=args.c, d=args.d,
                               r=args.r, eta=args.eta, clearance_m=args.clearance,
                               eta_max=args.eta_max, clearance_range_m=args.clearance_range,
                               n_eta=args.n_eta)
    if args.model == "slowflow":
        return slow
    d = exact()
    return d | {"slowflow": slow, "difference": difference(d, slow)}


def text_slowflow(d: dict) -> str:
    """A reader's summary of the slow flow's design."""
    v, i = d["vines"], d["inputs"]
    lines = [f"slow flow, band omega {i['omega_band'][0]:g}-{i['omega_band'][1]:g}, "
             f"{i['mode']}",
             f"  LO alone: worst x_max/A {_fmt(d['lo_alone']['worst_ratio'])}",
             f"  VI NES eta {v['eta']:.4g}, clearance {1e3 * v['clearance_m']:.4g} mm: worst "
             f"{_fmt(v['worst_ratio'])} at omega {v['worst_omega']:.4g}"]
    if "optimal" in d:
        o = d["optimal"]
        lines.append(f"  best clearance for eta {o['eta']:.4g}: {1e3 * o['clearance_m']:.4g} "
                     f"mm, worst {_fmt(o['worst_ratio'])}")
    lines += [f"  warning: {w}" for w in v.get("warnings", [])]
    lines.append(f"  cost {d['cost']['wall_s']:.3f} s")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    return emit(args.json, with_model(args, lambda: compute(args)), text)


# --------------------------------------------------------------------------- mistuning

def add_mistuning_args(p) -> None:
    """--mistuning D (host frequency (1 + delta) w0, |delta| <= D), --n-delta, --robust."""
    from ..studies.mistuning import N_DELTA_DEFAULT, N_SEARCH_DEFAULT
    g = p.add_argument_group("mistuning: the host's natural frequency drifts to "
                             "(1 + delta) w0, absorbers and band fixed")
    g.add_argument("--mistuning", metavar="D", default=None,
                   help="evaluate the designs for delta in [-D, D] [0 <= D <= 0.5; "
                        "JSON key mistuning]")
    g.add_argument("--n-delta", metavar="N", default=N_DELTA_DEFAULT,
                   help=f"grid points in delta, odd [default {N_DELTA_DEFAULT}], then the "
                        "VI NES's worst refined")
    g.add_argument("--robust", action="store_true",
                   help="with --eta-max: also optimise the VI NES and re-tune the TMD for "
                        f"the worst case over delta ({N_SEARCH_DEFAULT} host frequencies "
                        "in the search)")


def checked_mistuning(args: argparse.Namespace):
    """--mistuning's values validated before any run (None when not asked)."""
    from ..core.params import ParameterError
    from ..studies.mistuning import check_mistuning
    if args.mistuning is None:
        if args.robust:
            raise ParameterError("robust", True, "give --mistuning D with it")
        return None
    if args.robust and args.eta_max is None:
        raise ParameterError("robust", True, "optimises a design: give --eta-max with it")
    return check_mistuning(args.mistuning, args.n_delta)


def add_mistuning(d: dict, res, args: argparse.Namespace, checked) -> dict:
    """``d`` with the key ``mistuning`` (None when not asked)."""
    d["mistuning"] = None
    if checked is not None:
        from ..studies.mistuning import mistuning
        with quiet_stdout():
            d["mistuning"] = mistuning(res, checked[0], n_delta=checked[1],
                                       robust=args.robust,
                                       n_threads=res.cost["n_threads"])
    return d


def compute(args: argparse.Namespace) -> dict:
    """The design's JSON object (``DesignResult.to_dict``); ParameterError on bad input."""
    from ..studies.design import design
    mis = checked_mistuning(args)
    design_uncertainty.precheck(args)
    with quiet_stdout():
        res = design(omega_band=args.omega_band, n_omega=args.n_omega,
                     amplitudes_m=args.amplitude, M_kg=args.M, k_N_per_m=args.k,
                     c_Ns_per_m=args.c, d=args.d, r=args.r, eta=args.eta,
                     clearance_m=args.clearance, eta_max=args.eta_max,
                     clearance_range_m=args.clearance_range, n_eta=args.n_eta,
                     n_clearance=args.n_clearance, view=args.view, census_n=args.census_n,
                     t_end=args.t_end, t_transient=args.t_transient, n_threads=args.threads)
        out = res.to_dict()
        # uncertain parts (studies.uncertainty)
        uncertain = design_uncertainty.compute(args, res)
    if uncertain is not None:
        out["uncertainty"] = uncertain
    return add_mistuning(out, res, args, mis)


def _fmt(x) -> str:
    return "n/a" if x is None else f"{x:.3g}"


def _mm(x) -> str:
    return "n/a" if x is None else f"{1e3 * x:.3g} mm"


def _stroke(t: dict) -> str:
    """', stroke ... (LO x_max ...)' of a TMD object at the largest amplitude."""
    if "stroke_m" not in t:
        return ""
    return (f", stroke |u - x| {_mm(t['stroke_m'])} and LO x_max {_mm(t['x_max_m'])} at "
            "the largest amplitude")


def tmd_equal_travel_text(t: dict | None, v: dict) -> list:
    """The line of the TMD at equal travel (none for an object without it)."""
    if t is None:
        return ["  TMD at equal travel: no tuning keeps the stroke within the clearance"] \
            if v.get("stroke_m") is not None else []
    if not t["binding"]:
        return [f"  TMD at equal travel (stroke <= L = {_mm(t['max_stroke_m'])}): the TMD "
                "above (its stroke is within L)"]
    return [f"  TMD at equal travel (stroke <= L = {_mm(t['max_stroke_m'])}): f = "
            f"{t['frequency_ratio']:.4f}, zeta = {t['damping_ratio']:.4f}: worst "
            f"{_fmt(t['worst_ratio'])}{_stroke(t)}"]


def text(d: dict) -> str:
    """A reader's summary of ``run``'s object."""
    if d.get("model") == "slowflow":
        return text_slowflow(d)
    if "slowflow" in d:
        diff = d["difference"]
        return "\n".join([text({k: x for k, x in d.items() if k not in ("slowflow", "difference")}), text_slowflow(d["slowflow"]),
                          f"  slow flow minus exact: worst ratio {diff['worst_ratio']:+.4g} "
                          f"({100 * diff['worst_ratio_relative']:+.1f} %), "
                          f"{diff['speedup']:.3g}x faster"])
    v, t, lo = d["vines"], d["tmd"], d["lo_alone"]
    lines = [f"band omega {d['inputs']['omega_band'][0]:g}-{d['inputs']['omega_band'][1]:g}"
             f" ({d['inputs']['n_omega']} points), {d['inputs']['mode']}",
             f"  LO alone: worst x_max/A {_fmt(lo['worst_ratio'])}"
             + (f", x_max {_mm(lo['x_max_m'])} at the largest amplitude"
                if lo.get("x_max_m") is not None else ""),
             f"  TMD  eta {t['eta']:g}: f = {t['frequency_ratio']:.4f}, zeta = "
             f"{t['damping_ratio']:.4f}: worst {_fmt(t['worst_ratio'])}{_stroke(t)}",
             *tmd_equal_travel_text(d.get("tmd_equal_travel"), v),
             f"  VI NES eta {v['eta']:.4g}, clearance {1e3 * v['clearance_m']:.4g} mm: worst "
             f"{_fmt(v['worst_ratio'])} from rest, {_fmt(v['worst_ratio_any_attractor'])} over "
             f"attractors ({v['view'] or 'not evaluated'}); ball travel +-L = "
             f"{_mm(v.get('stroke_m'))} relative to the LO, LO x_max {_mm(v.get('x_max_m'))} "
             "from rest"]
    any_ = v["worst_ratio_any_attractor_per_amplitude"] or [None] * len(v["F"])
    for A, F, w, a in zip(d["curves"]["amplitude_m"], v["F"], v["worst_ratio_per_amplitude"],
                          any_, strict=True):
        lines.append(f"    A = {1e3 * A:.4g} mm (F = {F:.4g}): {_fmt(w)} from rest, "
                     f"{_fmt(a)} over attractors")
    lines.append(_cost_text(d))
    lines += design_uncertainty.text(d.get("uncertainty"))
    return "\n".join(lines + mistuning_text(d.get("mistuning")))


def _cost_text(d: dict) -> str:
    """The cost line: the design's runs, and the parts added by --uncertainty and
    --mistuning with the total."""
    c = d["cost"]
    text = (f"  cost {c['wall_s']:.1f} s for the design ({c['n_runs_from_rest']} runs from "
            f"rest, {c['n_runs_census']} census runs)")
    extra = [(name, blk["cost"]["wall_s"]) for name in ("uncertainty", "mistuning")
             if isinstance(blk := d.get(name), dict) and "wall_s" in blk.get("cost", {})]
    if not extra:
        return text
    parts = ", ".join(f"{name} {s:.1f} s" for name, s in extra)
    return f"{text}, {parts}: {c['wall_s'] + sum(s for _, s in extra):.1f} s in all"


def mistuning_text(m: dict | None) -> list:
    """Lines of the worst cases over the host's drift (none when not asked)."""
    if m is None:
        return []
    n_grid = m.get("n_delta", len(m["delta"]))
    lines = [f"  mistuning |delta| <= {m['D']:g} ({len(m['delta'])} host frequencies: a grid "
             f"of {n_grid} and {len(m['delta']) - n_grid} added where the VI NES's worst "
             "case was refined):"]
    for name, blk in (("nominal designs", m), ("robust designs", m["robust"])):
        if blk is None:
            continue
        w, v = blk["worst"], blk["design"]["vines"]
        lines.append(f"    {name}: worst LO alone {_fmt(w['lo_alone'])}, TMD (f = "
                     f"{blk['design']['tmd']['frequency_ratio']:.4f}) {_fmt(w['tmd'])}, "
                     f"VI NES (eta {v['eta']:.4g}, {1e3 * v['clearance_m']:.4g} mm) "
                     f"{_fmt(w['vines'])} from rest, {_fmt(w['vines_any_attractor'])} over "
                     "attractors")
    if m.get("tmd_stroke_m") is not None:
        lines.append(f"    TMD stroke over the drift {_mm(m['tmd_stroke_m'])}")
    eq = m.get("tmd_equal_travel")
    if eq is not None:
        lines.append(f"    TMD at equal travel (f = {eq['design']['frequency_ratio']:.4f}, "
                     f"zeta = {eq['design']['damping_ratio']:.4f}): worst "
                     f"{_fmt(eq['worst'])} over the drift, stroke {_mm(eq['stroke_m'])} "
                     f"(L = {_mm(eq['max_stroke_m'])} at delta = 0)")
    return lines
