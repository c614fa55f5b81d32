"""``vines simulate``: exact event-driven simulation of one parameter point."""
from __future__ import annotations

import argparse
import math

from ..core.params import (
    MAX_IMPACTS_DEFAULT,
    MAX_IMPACTS_MAX,
    RTOL_DEFAULT,
    RTOL_MAX,
    RTOL_MIN,
    T_END_DEFAULT,
    T_END_MAX,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    V_STICK_MAX,
    SolverSettings,
    check_real,
)
from ..solvers import SOLVERS
from .common import VinesArgumentParser, add_model_args, emit, model_params, quiet_stdout

NAME = "simulate"


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME,
        help="exact event-driven simulation: KE ratio, x_max and regime of one parameter point",
        description="Simulate the VI NES from rest and report the energy-transfer measures "
                    "over the window [t_transient, t_end] (exact time averages).",
    )
    add_model_args(p, phi=True, optional_group="model parameters (required unless --model)")
    p.add_argument("--model", metavar="FILE", default=None,
                   help="simulate the host with several degrees of freedom and absorbers of "
                        "this model file instead (YAML; docs/usage.md, 'A host with several "
                        "modes'; exact solver; --eta, --omega, --F, --r, --d, --phi do not "
                        "apply)")
    run = p.add_argument_group("run and solver settings")
    run.add_argument("--t-end", metavar="T", default=T_END_DEFAULT,
                     help=f"end of the run, dimensionless time [> 0 and <= {T_END_MAX:g}; "
                          f"default {T_END_DEFAULT:g}]")
    run.add_argument("--t-transient", metavar="T0", default=T_TRANSIENT_DEFAULT,
                     help="start of the measurement window [>= 0 and < t-end; "
                          f"default {T_TRANSIENT_DEFAULT:g}]")
    run.add_argument("--solver", choices=SOLVERS, default="exact",
                     help="exact: closed-form event-driven flow (default); rk: general-purpose "
                          "ODE solver with event location (reference)")
    run.add_argument("--rtol", metavar="X", default=RTOL_DEFAULT,
                     help=f"relative tolerance of the rk solver [{RTOL_MIN:g} <= X <= {RTOL_MAX:g}; "
                          f"default {RTOL_DEFAULT:g}]")
    run.add_argument("--v-stick", metavar="V", default=V_STICK_DEFAULT,
                     help="chatter threshold on the post-impact relative velocity below which "
                          f"ball and LO stick [>= 0 and <= {V_STICK_MAX:g}; default {V_STICK_DEFAULT:g}]")
    run.add_argument("--max-impacts", metavar="N", default=MAX_IMPACTS_DEFAULT,
                     help=f"stop after this many impacts (the run is then reported with status "
                          f"max_impacts and regime unfinished) [integer >= 1 and <= "
                          f"{MAX_IMPACTS_MAX}; default {MAX_IMPACTS_DEFAULT}]")
    run.add_argument("--no-periodic-shortcut", dest="periodic_shortcut", action="store_false",
                     help="integrate to t-end even after the motion has settled on a periodic "
                          "orbit (default: complete the run from one period of the orbit, "
                          "exact to ~1e-10; JSON key shortcut_time says when; exact solver "
                          "only)")
    p.set_defaults(parser=p)
    p.allowed_values.update({
        "--t-end": f"a number > 0 and <= {T_END_MAX:g}",
        "--t-transient": "a number >= 0 and < t-end",
        "--rtol": f"a number >= {RTOL_MIN:g} and <= {RTOL_MAX:g}",
        "--v-stick": f"a number >= 0 and <= {V_STICK_MAX:g}",
        "--max-impacts": f"an integer >= 1 and <= {MAX_IMPACTS_MAX}",
    })
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: docs/usage.md, 'The simulate "
                        "command'; every command's options: docs/cli.md)")
    return p


