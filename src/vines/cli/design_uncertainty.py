"""``vines design --uncertainty``: the design's uncertain parts (``studies.uncertainty``).

The arguments, the JSON key ``uncertainty`` and its text summary, kept apart from
``cli.design`` (which calls the three functions below)."""
from __future__ import annotations

import argparse

from ..studies.uncertainty_checks import N_SAMPLES_DEFAULT, PARAMETERS


def add_args(p) -> None:
    """The argument group of the uncertain parts."""
    g = p.add_argument_group("uncertain parts (the design above with parts that are not "
                             "exact; from-rest view)")
    g.add_argument("--uncertainty", nargs="+", metavar="NAME=DIST", default=None,
                   help="each NAME=uniform:LO:HI or NAME=normal:MEAN:SD (truncated at 3 SD); "
                        f"NAME one of {', '.join(PARAMETERS)}: frequency (host natural "
                        "frequency), clearance and mass (absorber mass) as relative "
                        "deviations (0.05 = +5 %%), r the restitution itself")
    g.add_argument("--samples", metavar="N", default=N_SAMPLES_DEFAULT,
                   help="Sobol base sample size n, a power of 2: the design is evaluated "
                        f"at n (k + 2) points for k parameters [default {N_SAMPLES_DEFAULT}]")
    g.add_argument("--uncertainty-seed", metavar="S", default=0,
                   help="seed of the scrambled Sobol sequence [an integer >= 0; default 0]")


def precheck(args: argparse.Namespace) -> None:
    """What can be checked before the design is computed (ParameterError on bad input)."""
    from ..studies.uncertainty_checks import check_parameters, check_samples
    if args.uncertainty is not None:
        check_parameters(args.uncertainty)
        check_samples(args.samples)


def compute(args: argparse.Namespace, result) -> dict | None:
    """The JSON object ``uncertainty`` of a design result (None without --uncertainty)."""
    if args.uncertainty is None:
        return None
    from ..studies.uncertainty import uncertainty
    return uncertainty(result, args.uncertainty, samples=args.samples,
                       seed=args.uncertainty_seed, n_threads=args.threads).to_dict()


def _stats(d: dict) -> str:
    return f"mean {d['mean']:.3g}, 95 % quantile {d['q95']:.3g} (nominal {d['nominal']:.3g})"


def text(d: dict | None) -> list[str]:
    """A reader's lines of the ``uncertainty`` object."""
    if d is None:
        return []
    shares = ", ".join(f"{k} {v:.0%}" for k, v in d["vines"]["regime_shares"].items() if v)
    lines = [f"  uncertain parts: {d['n_points']} points ("
             + ", ".join(p["name"] for p in d["parameters"]) + ")",
             f"    VI NES worst x_max/A: {_stats(d['vines'])}; regime at the worst point: "
             f"{shares}",
             f"    TMD worst x_max/A:    {_stats(d['tmd'])}",
             f"    VI NES better than the TMD in {d['vines_better_probability']:.0%} of them"]
    for key in ("vines", "tmd"):
        s = d["sensitivity"][key]
        if s:
            lines.append(f"    Sobol indices {key} (first, total): " + ", ".join(
                f"{n} {v['first_order']:.2f}/{v['total_order']:.2f}"
                + ("" if v["reliable"] else " (unreliable)") for n, v in s.items()))
    lines += [f"    note: {n}" for n in d["sensitivity_notes"]]
    return lines
