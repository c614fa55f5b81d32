"""The cost estimate of a dry run (``snakemake -n``), from measured job times.

A planned job's cost is the wall time of a measured run of it, taken in this order: its
own benchmark file in ``results/<run>/benchmarks/`` (the last run of that very job), the
mean over the benchmark files of its rule in the same run, the costs shipped in
``measured.py`` (measured on the named runs); a figure job (no benchmark file) costs the
mean figure job of ``measured.FIGURE_SECONDS``. Where the shipped costs of a run measured a
chunked stage as one job per entry (``measured.WHOLE``), each chunk job of an entry
(rule ``<stage>_chunk``) costs the stage's mean entry over the entry's planned chunk jobs, and
the stage's gather job the mean gather of grid chunks (rule ``extract_measures``). A job of k threads takes k of the cores
for its time: the estimate is the sum of time x threads over the cores, at least the
longest job. An estimate: exact only when the jobs pack perfectly and the machine is as
fast and as loaded as the measured one.

Regenerate the shipped costs from finished runs (their benchmark files, and the figure job
times of their console logs)::

    python -m snakemake_logger_plugin_vines.cost results/paper:paper.log results/smoke:smoke.log
"""
from __future__ import annotations

import os
import re
import sys
from pathlib import Path

from .measured import FIGURE_SECONDS, MEASURED, NOT_COUNTED, SOURCE, WHOLE


def read_benchmark(path) -> float | None:
    """Wall seconds (column ``s``) of the last row of a Snakemake benchmark file, or None."""
    try:
        head, *rows = Path(path).read_text().splitlines()
        row = dict(zip(head.split("\t"), rows[-1].split("\t"), strict=True))
        return float(row["s"])
    except (OSError, ValueError, KeyError, IndexError):
        return None


def rule_costs(run_dir) -> dict:
    """{rule: (jobs, mean wall seconds, longest wall seconds)} of a run's benchmark files."""
    out = {}
    bench = Path(run_dir) / "benchmarks"
    for rule_dir in sorted(p for p in bench.glob("*") if p.is_dir()):
        times = [t for t in map(read_benchmark, sorted(rule_dir.rglob("*.tsv"))) if t is not None]
        if times:
            out[rule_dir.name] = (len(times), round(sum(times) / len(times), 2),
                                  round(max(times), 2))
    return out


def run_of(benchmark: str | None, output: str | None) -> str | None:
    """``results/<run>`` of a job: the folder above ``benchmarks/`` in its benchmark path,
    else the first two parts of its first output (``results/<run>/...``)."""
    if benchmark and "benchmarks" in Path(benchmark).parts:
        parts = Path(benchmark).parts
        return str(Path(*parts[:parts.index("benchmarks")]))
    parts = Path(output).parts if output else ()
    return str(Path(*parts[:2])) if len(parts) > 2 else None


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
    return f"{seconds / 60:.0f} min" if seconds >= 120 else f"{seconds:.0f} s"


def chunk_counts(jobs) -> dict:
    """{(stage, entry benchmark folder): planned chunk jobs} of the ``<stage>_chunk`` jobs
    (benchmark ``.../benchmarks/<stage>_chunk/<entry>/<k>.tsv``)."""
    out = {}
    for rule, benchmark, _, _ in jobs:
        if rule.endswith("_chunk") and benchmark:
            key = (rule.removesuffix("_chunk"), str(Path(benchmark).parent))
            out[key] = out.get(key, 0) + 1
    return out


def _entry_chunks(rule, benchmark, chunks) -> int:
    """Planned chunk jobs of the entry of a chunk job, or of a gather job (0: none)."""
    if not benchmark:
        return 0
    if rule.endswith("_chunk"):
        return chunks.get((rule.removesuffix("_chunk"), str(Path(benchmark).parent)), 0)
    entry = Path(benchmark)
    folder = entry.parent.parent / f"{rule}_chunk" / entry.stem
    return chunks.get((rule, str(folder)), 0)


def _split_whole(shipped: dict, whole, rule, benchmark, chunks) -> dict:
    """The shipped costs of a run, with those of a stage measured as whole entries
    (``whole``) split over the planned chunk jobs of the entry of ``rule``'s job."""
    stage = rule.removesuffix("_chunk")
    n = _entry_chunks(rule, benchmark, chunks)
    if stage not in whole or stage not in shipped or not n:
        return shipped
    jobs, mean, longest = shipped[stage]
    if rule.endswith("_chunk"):
        return {**shipped, rule: (jobs, round(mean / n, 2), round(longest / n, 2))}
    gather = shipped.get("extract_measures")
    return {k: v for k, v in shipped.items() if k != stage} | (
        {stage: gather} if gather else {})


