"""Peak memory and wall time per rule of a finished run, from its jobs' benchmark files, and
the resources the rules declare from them.

Run: python benchmarks/rule_resources.py RESULTS [RESULTS ...]
RESULTS: a run's results folder (``results/<run>``, holding ``benchmarks/<rule>/...tsv``).
Prints per rule: jobs, the largest ``max_rss`` (MB) and ``s`` (wall seconds) of its jobs,
and ``mem_mb`` = MEM_MARGIN x max_rss rounded up to 100 MB, ``runtime`` = TIME_MARGIN x s
in whole minutes, at least MIN_RUNTIME: the values of the rules' ``resources:``
(docs/performance.md says why these margins). Nothing is asserted. The chunk jobs of a
chunked stage are a rule of their own (``<stage>_chunk``, files under
``benchmarks/<stage>_chunk/<entry>/``), its gather the stage's rule; a run from before the
split measured the stage as whole entries under the stage's rule (the ``WHOLE`` runs of
``snakemake_logger_plugin_vines.measured``).
"""
import argparse
import csv
import math
from collections import defaultdict
from pathlib import Path

#: memory margin: more threads than the measured jobs' two (each holds one block of points
#: in flight, small against the 160-220 MB of interpreter, libraries and compiled kernels
#: every job holds), other library versions
MEM_MARGIN = 2.0
#: time margin: one thread instead of the measured two, on a node 1.5x slower
TIME_MARGIN = 3.0
MIN_RUNTIME = 5


def rule_peaks(results: list[Path]) -> dict[str, tuple[int, float, float]]:
    """(jobs, max max_rss in MB, max s) by rule over ``<results>/benchmarks/<rule>/**.tsv``."""
    rows = defaultdict(list)
    for res in results:
        for tsv in (res / "benchmarks").glob("*/**/*.tsv"):
            rule = tsv.relative_to(res / "benchmarks").parts[0]
            with open(tsv) as fh:
                rows[rule] += list(csv.DictReader(fh, delimiter="\t"))
    return {rule: (len(r), max(float(x["max_rss"]) for x in r), max(float(x["s"]) for x in r))
            for rule, r in sorted(rows.items())}


def declared(rss_mb: float, seconds: float) -> tuple[int, int]:
    """(mem_mb, runtime in minutes) a rule declares for these peaks."""
    mem = 100 * math.ceil(MEM_MARGIN * rss_mb / 100.0)
    return mem, max(MIN_RUNTIME, math.ceil(TIME_MARGIN * seconds / 60.0))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="+", type=Path, help="results/<run> folder(s)")
    args = ap.parse_args(argv)
    print("| rule | jobs | peak memory (max_rss, MB) | longest job (s) | mem_mb | runtime (min) |")
    print("|---|---|---|---|---|---|")
    for rule, (n, rss, s) in rule_peaks(args.results).items():
        mem, minutes = declared(rss, s)
        print(f"| {rule} | {n} | {rss:.0f} | {s:.1f} | {mem} | {minutes} |")


if __name__ == "__main__":
    main()
