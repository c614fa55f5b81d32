"""Speed of the event kernel against the kernel of another revision, in one process.

Run: python benchmarks/bench_kernel.py [--ref main] [--repeat N]
The kernel module of git revision REF (``src/vines/core/kernel.py``, with that revision's
``flow.py``) is loaded beside the current ones, both run the same trajectories (the 1:1 orbit and the
chatter point, whole runs from rest, no shortcut), interleaved, best of N each (CPU
time of the thread); the script prints the time ratio current / REF, checks that both give bit-identical state, counters,
impacts and segments, and prints the machine's load. No timing is asserted anywhere.
"""
import argparse
import importlib.util
import inspect
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from vines.core import kernel as current
from vines.core.exact import kernel_params, oscillators
from vines.core.params import ModelParams, SolverSettings

#: (label, model point, t_end): the 1:1 orbit of Fig 4(a) and the chatter point
CASES = (("1:1 (0.05, 1, 0.05)", dict(eta=0.05, omega=1.0, F=0.05), 20000.0),
         ("chatter (0.2, 0.9, 0.4)", dict(eta=0.2, omega=0.9, F=0.4), 3000.0))


def _load(name: str, path: str):
    """Import the file ``path`` as the module ``vines.core.<name>`` (relative imports
    resolve in vines.core)."""
    spec = importlib.util.spec_from_file_location(f"vines.core.{name}", path)
    mod = importlib.util.module_from_spec(spec)
    mod.__package__ = "vines.core"
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def load_ref(ref: str):
    """The kernel module of git revision ``ref`` with that revision's ``flow`` (closed form,
    bounds, integrals), importable beside the current ones; walls, params from the current."""
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, check=True).stdout.strip()
    folder = tempfile.mkdtemp(prefix="vines_kernel_ref_")
    tag = "".join(c if c.isalnum() else "_" for c in ref)
    paths = {}
    for part in ("flow", "kernel"):
        src = subprocess.run(["git", "-C", root, "show", f"{ref}:src/vines/core/{part}.py"],
                             capture_output=True, text=True, check=True).stdout
        src = src.replace("from .flow import", f"from ._flow_{tag} import")
        paths[part] = os.path.join(folder, f"_{part}_{tag}.py")
        with open(paths[part], "w") as fh:
            fh.write(src)
    _load(f"_flow_{tag}", paths["flow"])
    return _load(f"_kernel_{tag}", paths["kernel"])


def make_runner(mod, p: ModelParams, st: SolverSettings):
    """fn() -> (rc, cur, acc, cnt, imp, seg): one whole run with module ``mod``'s kernel,
    called with the signature that module has."""
    osc = oscillators(p)
    cap = 6 * int(st.t_end / p.period + 64) * 20

    def fn():
        cur = np.array([0.0, *st.state0, 0.0, 0.0])
        acc, cnt = np.zeros(mod.N_ACC), np.zeros(mod.N_CNT, dtype=np.int64)
        imp, seg = np.empty((cap, 6)), np.empty((2 * cap, 6))
        params = list(inspect.signature(mod.run_kernel.py_func).parameters)
        if params[0] == "osc_f":              # one argument per scalar (before #23)
            rc = mod.run_kernel(*osc, p.eta, p.r, p.omega, p.phi, st.t_end, st.t_transient,
                                st.v_stick, st.root_tol, st.max_impacts, 0.0, cur, acc,
                                cnt, imp, seg)
        else:
            kp = kernel_params(osc, p, st, st.t_end, st.t_transient, 0.0)
            rc = mod.run_kernel(kp, (cur, acc, cnt), imp, seg)
        return rc, cur, acc, cnt, imp[:cnt[mod.C_NIMP_REC]], seg[:cnt[mod.C_NSEG_REC]]
    return fn


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--ref", default="main", help="git revision of the reference kernel")
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    ref = load_ref(args.ref)
    print(f"kernel: current vs {args.ref}, best of {args.repeat}, interleaved; "
          f"{os.cpu_count()} cores, load average before {os.getloadavg()[0]:.2f}")
    for label, point, t_end in CASES:
        p = ModelParams(**point)
        st = SolverSettings(t_end=t_end, t_transient=t_end / 2)
        runs = {"current": make_runner(current, p, st), args.ref: make_runner(ref, p, st)}
        out = {k: fn() for k, fn in runs.items()}              # compile / load the cache
        same = all(np.array_equal(a, b) for a, b in zip(*out.values(), strict=True))
        best = dict.fromkeys(runs, float("inf"))
        for _ in range(args.repeat):
            for k, fn in runs.items():
                t = time.thread_time()          # CPU time: less sensitive to the load
                fn()
                best[k] = min(best[k], time.thread_time() - t)
        n = int(out["current"][3][current.C_NIMP_TOTAL])
        print(f"{label}, t_end {t_end:g}, {n} impacts: current {best['current'] * 1e3:.1f} ms, "
              f"{args.ref} {best[args.ref] * 1e3:.1f} ms, ratio "
              f"{best['current'] / best[args.ref]:.3f}; bit-identical: {same}")
    print(f"load average after {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
