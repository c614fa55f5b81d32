"""The cost estimate of a dry run (``snakemake -n``), from measured job times.

A planned job's cost is the CPU time of a measured run of it, taken in this order: its own
benchmark file in ``results/<run>/benchmarks/`` (the last run of that very job), the mean
over the benchmark files of its rule in the same run, the costs shipped in ``measured.py``
(measured on the named runs). The estimate is the planned jobs' CPU time spread over the
cores, and at least the longest job's wall time: an estimate, exact only when the jobs
pack perfectly and the machine is as fast as the measured one. Jobs without a benchmark
(figures, targets) are not counted; the message says how many.

Regenerate the shipped costs from finished runs (their benchmark files)::

    python -m snakemake_logger_plugin_vines.cost results/paper results/smoke
"""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from pathlib import Path

from .measured import MEASURED, SOURCE


@dataclass(frozen=True)
class Cost:
    """CPU seconds of one job and its wall seconds."""
    cpu: float
    wall: float


def read_benchmark(path) -> Cost | None:
    """The (last) row of a Snakemake benchmark file, or None if unreadable."""
    try:
        head, *rows = Path(path).read_text().splitlines()
        row = dict(zip(head.split("\t"), rows[-1].split("\t"), strict=True))
        return Cost(cpu=float(row["cpu_time"]), wall=float(row["s"]))
    except (OSError, ValueError, KeyError, IndexError):
        return None


def rule_costs(run_dir) -> dict:
    """{rule: (jobs, mean CPU seconds, longest wall seconds)} of a run's benchmark files."""
    out = {}
    bench = Path(run_dir) / "benchmarks"
    for rule_dir in sorted(p for p in bench.glob("*") if p.is_dir()):
        costs = [c for c in map(read_benchmark, sorted(rule_dir.rglob("*.tsv"))) if c]
        if costs:
            out[rule_dir.name] = (len(costs), round(sum(c.cpu for c in costs) / len(costs), 2),
                                  round(max(c.wall for c in costs), 2))
    return out


def run_of(benchmark: str) -> str | None:
    """``results/<run>`` of a benchmark path ``results/<run>/benchmarks/...``."""
    parts = Path(benchmark).parts
    return str(Path(*parts[:parts.index("benchmarks")])) if "benchmarks" in parts else None


def cores_of(argv) -> int:
    """Cores of a Snakemake command line (``-c2``, ``--cores 2``, ``-j 2``; all cores for
    ``all`` or none given)."""
    value = None
    for k, arg in enumerate(argv):
        for flag in ("-c", "--cores", "-j", "--jobs"):
            if arg == flag and k + 1 < len(argv):
                value = argv[k + 1]
            elif arg.startswith(flag + "=") or (flag in ("-c", "-j") and arg[:2] == flag
                                                 and arg[2:].isdigit()):
                value = arg[len(flag):].lstrip("=")
    return int(value) if value and value.isdigit() and int(value) > 0 else os.cpu_count() or 1


def _minutes(seconds: float) -> str:
    return f"{seconds / 60:.0f} min" if seconds >= 90 else f"{seconds:.0f} s"


def estimate(jobs, cores: int, measured=MEASURED) -> str:
    """The estimate sentence for planned ``jobs``: (rule, benchmark path or None) pairs."""
    found = {"own": 0, "rule": 0, "shipped": 0}
    cpu = longest = 0.0
    unbenchmarked = unknown = 0
    runs, own_rules = set(), {}
    for rule, benchmark in jobs:
        if not benchmark:
            unbenchmarked += 1
            continue
        run = run_of(benchmark)
        runs.add(run)
        if run not in own_rules:
            own_rules[run] = rule_costs(run) if run else {}
        cost, kind = read_benchmark(benchmark), "own"
        if cost is None and rule in own_rules[run]:
            _, mean, wall = own_rules[run][rule]
            cost, kind = Cost(mean, wall), "rule"
        name = Path(run).name if run else ""
        if cost is None and rule in measured.get(name, {}):
            _, mean, wall = measured[name][rule]
            cost, kind = Cost(mean, wall), "shipped"
        if cost is None:
            unknown += 1
            continue
        found[kind] += 1
        cpu += cost.cpu
        longest = max(longest, cost.wall)
    return _sentence(found, cpu, longest, cores, sorted(r for r in runs if r),
                     unbenchmarked, unknown)


def _sentence(found, cpu, longest, cores, runs, unbenchmarked, unknown) -> str:
    counted = sum(found.values())
    if not counted:
        return ("Cost estimate: none (no benchmark files of an earlier run of these jobs and "
                "no shipped costs for this run).")
    where = []
    if found["own"] or found["rule"]:
        where.append(f"the benchmark files of {', '.join(runs)} ({found['own']} jobs their own"
                     f" last run, {found['rule']} the mean of their rule there)")
    if found["shipped"]:
        where.append(f"the costs shipped with vines for {found['shipped']} jobs ({SOURCE})")
    left = [f"{n} {what}" for n, what in ((unbenchmarked, "jobs without benchmark (figures, "
                                                           "targets; seconds each)"),
                                          (unknown, "jobs never measured")) if n]
    return (f"Cost estimate: about {_minutes(max(cpu / cores, longest))} on {cores} cores "
            f"for {counted} jobs ({_minutes(cpu)} CPU), measured from "
            f"{' and '.join(where)}. An estimate: the jobs' CPU time over the cores, on a "
            "machine as fast as the measured one; not counted: "
            f"{', '.join(left + ['the numba compilation when its cache is cold'])}.")


def main(argv=None) -> int:
    """Print the ``MEASURED`` table of the runs given (for measured.py)."""
    args = sys.argv[1:] if argv is None else argv
    table = {Path(run).name: rule_costs(run) for run in args}
    print("MEASURED = {")
    for run, rules in table.items():
        print(f"    {run!r}: {{")
        for rule, cost in rules.items():
            print(f"        {rule!r}: {cost},")
        print("    },")
    print("}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
