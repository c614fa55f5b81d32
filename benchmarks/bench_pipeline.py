"""Wall and CPU time of the whole pipeline from scratch, in a fresh copy of the checkout.

    python benchmarks/bench_pipeline.py [--target all] [--configfile config/smoke.yaml]
                                        [--cores 2] [--runs cold warm]

The tracked files of this checkout (with their uncommitted edits) are copied to a temporary
directory, and ``snakemake -c CORES [TARGET]`` runs there once per entry of ``--runs``
(TARGET: the Snakefile's default ``paper`` unless given):

* ``cold``: the first run of a fresh clone, numba compiling every kernel it calls;
* ``warm``: the results deleted, the numba cache of the run before kept (what a second
  study on the same checkout costs).

Printed per run: wall time, CPU time of all processes (user + system), jobs run, load
average before and after, and the CPU seconds by rule from the jobs' ``benchmark:`` files
(compute rules only; figure rules have none). Nothing is asserted.
"""
from __future__ import annotations

import argparse
import csv
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def copy_checkout(dest: Path) -> None:
    """Copy the tracked files of the checkout (working-tree contents) to ``dest``."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True,
                           capture_output=True).stdout.decode().split("\0")
    for rel in filter(None, files):
        src = ROOT / rel
        if src.is_file():
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / rel)


def children_cpu() -> float:
    """CPU seconds (user + system) of all finished child processes so far."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def rule_cpu(results: Path) -> dict[str, tuple[int, float]]:
    """(jobs, CPU seconds) by rule from ``results/*/benchmarks/<rule>/...tsv``."""
    by_rule: dict[str, list[float]] = defaultdict(list)
    for tsv in results.glob("*/benchmarks/*/**/*.tsv"):
        rule = tsv.relative_to(results).parts[2]
        with open(tsv) as fh:
            rows = list(csv.DictReader(fh, delimiter="\t"))
        by_rule[rule] += [float(r["cpu_time"]) for r in rows]
    return {r: (len(v), sum(v)) for r, v in sorted(by_rule.items(), key=lambda kv: -sum(kv[1]))}


def run_once(work: Path, args, label: str) -> None:
    cmd = ["snakemake", "-c", str(args.cores), *([args.target] if args.target else [])]
    if args.configfile:     # after the target: --configfile takes every name that follows
        cmd += ["--configfile", args.configfile]
    # the copy's own sources: the Snakefile puts them first on the jobs' path, and the
    # logger plugin of the default profile (src/snakemake_logger_plugin_vines) is found there
    env = {**os.environ, "PYTHONPATH": str(work / "src")}
    load0 = os.getloadavg()[0]
    cpu0, t0 = children_cpu(), time.perf_counter()
    proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True)
    wall, cpu = time.perf_counter() - t0, children_cpu() - cpu0
    log = proc.stdout + proc.stderr
    if proc.returncode != 0:
        sys.exit(f"{label} run failed (exit {proc.returncode}):\n{log[-3000:]}")
    # one line per finished job: "[12/83] rule ..." (logger plugin vines), or Snakemake's own
    jobs = len(re.findall(r"^\[\s*\d+/\d+\] |^Finished job", log, flags=re.M))
    print(f"{label:5s}: wall {wall:7.1f} s, CPU {cpu:7.1f} s (all processes), {jobs} jobs, "
          f"load {load0:.1f} -> {os.getloadavg()[0]:.1f}")
    for rule, (n, sec) in rule_cpu(work / "results").items():
        print(f"        {rule:18s} {n:3d} jobs {sec:7.1f} CPU s")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configfile", default=None,
                    help="config for the run (default: the Snakefile's config/config.yaml)")
    ap.add_argument("--target", default=None,
                    help="target rule, e.g. all (default: the Snakefile's default, paper)")
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--runs", nargs="+", choices=("cold", "warm"), default=["cold", "warm"])
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="vines-bench-") as tmp:
        work = Path(tmp)
        copy_checkout(work)
        target = f" {args.target}" if args.target else ""
        config = f" --configfile {args.configfile}" if args.configfile else ""
        print(f"snakemake -c {args.cores}{target}{config} in a fresh copy; "
              f"{os.cpu_count()} CPUs on this machine")
        if args.runs[0] == "warm":
            run_once(work, args, "setup")        # fills the numba cache; not a measurement
        for label in args.runs:
            shutil.rmtree(work / "results", ignore_errors=True)
            run_once(work, args, label)


if __name__ == "__main__":
    main()
