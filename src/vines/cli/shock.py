"""``vines shock``: free decay after an impulse, the VI NES against the TMD and the LO alone.

Every value is read as a string and validated by ``studies.shock.shock``; a ParameterError
names its flag through ``FLAG_OF``.
"""
from __future__ import annotations

import argparse

from ..studies.design_checks import DEFAULT_BAND
from ..studies.shock import N_PERIODS_DEFAULT
from .common import VinesArgumentParser, add_structure_args, emit, quiet_stdout

NAME = "shock"

#: name of the ParameterError raised by studies.shock -> its flag
FLAG_OF = {"omega_band": "--omega-band", "M": "--M", "k": "--k", "c": "--c", "d": "--d",
           "r": "--r", "eta": "--eta", "clearance": "--clearance",
           "velocity": "--velocity", "energy": "--energy", "energy_range": "--energy-range",
           "periods": "--periods", "mu": "--eta", "starts": "--starts", "seed": "--seed"}


def add_parser(subparsers) -> VinesArgumentParser:
    """The ``shock`` sub-parser."""
    p = subparsers.add_parser(
        NAME,
        help="free decay after an impulse: energy dissipated by a VI NES, the equal-mass "
             "TMD and the LO alone within N natural periods",
        description="The LO starts at rest position with an initial velocity (an impulse), "
                    "no forcing, the ball at rest at the cavity centre. Fraction of the "
                    "initial energy dissipated within --periods natural periods of the LO, "
                    "by LO damping and by impacts (the TMD: by its damper), the energy left, "
                    "the impacts and the times to decay to 10 % and 1 % of it. VI NES by "
                    "the exact solver; TMD (tuned as in vines design) and LO alone in "
                    "closed form (matrix exponential).")
    add_structure_args(p)
    des = p.add_argument_group("VI NES design (required)")
    des.add_argument("--eta", metavar="E", required=True,
                     help="ball-to-LO mass ratio m/M; also the TMD's mass ratio [0 < E <= 1000]")
    des.add_argument("--clearance", metavar="L", required=True,
                     help="clearance in metres: half the cavity length (Table 1: 0.015) [> 0]")
    des.add_argument("--omega-band", nargs=2, metavar=("LO", "HI"),
                     default=list(DEFAULT_BAND),
                     help=f"band the TMD is tuned for, as in vines design [0 < LO < HI <= "
                          f"1000; default {DEFAULT_BAND[0]:g} {DEFAULT_BAND[1]:g}]")
    ini = p.add_argument_group("initial condition (one of)").add_mutually_exclusive_group(
        required=True)
    ini.add_argument("--velocity", metavar="V0",
                     help="LO's initial velocity in m/s [> 0]")
    ini.add_argument("--energy", metavar="E0",
                     help="initial energy M V0^2/2 in J [> 0]")
    ini.add_argument("--energy-range", nargs=3, metavar=("A", "B", "N"),
                     help="the curve over N energies from A to B J, geometric "
                          "[0 < A < B, 2 <= N <= 10000]")
    p.add_argument("--periods", metavar="N", default=N_PERIODS_DEFAULT,
                   help="window: natural periods 2 pi/w0 of the LO [0 < N <= 10000; default "
                        f"{N_PERIODS_DEFAULT:g}]")
    p.add_argument("--starts", metavar="N", default=0,
                   help="also N ball states at the moment of the shock, drawn over the "
                        "cavity (position) and within +-V0 (velocity), and the distribution "
                        "of the VI NES's dissipated fraction over them [0 <= N <= 4096; "
                        "default 0]")
    p.add_argument("--seed", metavar="S", default=0,
                   help="seed of the ball starts [an integer >= 0; default 0]")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object on stdout (keys: inputs, scales, activation, "
                        "vines, tmd, tmd_fastest, tmd_equal_travel, lo_alone, stroke, "
                        "starts, cost; one shock: history, and in vines "
                        "impacts_stop_amplitude, the LO amplitude in units of L where the "
                        "two-impact regime ends, or null, beside the slow flow's xi_min; a "
                        "range: curve, optimal)")
    return p


def run(args: argparse.Namespace) -> int:
    return emit(args.json, compute(args), text)


