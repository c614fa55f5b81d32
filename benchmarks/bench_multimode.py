"""Cost of the general engine (``vines.multimode``) per impact at 2 degrees of freedom and
2 absorbers (the host of docs/models/two_mode.yaml: a VI NES and a TMD with end stops),
beside its RK oracle (DOP853 at rtol 1e-10) on the same run, in one process. Prints the
load of the machine, microseconds per impact of each and their ratio.

    python benchmarks/bench_multimode.py [t_end]
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from vines.multimode import ModelSettings, read_model, simulate_model
from vines.reference.rk_multimode import run_rk_model

MODEL = Path(__file__).resolve().parents[1] / "docs" / "models" / "two_mode.yaml"


def main(t_end=400.0):
    model = read_model(MODEL)
    st = ModelSettings(t_end=t_end, t_transient=t_end / 2, n_record=0)
    simulate_model(model, ModelSettings(t_end=10.0, t_transient=5.0))   # compile / cache
    print(f"load {os.getloadavg()[0]:.2f}, t_end {t_end:g}")
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        res = simulate_model(model, st)
        best = min(best, time.perf_counter() - t0)
    n = int(res.n_impacts_whole_run.sum())
    t0 = time.perf_counter()
    ref = run_rk_model(model, t_end, t_transient=t_end / 2, rtol=1e-10, atol=1e-12,
                       max_events=10 ** 7)
    rk = time.perf_counter() - t0
    n_rk = ref["t"].size
    print(f"engine: {n} impacts, {1e6 * best / max(n, 1):.2f} us per impact ({best:.3f} s)")
    print(f"rk 1e-10: {n_rk} impacts, {1e6 * rk / max(n_rk, 1):.2f} us per impact ({rk:.3f} s)")
    print(f"ratio rk / engine: {rk / best:.1f}")


if __name__ == "__main__":
    main(*(float(a) for a in sys.argv[1:2]))