def estimate(jobs, cores: int, measured=None, figures=None, whole=None) -> str:
    """The estimate sentence for planned ``jobs``: (rule, benchmark path or None, first
    output or None, threads) tuples; ``measured``, ``figures``, ``whole``: the shipped
    costs (default ``MEASURED``, ``FIGURE_SECONDS``, ``WHOLE``)."""
    measured = MEASURED if measured is None else measured
    figures = FIGURE_SECONDS if figures is None else figures
    whole = WHOLE if whole is None else whole
    found = {"own": 0, "rule": 0, "shipped": 0, "figure": 0}
    core_seconds = longest = 0.0
    runs, own_rules, unknown = set(), {}, 0
    chunks = chunk_counts(jobs)
    for rule, benchmark, output, threads in jobs:
        run = run_of(benchmark, output)
        if run is None:            # a target rule (all, paper, figures): no work of its own
            continue
        runs.add(run)
        if run not in own_rules:
            own_rules[run] = rule_costs(run)
        name = Path(run).name
        shipped = _split_whole(measured.get(name, {}), whole.get(name, ()), rule, benchmark,
                               chunks)
        seconds, kind = _job_seconds(rule, benchmark, own_rules[run], name,
                                     {**measured, name: shipped}, figures)
        if seconds is None:
            unknown += 1
            continue
        found[kind] += 1
        core_seconds += seconds * min(max(int(threads or 1), 1), cores)
        longest = max(longest, seconds)
    return _sentence(found, max(core_seconds / cores, longest), cores, sorted(runs), unknown)


def _job_seconds(rule, benchmark, own, name, measured, figures):
    """(wall seconds, where from) of one job, or (None, "")."""
    if benchmark:
        seconds = read_benchmark(benchmark)
        if seconds is not None:
            return seconds, "own"
        if rule in own:
            return own[rule][1], "rule"
        if rule in measured.get(name, {}):
            return measured[name][rule][1], "shipped"
    elif rule.startswith("fig") and name in figures:
        return figures[name], "figure"
    return None, ""


def _sentence(found, seconds, cores, runs, unknown) -> str:
    counted = sum(found.values())
    if not counted:
        return ("Cost estimate: none (no benchmark files of an earlier run of these jobs and "
                "no shipped costs for this run).")
    where = []
    if found["own"] or found["rule"]:
        parts = [f"{n} {what}" for n, what in ((found["own"], "jobs from their own last run"),
                                               (found["rule"], "at the mean of their rule "
                                                               "there")) if n]
        where.append(f"the benchmark files of {', '.join(runs)} ({', '.join(parts)})")
    if found["shipped"]:
        where.append(f"the costs shipped with vines for {found['shipped']} jobs")
    if found["figure"]:
        where.append(f"the mean figure job for {found['figure']} figures")
    shipped = f" ({SOURCE})" if found["shipped"] or found["figure"] else ""
    left = [f"{unknown} jobs never measured"] if unknown else []
    return (f"Cost estimate: about {_minutes(seconds)} on {cores} cores for {counted} jobs, "
            f"from their measured times: {'; '.join(where)}{shipped}. An estimate: each job "
            "takes its threads' share of the cores, on a machine as fast and as loaded as the "
            f"measured one; not counted: {', '.join(left + [NOT_COUNTED])}.")


def figure_seconds(console: str) -> float | None:
    """Mean seconds of the figure jobs (rules fig*) in a console log, or None without any:
    this plugin's lines ("[ 3/9] fig7 (2.1 s)") or Snakemake's own log
    (.snakemake/log/*.snakemake.log: a job's start and "Finished jobid" times, to the
    second)."""
    times = [float(t) for t in re.findall(r"^\[ *\d+/\d+\] fig\S* .*?\(([\d.]+) s\)$",
                                          console, re.M)]
    times += _snakemake_log_seconds(console, "fig")
    return round(sum(times) / len(times), 1) if times else None


def _snakemake_log_seconds(text: str, prefix: str) -> list:
    """Durations of the jobs of rules ``prefix*`` in Snakemake's own log format."""
    from datetime import datetime
    out, started, stamp, rule = [], {}, None, None
    for line in text.splitlines():
        if m := re.fullmatch(r"\[(\w{3} \w{3} +\d+ [\d:]+ \d{4})\]", line):
            stamp = datetime.strptime(m.group(1), "%a %b %d %H:%M:%S %Y")
        elif m := re.fullmatch(r"(?:local)?rule (\S+):", line):
            rule = m.group(1)
        elif (m := re.fullmatch(r"    jobid: (\d+)", line)) and rule and stamp:
            started[m.group(1)] = (rule, stamp)
        elif (m := re.match(r"Finished jobid: (\d+)", line)) and m.group(1) in started:
            rule, start = started.pop(m.group(1))
            if rule.startswith(prefix) and stamp:
                out.append((stamp - start).total_seconds())
    return out


def main(argv=None) -> int:
    """Print the tables of measured.py from runs given as RUN_DIR[:CONSOLE_LOG] (the
    benchmark files of the run; the figure job lines of its console log)."""
    args = sys.argv[1:] if argv is None else argv
    measured, figures = {}, {}
    for arg in args:
        run, _, console = arg.partition(":")
        measured[Path(run).name] = rule_costs(run)
        if console and (f := figure_seconds(Path(console).read_text())) is not None:
            figures[Path(run).name] = f
    print("MEASURED = {")
    for run, rules in measured.items():
        print(f"    {run!r}: {{")
        for rule, cost in rules.items():
            print(f"        {rule!r}: {cost},")
        print("    },")
    print("}")
    print(f"FIGURE_SECONDS = {figures!r}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
