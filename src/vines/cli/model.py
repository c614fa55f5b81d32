"""``vines model check FILE``: validate a model file of the general host (docs/model.md,
"General model") and describe it."""
from __future__ import annotations

import argparse

import numpy as np

from .common import VinesArgumentParser, add_json_flag, emit

NAME = "model"
ACTIONS = ("check",)


def add_parser(subparsers) -> VinesArgumentParser:
    p = subparsers.add_parser(
        NAME, help="check a model file of a host with several degrees of freedom and absorbers",
        description="Validate a model file (YAML: host, absorbers, forcing; docs/usage.md, "
                    "'A host with several modes') and print what it holds: the host's modes "
                    "and the absorbers' kinds. A bad file is refused in one line (exit 2).")
    p.add_argument("action", choices=ACTIONS, help="check: validate and describe the file")
    p.add_argument("file", metavar="FILE", help="the model file (YAML)")
    add_json_flag(p, "keys: valid, n_dof, natural_frequencies, damping_ratios, absorbers, "
                     "forcing")
    return p


def describe(model) -> dict:
    """The model's host modes (undamped natural frequencies; modal damping ratios of the
    diagonal of the modal damping matrix) and its absorbers and forcing."""
    h = model.host
    L = np.linalg.cholesky(h.mass)
    Li = np.linalg.inv(L)
    w2, U = np.linalg.eigh(Li @ h.stiffness @ Li.T)
    Cm = U.T @ Li @ h.damping @ Li.T @ U
    w = np.sqrt(w2)
    d = model.to_dict()
    return {"valid": True, "n_dof": model.n_dof, "natural_frequencies": w,
            "damping_ratios": np.diag(Cm) / (2.0 * w), "absorbers": d["absorbers"],
            "forcing": d["forcing"]}


def run(args: argparse.Namespace) -> int:
    from ..multimode.modelfile import read_model

    info = describe(read_model(args.file))

    def text(d):
        freqs = ", ".join(f"{x:.6g}" for x in d["natural_frequencies"])
        lines = [f"valid model: {d['n_dof']} degrees of freedom, natural frequencies {freqs}",
                 f"forcing: {d['forcing']['kind']}, amplitude {d['forcing']['amplitude']:g}, "
                 f"frequency {d['forcing']['frequency']:g}"]
        lines += [f"absorber {i}: {a['kind']} on dof {a['dof']}, mass {a['mass']:g}, "
                  f"stiffness {a['stiffness']:g}, damping {a['damping']:g}, gap {a['gap']:g}, "
                  f"restitution {a['restitution']:g}" for i, a in enumerate(d["absorbers"])]
        return "\n".join(lines)

    return emit(args.json, info, text)
