"""Peak memory and time of long `vines simulate` runs (issue: memory grew with t_end).

Run: python benchmarks/bench_memory.py [--ref REV] [--only N]
Each command runs in a child process; its peak resident set (ru_maxrss) and CPU time come
from resource.getrusage(RUSAGE_CHILDREN) taken around it, wall time from the clock. With
--ref, the same commands also run on the sources of git revision REV (exported to a
temporary directory) and the JSON outputs are compared. Target: peak RSS <= 400 MB for
both runs. Nothing is asserted; the load average is printed beside the numbers.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

FLAGS = ["--t-transient", "0", "--no-periodic-shortcut", "--max-impacts", "100000000",
         "--json"]
#: the 1:1 orbit over 3e7 time units (9.5e6 impacts) and the chatter point (9.7e6 impacts)
RUNS = (["--eta", "0.05", "--omega", "1", "--F", "0.05", "--t-end", "3e7"],
        ["--eta", "0.2", "--omega", "0.9", "--F", "0.4", "--t-end", "1e6"])
TARGET_MB = 400


def measure(src: str, args: list) -> dict:
    """Run `python -m vines simulate ARGS` with ``src`` on the path, one child process."""
    env = dict(os.environ, PYTHONPATH=src)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "vines", "simulate", *args, *FLAGS],
                         env=env, capture_output=True, text=True, check=True).stdout
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    # ru_maxrss of the children is the largest of any child so far (kB on Linux)
    return dict(rss_mb=after.ru_maxrss / 1024, wall=wall, cpu=cpu, json=json.loads(out))


def export(rev: str) -> str:
    """The src directory of git revision ``rev`` in a temporary directory."""
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, check=True).stdout.strip()
    dest = tempfile.mkdtemp(prefix="vines_ref_")
    tar = subprocess.run(["git", "-C", root, "archive", rev, "src"], capture_output=True,
                         check=True).stdout
    subprocess.run(["tar", "-x", "-C", dest], input=tar, check=True)
    return os.path.join(dest, "src")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--ref", help="also run the sources of this git revision (first)")
    ap.add_argument("--only", type=int, choices=range(len(RUNS)), help="run one case")
    args = ap.parse_args()
    here = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "src")
    sources = ([(args.ref, export(args.ref))] if args.ref else []) + [("current", here)]
    cases = RUNS if args.only is None else [RUNS[args.only]]
    for case in cases:
        print(" ".join(case))
        outs = {}
        for name, src in sources:
            # ru_maxrss of RUSAGE_CHILDREN never decreases: a fresh child per measurement
            r = json.loads(subprocess.run(
                [sys.executable, __file__, "--child", src, *case],
                capture_output=True, text=True, check=True).stdout)
            outs[name] = r["json"]
            mark = "<=" if r["rss_mb"] <= TARGET_MB else ">"
            print(f"  {name:8s}: peak RSS {r['rss_mb']:7.0f} MB ({mark} {TARGET_MB} MB), "
                  f"wall {r['wall']:6.1f} s, CPU {r['cpu']:6.1f} s, load "
                  f"{os.getloadavg()[0]:.1f}; {r['json']['n_impacts']} impacts")
        if len(outs) == 2:
            a, b = outs.values()
            print(f"  JSON identical: {a == b}")


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--child":
        print(json.dumps(measure(sys.argv[2], sys.argv[3:])))
    else:
        main()
