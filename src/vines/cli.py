"""Command-line interface: ``vines <command> ...`` (also ``python -m vines``).

Contract (see the README and the project specification, section 7):

* ``--json`` prints exactly one JSON object on stdout (NaN and infinities become null).
* Bad input of any kind (a non-number, a value out of range, an unknown flag, a missing
  required flag, a bad choice) exits with status 2 after printing exactly one line
  ``vines <command>: error: <message>`` on stderr, naming the parameter, the value given and
  what is allowed. No traceback, no output file.
* Unexpected internal errors are not caught: they keep their traceback.

Every number is read as a string and validated by the same code the Python API uses
(``vines.params``), so the CLI and the API accept exactly the same values.

Adding a command: write ``_add_<name>(subparsers)`` that builds its sub-parser (reusing
``_add_model_args`` for eta/omega/F/r/d) and sets ``handler=_cmd_<name>``, then list it in
``_COMMANDS``.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
from collections.abc import Sequence
from typing import NoReturn

from . import __version__
from .core.params import (
    BRANCH_KINDS,
    CONTINUATION_METHODS,
    D_DEFAULT,
    MAX_IMPACTS_DEFAULT,
    MAX_IMPACTS_MAX,
    MAX_INADMISSIBLE_DEFAULT,
    MAX_POINTS_DEFAULT,
    MAX_POINTS_MAX,
    PARAM_BOUNDS,
    PARAM_NAMES,
    R_DEFAULT,
    RTOL_DEFAULT,
    RTOL_MAX,
    RTOL_MIN,
    T_END_DEFAULT,
    T_END_MAX,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    V_STICK_MAX,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_int,
    check_real,
    check_step_points,
)
from .core.simulation import SOLVERS

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


def _param_allowed(name: str) -> str:
    """Allowed values of a model parameter, from ``PARAM_BOUNDS`` (e.g. 'a number > 0 and <= 1000')."""
    lo, lo_open, hi = PARAM_BOUNDS[name]
    if name == "phi":
        return f"a number with |phi| <= {hi:g}"
    if lo == 0.0 and hi == 1.0 and not lo_open:
        return "a number in [0, 1]"
    return f"a number {'>' if lo_open else '>='} {lo:g} and <= {hi:g}"


def _flag_for(name: str) -> str:
    """Command-line flag of a parameter name used by ``vines.params`` (t_end -> --t-end)."""
    return "--" + name.replace("_", "-")


def _add_value(parser: VinesArgumentParser, flag: str, allowed: str, help: str, **kwargs):
    """Add an option taking one value (parsed as a string and validated later)."""
    parser.allowed_values[flag] = allowed
    metavar = kwargs.pop("metavar", flag.lstrip("-").upper().replace("-", "_"))
    parser.add_argument(flag, metavar=metavar, help=f"{help} [{allowed}]", **kwargs)


def _add_model_args(parser: VinesArgumentParser, *, phi: bool = False,
                    optional_group: str | None = None):
    """The model parameters eta, omega, F (required) and r, d (and phi) (optional).

    With ``optional_group`` (a group title) eta, omega and F default to None and are listed
    with r and d in that group; the command then checks which ones it needs.
    """
    required = optional_group is None
    req = parser.add_argument_group(optional_group or "model parameters (required)")
    for flag, allowed, help in (
        ("--eta", _param_allowed("eta"), "ball-to-LO mass ratio m/M"),
        ("--omega", _param_allowed("omega"), "forcing frequency ratio omega = w/w0"),
        ("--F", _param_allowed("F"), "forcing amplitude A/L"),
    ):
        parser.allowed_values[flag] = allowed
        kw = {"required": True} if required else {"default": None}
        req.add_argument(flag, metavar=flag.lstrip("-").upper(), help=f"{help} [{allowed}]",
                         **kw)
    opt = parser.add_argument_group("model parameters (optional)") if required else req
    parser.allowed_values["--r"] = _param_allowed("r")
    opt.add_argument("--r", metavar="R", default=R_DEFAULT,
                     help=f"coefficient of restitution [0 <= r <= 1; default {R_DEFAULT:g}]")
    parser.allowed_values["--d"] = _param_allowed("d")
    opt.add_argument("--d", metavar="D", default=D_DEFAULT,
                     help=f"LO damping c/(M w0), fixed for every eta "
                          f"[{_param_allowed('d')}; default {D_DEFAULT:.6f}]")
    if phi:
        parser.allowed_values["--phi"] = _param_allowed("phi")
        opt.add_argument("--phi", metavar="P", default=0.0,
                         help=f"forcing phase at t = 0 in rad [{_param_allowed('phi')}; default 0]")


def _model_params(args: argparse.Namespace) -> ModelParams:
    return ModelParams(eta=args.eta, omega=args.omega, F=args.F, r=args.r, d=args.d,
                       phi=getattr(args, "phi", 0.0))


# --------------------------------------------------------------------------- simulate

def _add_simulate(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        "simulate",
        help="exact event-driven simulation: KE ratio, x_max and regime of one parameter point",
        description="Simulate the VI NES from rest and report the energy-transfer measures "
                    "over the window [t_transient, t_end] (exact time averages).",
    )
    _add_model_args(p, phi=True)
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
    p.allowed_values.update({
        "--t-end": f"a number > 0 and <= {T_END_MAX:g}",
        "--t-transient": "a number >= 0 and < t-end",
        "--rtol": f"a number >= {RTOL_MIN:g} and <= {RTOL_MAX:g}",
        "--v-stick": f"a number >= 0 and <= {V_STICK_MAX:g}",
        "--max-impacts": f"an integer >= 1 and <= {MAX_IMPACTS_MAX}",
    })
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: see the README)")
    p.set_defaults(handler=_cmd_simulate)
    return p


def _simulate_inputs(args: argparse.Namespace) -> dict:
    """Validate every simulate option; return the keyword arguments of ``simulate``."""
    params = _model_params(args)
    settings = SolverSettings(t_end=args.t_end, t_transient=args.t_transient,
                              v_stick=args.v_stick,
                              max_impacts=args.max_impacts)
    rtol = check_real("rtol", args.rtol, lo=RTOL_MIN, hi=RTOL_MAX)   # as vines.simulate
    return dict(eta=params.eta, omega=params.omega, F=params.F, r=params.r, d=params.d,
                phi=params.phi, t_end=settings.t_end, t_transient=settings.t_transient,
                solver=args.solver, rtol=rtol, v_stick=settings.v_stick,
                max_impacts=settings.max_impacts, periodic_shortcut=args.periodic_shortcut,
                keep_impacts=False)


def _emit(as_json: bool, d: dict, text) -> int:
    """Print ``d`` as one JSON object, or ``text(d)`` for a reader; exit status 0."""
    sys.stdout.write((json.dumps(_jsonable(d), allow_nan=False) if as_json else text(d)) + "\n")
    sys.stdout.flush()
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    kwargs = _simulate_inputs(args)
    from .core import simulation  # imported lazily: argument errors never pay for the solver

    if args.json:
        # stdout carries the JSON object only; stray prints from the solver go to stderr.
        with contextlib.redirect_stdout(sys.stderr):
            result = simulation.simulate(**kwargs)
        sys.stdout.write(json.dumps(_jsonable(result.to_dict()), allow_nan=False) + "\n")
    else:
        result = simulation.simulate(**kwargs)
        sys.stdout.write(_simulate_table(result.to_dict()))
    sys.stdout.flush()
    return 0


def _simulate_table(d: dict) -> str:
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


def _jsonable(x):
    """Plain JSON types only; NaN and +-inf become None (null)."""
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if hasattr(x, "tolist") and not isinstance(x, (str, bytes)):  # numpy arrays and scalars
        return _jsonable(x.tolist())
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return x
    if isinstance(x, int):
        return int(x)
    if isinstance(x, float):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, complex):
        return [_jsonable(x.real), _jsonable(x.imag)]
    return str(x)


# --------------------------------------------------------------------------- periodic

def _add_periodic(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        "periodic",
        help="1:1 periodic orbits from the impact maps, with admissibility and stability",
        description="Solve P2(P1(x_L)) = x_L + (0, 0, 0, T) for every 1:1 orbit reachable from "
                    "the built-in seeds (symmetric closed form, flight-time scan, short "
                    "simulation) and report admissibility and the eigenvalues of J_P2 J_P1.",
    )
    _add_model_args(p)
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (key: solutions)")
    p.set_defaults(handler=_cmd_periodic)
    return p


def _cmd_periodic(args: argparse.Namespace) -> int:
    params = _model_params(args)
    from .orbits.periodic import find_1to1

    with contextlib.redirect_stdout(sys.stderr):
        orbits = find_1to1(params.eta, params.omega, params.F, r=params.r, d=params.d)
    keys = ("symmetric", "admissible", "stable", "lambda_max", "eigenvalues", "dw_L", "dw_R",
            "phase_L", "phase_R", "flight_times")
    sols = [{k: o.to_dict()[k] for k in keys} for o in orbits]
    return _emit(args.json, {"solutions": sols, "params": params.as_dict()}, _periodic_text)


def _periodic_text(d: dict) -> str:
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


# --------------------------------------------------------------------------- continue

_CONT_PARAMS = PARAM_NAMES


def _add_continue(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        "continue",
        help="continue a 1:1 orbit in eta, omega or F and report bifurcation events",
        description="Pseudo-arclength continuation (through folds) of the preferred 1:1 "
                    "orbit of the chosen --branch at --start, until the parameter leaves "
                    "[start, stop]; events (fold, flip, neimark-sacker, admissibility-loss, "
                    "symmetry-breaking) are located along the arclength. --method natural: "
                    "natural-parameter continuation from --start to --stop (ends at a fold).",
    )
    p.add_argument("--param", choices=_CONT_PARAMS, required=True,
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
                        "point of the symmetric branch (JSON key switched; arclength only)")
    p.allowed_values["--max-inadmissible"] = f"an integer >= 1 and <= {MAX_POINTS_MAX}"
    p.add_argument("--max-inadmissible", metavar="N", default=MAX_INADMISSIBLE_DEFAULT,
                   help="end the branch after N consecutive non-admissible points "
                        f"(arclength) [integer >= 1 and <= {MAX_POINTS_MAX}; default "
                        f"{MAX_INADMISSIBLE_DEFAULT}]")
    p.allowed_values["--max-points"] = f"an integer >= 1 and <= {MAX_POINTS_MAX}"
    p.add_argument("--max-points", metavar="N", default=MAX_POINTS_DEFAULT,
                   help="refuse a step that needs more than N continuation points "
                        f"[integer >= 1 and <= {MAX_POINTS_MAX}; default {MAX_POINTS_DEFAULT}]")
    _add_model_args(p, optional_group="model parameters (the two not continued are required)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: branch, events)")
    p.set_defaults(handler=_cmd_continue, _parser=p)
    return p


def _cmd_continue(args: argparse.Namespace) -> int:
    sub = args._parser
    given = getattr(args, args.param)
    if given is not None:
        others = " and ".join(f"--{q}" for q in _CONT_PARAMS if q != args.param)
        sub.error(f"argument --{args.param}: invalid {args.param} = {given!r}: not allowed "
                  f"with --param {args.param} (the continued parameter runs from --start to "
                  f"--stop); give only {others}")
    others = [q for q in _CONT_PARAMS if q != args.param]
    missing = [f"--{q}" for q in others if getattr(args, q) is None]
    if missing:
        sub.error("missing required option " + ", ".join(
            f"{m} ({sub.allowed_values[m]})" for m in missing) + f" when --param is {args.param}")
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
    max_points = check_int("max_points", args.max_points, lo=1, hi=MAX_POINTS_MAX)
    step = None
    if args.step is not None:
        step = check_real("step", args.step, lo=0.0, lo_open=True)
        check_step_points(args.step, abs(values["stop"] - values["start"]), step, max_points,
                          "--max-points")
    max_inadmissible = check_int("max_inadmissible", args.max_inadmissible, lo=1,
                                 hi=MAX_POINTS_MAX)
    if args.switch and (args.method != "arclength" or args.branch != "symmetric"):
        sub.error(f"argument --switch: not allowed with --method {args.method} --branch "
                  f"{args.branch} (only with --method arclength --branch symmetric)")
    fixed = {q: getattr(params, q) for q in others}
    from .orbits.continuation import continue_branch

    with contextlib.redirect_stdout(sys.stderr):
        br = continue_branch(args.param, values["start"], values["stop"], step, fixed,
                             r=params.r, d=params.d, max_points=max_points,
                             method=args.method, branch=args.branch, switch=args.switch,
                             max_inadmissible=max_inadmissible)
    return _emit(args.json, br.to_dict(), lambda d: _branch_text(d, values))


def _branch_text(d: dict, values: dict, indent: str = "") -> str:
    """Table of a ``Branch.to_dict()`` (and of the branches switched to)."""
    param = d["param"]
    lines = [f"{indent}{d['family']} branch in {param} from {values['start']:g} towards "
             f"{values['stop']:g}: {len(d['branch'])} points ({d['stopped']})"]
    for pt in d["branch"]:
        lines.append(f"{indent}  {param} = {pt[param]:.6g}  |lambda_max| = "
                     f"{pt['lambda_max']:.6g}  stable = {pt['stable']}  symmetric = "
                     f"{pt['symmetric']}  admissible = {pt['admissible']}  "
                     f"dw_L = {pt['dw_L']:.6g}")
    for ev in d["events"]:
        con = f" (meets the {ev['connects']} branch)" if ev.get("connects") else ""
        lines.append(f"{indent}  event {ev['type']} at {param} = {ev['at']:.7g}{con}")
    for sw in d["switched"]:
        lines.append(_branch_text(sw, values, indent + "  "))
    return "\n".join(lines)


# --------------------------------------------------------------------------- boundaries

def _add_boundaries(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        "boundaries",
        help="curves of fold, flip, neimark-sacker, symmetry-breaking and grazing points of "
             "1:1 orbits in the (eta, omega) plane at fixed F",
        description="Seed from one-parameter continuations along lines of the box, then "
                    "continue every codimension-one point of the 1:1 orbits (augmented "
                    "systems, exact Jacobians) in (eta, omega) at fixed F: the edges of the "
                    "classes of the stability map (Fig 16).",
    )
    p.allowed_values["--F"] = _param_allowed("F")
    p.add_argument("--F", metavar="F", required=True,
                   help=f"forcing amplitude A/L [{_param_allowed('F')}]")
    for name, default in (("eta", (0.05, 1.0)), ("omega", (0.7, 1.4))):
        flag = f"--{name}-range"
        p.allowed_values[flag] = f"two numbers lo < hi, each {_param_allowed(name)}"
        p.add_argument(flag, nargs=2, metavar=("LO", "HI"), default=list(default),
                       help=f"{name} interval of the box [{p.allowed_values[flag]}; default "
                            f"{default[0]:g} {default[1]:g}]")
    opt = p.add_argument_group("model parameters (optional)")
    for flag, default, help in (("--r", R_DEFAULT, "coefficient of restitution"),
                                ("--d", D_DEFAULT, "LO damping c/(M w0)")):
        p.allowed_values[flag] = _param_allowed(flag[2:])
        opt.add_argument(flag, metavar=flag[2:].upper(), default=default,
                         help=f"{help} [{_param_allowed(flag[2:])}; default {default:g}]")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (key: curves)")
    p.set_defaults(handler=_cmd_boundaries)
    return p


def _cmd_boundaries(args: argparse.Namespace) -> int:
    params = ModelParams(eta=0.1, omega=1.0, F=args.F, r=args.r, d=args.d)
    from .orbits.boundaries import boundaries

    with contextlib.redirect_stdout(sys.stderr):
        res = boundaries(params.F, args.eta_range, args.omega_range, r=params.r, d=params.d)
    return _emit(args.json, res.to_dict(), lambda d: _boundaries_text(d, params.F))


def _boundaries_text(d: dict, F: float) -> str:
    lines = [f"F = {F:g}, eta in {d['eta_range']}, omega in {d['omega_range']}: "
             f"{len(d['curves'])} curve(s)"]
    for c in d["curves"]:
        (e0, w0), (e1, w1) = c["points"][0], c["points"][-1]
        where = f" (flight {c['flight']}, {c['wall']})" if "wall" in c else ""
        lines.append(f"  {c['type']}{where} of {c['family']} orbits: {len(c['points'])} "
                     f"points from (eta, omega) = ({e0:.4g}, {w0:.4g}) to ({e1:.4g}, "
                     f"{w1:.4g})")
    return "\n".join(lines)


# --------------------------------------------------------------------------- attractors

def _add_attractors(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        "attractors",
        help="attractor census at one point: coexisting attractors and their basin fractions",
        description="Run N scrambled-Sobol initial states (z_m, z_m' in [-1.5, 1.5], "
                    "w = z_m - z_b in [-1, 1], z_b' in [-1.5, 1.5], forcing phase 0) until "
                    "they settle on a periodic orbit or reach t-end, group the end states "
                    "into attractors and report each one's basin fraction with a 95 %% "
                    "Wilson interval, and which one the start from rest reaches.",
    )
    _add_model_args(p)
    _add_value(p, "--n", "an integer >= 1 and <= 1000000", "number of initial states "
               "(default 256)", default=256)
    _add_value(p, "--seed", "an integer >= 0", "scramble seed of the Sobol points "
               "(default 0)", default=0)
    _add_value(p, "--t-end", f"a number > 0 and <= {T_END_MAX:g}",
               f"longest run (default {T_END_DEFAULT:g})", default=T_END_DEFAULT)
    _add_value(p, "--t-transient", "a number >= 0 and < t-end", "start of the window of "
               f"the non-periodic measures (default {T_TRANSIENT_DEFAULT:g})",
               default=T_TRANSIENT_DEFAULT)
    _add_value(p, "--threads", "an integer >= 1", "threads (default: all cores)",
               default=None)
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout "
                   "(keys: attractors, from_rest, unsettled_fraction)")
    p.set_defaults(handler=_cmd_attractors)
    return p


def _cmd_attractors(args: argparse.Namespace) -> int:
    params = _model_params(args)
    threads = None if args.threads is None else check_int("threads", args.threads, lo=1)
    from .attractors import census
    with contextlib.redirect_stdout(sys.stderr):
        res = census(params.eta, params.omega, params.F, r=params.r, d=params.d, n=args.n,
                     seed=args.seed, t_end=args.t_end, t_transient=args.t_transient,
                     n_threads=threads)
    return _emit(args.json, res.to_dict(), lambda d: _attractors_text(d, params))


def _attractors_text(d: dict, params: ModelParams) -> str:
    lines = [f"eta = {params.eta:g}, omega = {params.omega:g}, F = {params.F:g}: "
             f"{len(d['attractors'])} attractor(s) from {d['n']} initial states, "
             f"unsettled {d['unsettled_fraction']:.3g}"]
    for i, a in enumerate(d["attractors"]):
        rest = "  <- from rest" if i == d["from_rest"] else ""
        lines.append(f"  {i}: {a['regime']:10s} basin {a['basin_fraction']:.3f} "
                     f"[{a['ci'][0]:.3f}, {a['ci'][1]:.3f}]  KE ratio {a['ke_ratio']:.4f}"
                     f"  x_max {1e3 * a['xmax_m']:.4g} mm{rest}")
    return "\n".join(lines)


# --------------------------------------------------------------------------- main

_COMMANDS = (_add_simulate, _add_periodic, _add_continue, _add_boundaries, _add_attractors)


def _value_flags(subparsers_map: dict) -> set[str]:
    flags = set()
    for sub in subparsers_map.values():
        for action in sub._actions:
            if action.option_strings and action.nargs is None and not isinstance(
                    action, (argparse._StoreTrueAction, argparse._StoreFalseAction)):
                flags.update(action.option_strings)
    return flags


def _join_negative_values(argv: list[str], value_flags: set[str]) -> list[str]:
    """Turn ``--phi -1e-3`` into ``--phi=-1e-3``.

    argparse only recognises plain negative numbers such as -1 or -0.5 as option values;
    exponent forms like -1e-3 would otherwise be rejected as an unknown option.
    """
    out, i = [], 0
    while i < len(argv):
        tok = argv[i]
        if tok == "--":
            out.extend(argv[i:])
            break
        if tok in value_flags and i + 1 < len(argv) and argv[i + 1].startswith("-"):
            try:
                float(argv[i + 1])
            except ValueError:
                pass
            else:
                out.append(f"{tok}={argv[i + 1]}")
                i += 2
                continue
        out.append(tok)
        i += 1
    return out


def build_parser() -> tuple[VinesArgumentParser, dict]:
    parser = VinesArgumentParser(
        prog=PROG,
        description="Exact simulation and map-based analysis of the vibro-impact nonlinear "
                    "energy sink (VI NES).",
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="command",
                                       parser_class=VinesArgumentParser)
    commands = {}
    for add in _COMMANDS:
        sub = add(subparsers)
        commands[sub.prog.split()[-1]] = sub
    return parser, commands


def main(argv: Sequence[str] | None = None) -> int:
    parser, commands = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    argv = _join_negative_values(argv, _value_flags(commands))
    args, extras = parser.parse_known_args(argv)
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    sub = commands[args.command]
    if extras:
        known = sorted(f for a in sub._actions for f in a.option_strings)
        sub.error(f"unrecognized argument {extras[0]!r} (allowed options: {', '.join(known)})")
    try:
        return args.handler(args)
    except ParameterError as err:
        flag = _flag_for(err.name)
        if any(flag in a.option_strings for a in sub._actions):
            sub.error(f"argument {flag}: {err}")
        sub.error(str(err))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
