"""``vines slowflow``: the averaged slow flow of the symmetric two-impact regime at one point
(``--omega``) or over a frequency range (``--omega-range A B N``): a first answer in
milliseconds, the exact one by ``vines periodic`` (docs/slowflow.md)."""
from __future__ import annotations

import argparse

import numpy as np

from ..core.params import D_DEFAULT, R_DEFAULT, ParameterError, check_int, check_param
from .common import VinesArgumentParser, emit

NAME = "slowflow"

#: name of the ParameterError raised by vines.slowflow -> its flag
FLAG_OF = {"omegas": "--omega-range"}
N_RANGE_MAX = 1_000_000
RANGE_ALLOWED = f"0 < A < B <= 1000 and an integer 2 <= N <= {N_RANGE_MAX}"


def add_parser(subparsers) -> VinesArgumentParser:
    """The ``slowflow`` sub-parser."""
    p = subparsers.add_parser(
        NAME,
        help="the averaged slow flow (light ball, light damping, near resonance): slow "
             "invariant manifold, its fold, fixed points and their stability, regime; "
             "or the FRC over a frequency range",
        description="Closed forms of the slow flow of the symmetric two-impact regime "
                    "(docs/slowflow.md): rho, the activation threshold xi_min (the fold of "
                    "the slow invariant manifold), every fixed point (LO amplitude max "
                    "|z_m| and ball amplitude in units of L, impact phase at L, stability) "
                    "and the regime from rest (two-impact, SMR, no impact), followed "
                    "through the jump onto the SIM. Refused for eta > 0.5, "
                    "d > 0.5 or r = 1; warnings where eta, d, F or |omega - 1| are not small.")
    g = p.add_argument_group("model parameters")
    flags = (("--eta", "a number > 0 and <= 0.5", "ball-to-LO mass ratio m/M"),
             ("--F", "a number >= 0 and <= 1000", "forcing amplitude A/L"))
    for flag, allowed, help in flags:
        p.allowed_values[flag] = allowed
        g.add_argument(flag, metavar=flag.lstrip("-").upper(), required=True,
                       help=f"{help} [{allowed}]")
    p.allowed_values["--r"] = "a number with 0 <= r < 1"
    g.add_argument("--r", metavar="R", default=R_DEFAULT,
                   help=f"coefficient of restitution [0 <= r < 1; default {R_DEFAULT:g}]")
    p.allowed_values["--d"] = "a number >= 0 and <= 0.5"
    g.add_argument("--d", metavar="D", default=D_DEFAULT,
                   help=f"LO damping c/(M w0) [0 <= d <= 0.5; default {D_DEFAULT:.6f}]")
    w = p.add_argument_group("frequency (one of)").add_mutually_exclusive_group(required=True)
    w.add_argument("--omega", metavar="OMEGA",
                   help="forcing frequency ratio omega = w/w0 [a number > 0 and <= 1000]")
    w.add_argument("--omega-range", nargs=3, metavar=("A", "B", "N"),
                   help=f"the FRC over N frequencies from A to B [{RANGE_ALLOWED}]")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: model, params, rho, xi_min, "
                        "x_symmetry_breaking (x_flip: its deprecated name), orbits, regime, "
                        "from_rest, smr, linear_amplitude, warnings; with "
                        "--omega-range: frc, regimes instead of orbits and regime)")
    return p


def omega_range(values) -> np.ndarray:
    """The N frequencies of --omega-range A B N; ParameterError naming omega_range."""
    a, b, n = values
    try:
        a, b = check_param("omega", a), check_param("omega", b)
        n = check_int("omega_range", n, lo=2, hi=N_RANGE_MAX)
    except ParameterError:
        raise ParameterError("omega_range", " ".join(values), RANGE_ALLOWED) from None
    if not a < b:
        raise ParameterError("omega_range", " ".join(values), RANGE_ALLOWED)
    return np.linspace(a, b, n)


def run(args: argparse.Namespace) -> int:
    return emit(args.json, compute(args), text)


def compute(args: argparse.Namespace) -> dict:
    """The JSON object; ParameterError on bad input."""
    from ..slowflow import frc, response

    if args.omega_range is not None:
        out = frc(args.eta, omega_range(args.omega_range), args.F, r=args.r, d=args.d)
        d = out.to_dict()
        d["params"] = {"eta": float(args.eta), "F": float(args.F), "r": float(args.r),
                       "d": float(args.d), "omega_range": [float(x) for x in
                                                           out.omega_grid[[0, -1]]],
                       "n_omega": int(out.omega_grid.size)}
        return d
    return response(args.eta, args.omega, args.F, r=args.r, d=args.d).to_dict()


def _orbit(o: dict) -> str:
    return (f"  amplitude {o['amplitude']:.6g}, ball {o['ball_amplitude']:.6g}, phase "
            f"{o['phase']:.4f} rad, {'stable' if o['stable'] else 'unstable'} "
            f"({o['branch']} branch of the SIM)")


#: what the numbers of the text output are (lengths in units of L, docs/slowflow.md)
LEGEND = ("  rho = (2/pi)(1 - r)/(1 + r): the impact loss of the slow invariant manifold (SIM); "
          "xi_min: the LO amplitude below which no two-impact motion exists (its fold); "
          "amplitude: max |z_m|, ball: max |z_b|, phase: forcing phase at the L impact")


def text(d: dict) -> str:
    """A reader's summary."""
    lines = [f"slow flow: rho {d['rho']:.6g}, xi_min {d['xi_min']:.6g} (fold), "
             f"x_symmetry_breaking {d['x_symmetry_breaking']:.6g} (upper end of the stable "
             "branch: the symmetric orbit's symmetry-breaking pitchfork)"]
    if "frc" in d:
        counts = {}
        for g in d["regimes"]:
            counts[g["regime"]] = counts.get(g["regime"], 0) + 1
        lines.append(f"  {len(d['frc'])} fixed points over {len(d['regimes'])} frequencies; "
                     + ", ".join(f"{k}: {v}" for k, v in sorted(counts.items())))
        lines += [f"  omega {p['omega']:.6g}: " + _orbit(p).strip() for p in d["frc"]]
    else:
        fr = d["from_rest"]
        lines.append(f"  regime {d['regime']} from rest ({fr['decided_by']}, {fr['jumps']} "
                     f"jump(s) onto the SIM); LO without impacts "
                     f"{d['linear_amplitude']:.6g}")
        lines += [_orbit(o) for o in d["orbits"]]
        if d["smr"] is not None:
            lines.append(f"  SMR: LO amplitude from {d['smr']['amplitude_low']:.4g} to "
                         f"{d['smr']['amplitude_high']:.4g}")
    lines += [f"  warning: {w}" for w in d["warnings"]]
    lines.append(LEGEND)
    return "\n".join(lines)