def run(args: argparse.Namespace) -> int:
    if args.model is not None:
        return _run_model(args)
    missing = [f for f in ("--eta", "--omega", "--F") if getattr(args, f[2:]) is None]
    if missing:   # argparse's own message, as when these flags were required
        args.parser.error("the following arguments are required: " + ", ".join(missing))
    params = model_params(args)
    settings = SolverSettings(t_end=args.t_end, t_transient=args.t_transient,
                              v_stick=args.v_stick, max_impacts=args.max_impacts)
    rtol = check_real("rtol", args.rtol, lo=RTOL_MIN, hi=RTOL_MAX)   # as vines.simulate
    from ..solvers import run_simulation

    with quiet_stdout():
        result = run_simulation(params, settings, solver=args.solver, rtol=rtol,
                                periodic_shortcut=args.periodic_shortcut,
                                keep_impacts=False)   # memory bounded in t_end
    return emit(args.json, result.to_dict(), lambda d: _table(d).rstrip("\n"))


def _table(d: dict) -> str:
    p = d.get("params", {})

    def num(x, fmt):
        if x is None or (isinstance(x, float) and not math.isfinite(x)):
            return "n/a"
        return format(x, fmt)

    head = (f"eta = {p.get('eta')!s}, omega = {p.get('omega')!s}, F = {p.get('F')!s}, "
            f"window [{p.get('t_transient')!s}, {p.get('t_end')!s}], solver {d.get('solver')}")
    rows = [
        ("ke_ratio", num(d.get("ke_ratio"), ".6g")),
        ("xmax [m]", num(d.get("xmax_m"), ".6g")),
        ("xmax whole run [m]", num(d.get("xmax_whole_run_m"), ".6g")),
        ("regime", str(d.get("regime"))),
        ("impacts per period", num(d.get("impacts_per_period"), ".4g")),
        ("t_stuck", num(d.get("t_stuck"), ".6g")),
        ("status", str(d.get("status"))),
        ("periodic shortcut from t", num(d.get("shortcut_time"), ".6g")),
    ]
    width = max(len(k) for k, _ in rows)
    return head + "\n" + "".join(f"  {k:<{width}}  {v}\n" for k, v in rows)


def _run_model(args: argparse.Namespace) -> int:
    """``--model FILE``: the general engine (``vines.simulate_model``)."""
    from ..multimode import ModelSettings, read_model, simulate_model

    given = [f for f in ("eta", "omega", "F") if getattr(args, f, None) is not None]
    if given:
        args.parser.error(f"argument --{given[0]}: not allowed with --model (the model file "
                          "holds the model)")
    if args.solver != "exact":
        args.parser.error("argument --solver: --model runs the exact solver only")
    model = read_model(args.model)
    settings = ModelSettings(t_end=args.t_end, t_transient=args.t_transient,
                             v_stick=args.v_stick, max_impacts=args.max_impacts, n_record=4096)
    with quiet_stdout():
        result = simulate_model(model, settings)
    out = result.summary()
    out["model"] = model.to_dict()
    return emit(args.json, out, lambda d: _model_table(d).rstrip("\n"))


def _model_table(d: dict) -> str:
    h = d["host"]
    lines = [f"window [{d['window'][0]:g}, {d['window'][1]:g}], status {d['status']}"]
    for j, (x, a) in enumerate(zip(h["x_max"], h["accel_max"], strict=True)):
        lines.append(f"  host dof {j}: x_max {x:.6g}, acceleration max {a:.6g}")
    lines.append(f"  host damping dissipated {h['dissipated_damping']:.6g}, forcing work "
                 f"{h['forcing_work']:.6g}")
    for i, a in enumerate(d["absorbers"]):
        lines.append(f"  absorber {i} ({a['kind']} on dof {a['dof']}): travel {a['travel']:.6g}, "
                     f"ke_ratio {a['ke_ratio']:.6g}, dissipated damper {a['dissipated_damper']:.6g} "
                     f"impacts {a['dissipated_impacts']:.6g}, {a['n_impacts']} impacts, "
                     f"regime {a['regime']}")
    return "\n".join(lines) + "\n"
