"""Cost of the default design: optimise a VI NES against the LO alone and the optimal TMD.

Run: python benchmarks/bench_design.py [--threads N] [--census-n N] [--json PATH]

The issue's default: band omega 0.8-1.2 (21 points), base amplitudes 0.75, 3 and 6 mm
(F = 0.05, 0.2, 0.4 at the paper's L = 0.015 m), eta_max 0.1, Table 1 structure. Prints
wall and CPU time split by part (TMD, search, attractor census), the number of runs, the
load average before and after, and the comparison table (worst x_max/A per amplitude).
No assertion: the numbers are to be read beside the load (2 cores shared).
"""
import argparse
import json
import os
import time

import vines


def _load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--census-n", type=int, default=None, help="census states (default: "
                    "the API's)")
    ap.add_argument("--json", metavar="PATH", help="also write the result's JSON here")
    args = ap.parse_args()
    vines.simulate(0.1, 1.0, 0.2, t_end=50.0, t_transient=10.0)   # load the compiled kernels
    kw = {} if args.census_n is None else {"census_n": args.census_n}
    load0 = _load()
    cpu0, t0 = time.process_time(), time.perf_counter()
    res = vines.design(eta_max=0.1, n_threads=args.threads, **kw)
    wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
    d = res.to_dict()
    c = d["cost"]
    print(f"default design on {args.threads} thread(s): wall {wall:.1f} s, CPU {cpu:.1f} s "
          f"(load average before {load0}, after {_load()})")
    print(f"  TMD optimisation {c['tmd_s']:.2f} s; search {c['search_s']:.1f} s "
          f"({c['n_designs']} designs, {c['n_runs_from_rest']} runs from rest); "
          f"census {c['census_s']:.1f} s ({c['n_runs_census']} runs)")
    print(f"  CPU: search {c['search_cpu_s']:.1f} s, census {c['census_cpu_s']:.1f} s "
          f"(process time of all threads; wall on {args.threads} idle cores is about "
          f"CPU / {args.threads})")
    v, t, lo = d["vines"], d["tmd"], d["lo_alone"]
    print(f"  VI NES: eta {v['eta']:.4g}, clearance {1e3 * v['clearance_m']:.3g} mm; "
          f"TMD: f {t['frequency_ratio']:.4f}, zeta {t['damping_ratio']:.4f}")
    print("  amplitude [mm]   F      LO alone   TMD    VI NES rest  VI NES any attractor")
    any_ = v["worst_ratio_any_attractor_per_amplitude"] or [None] * len(v["F"])
    for A, F, w, a in zip(d["curves"]["amplitude_m"], v["F"], v["worst_ratio_per_amplitude"],
                          any_, strict=True):
        a_txt = "n/a" if a is None else f"{a:.2f}"
        print(f"  {1e3 * A:13.3g} {F:7.4f} {lo['worst_ratio']:9.2f} {t['worst_ratio']:7.3f}"
              f" {w:11.2f}  {a_txt:>10}")
    if args.json:
        from vines.cli import _jsonable
        with open(args.json, "w") as fh:
            json.dump(_jsonable(d), fh, allow_nan=False)


if __name__ == "__main__":
    main()