def compute(args: argparse.Namespace) -> dict:
    """The JSON object of ``studies.shock.shock``; ParameterError on bad input."""
    from ..studies.shock import shock
    with quiet_stdout():
        return shock(eta=args.eta, clearance_m=args.clearance, velocity_m_s=args.velocity,
                     energy_J=args.energy, energy_range=args.energy_range,
                     periods=args.periods, M_kg=args.M, k_N_per_m=args.k, c_Ns_per_m=args.c,
                     d=args.d, r=args.r, omega_band=args.omega_band, starts=args.starts,
                     seed=args.seed)


def _t(x) -> str:
    return "not reached" if x is None else f"{x:.4g} s"


def _line(name: str, s: dict) -> str:
    return (f"  {name:<9} dissipated {s['dissipated_fraction']:.4f} (damping "
            f"{s['by_damping']:.4f}, impacts {s['by_impacts']:.4f}, absorber "
            f"{s['by_absorber']:.4f}), left {s['remaining_fraction']:.4g}, "
            f"{s['n_impacts']} impacts, t_10 {_t(s['t_10'])}, t_1 {_t(s['t_1'])}")


def _tmd_lines(d: dict) -> list:
    """The three TMDs: tuning, decay and peak stroke after the (largest) shock."""
    lines = []
    for key, name in (("tmd", "TMD tuned for the band"), ("tmd_fastest", "TMD decaying "
                      "fastest"), ("tmd_equal_travel", "TMD decaying fastest with stroke <= L")):
        t = d.get(key)
        if t is None:
            if key in d:
                lines.append(f"  {name}: no tuning keeps the stroke within L")
            continue
        lines += [f"  {name} (f = {t['design']['frequency_ratio']:.4f}, zeta = "
                  f"{t['design']['damping_ratio']:.4f}): stroke |y - x| "
                  f"{1e3 * t['stroke_m']:.3g} mm, LO x_max {1e3 * t['x_max_m']:.3g} mm, "
                  f"slowest decay rate {t['slowest_decay_rate_per_s']:.3g} 1/s",
                  _line("", t)]
    return lines


def _starts_lines(d: dict) -> list:
    st = d.get("starts")
    if not st:
        return []
    q = st["dissipated_fraction_quantiles"]
    where = ("" if "curve" not in d else " at the largest energy")
    q = q[-1] if "curve" in d else q
    return [f"  VI NES over {st['n']} ball starts (seed {st['seed']}){where}: dissipated "
            "fraction quantiles " + ", ".join(f"{100 * p:g} % {v:.4f}"
                                              for p, v in zip(st["quantiles"], q,
                                                              strict=True))]


def text(d: dict) -> str:
    """A reader's summary of ``run``'s object."""
    i, act = d["inputs"], d["activation"]
    head = (f"eta {i['eta']:g}, clearance {1e3 * i['clearance_m']:.4g} mm, "
            f"{i['periods']:g} periods ({d['scales']['window_s']:.4g} s); impacts from "
            f"V0 {act['velocity_m_s']:.4g} m/s (E0 {act['energy_J']:.4g} J)")
    if "curve" not in d:
        lines = [head, f"V0 {i['velocity_m_s']:.4g} m/s, E0 {i['energy_J']:.4g} J:",
                 _line("VI NES", d["vines"])]
    else:
        c, o = d["curve"], d["optimal"]
        lines = [head, f"  best VI NES: {o['dissipated_fraction']:.4f} at E0 "
                       f"{o['energy_J']:.4g} J (V0 {o['velocity_m_s']:.4g} m/s)",
                 "  E0 [J]      VI NES dissipated fraction   impacts"]
        for E, f, n in zip(c["energy_J"], c["vines"]["dissipated_fraction"],
                           c["vines"]["n_impacts"], strict=True):
            lines.append(f"  {E:<10.4g}  {f:<26.4f}   {n}")
    lines += [f"  VI NES ball travel +-L = {1e3 * d['inputs']['clearance_m']:.4g} mm "
              "relative to the LO", *_starts_lines(d), *_tmd_lines(d),
              _line("LO alone", d["lo_alone"])
              + (f", x_max {1e3 * d['lo_alone']['x_max_m']:.3g} mm"
                 if "x_max_m" in d["lo_alone"] else ""),
              f"  cost {d['cost']['wall_s']:.2f} s, {d['cost']['n_runs']} exact runs"]
    return "\n".join(lines)
