"""How a finished run's jobs would pack on more cores: total CPU, the critical path of its
DAG and a simulated list schedule per core count, from the jobs' benchmark files.

Run from the repository root: python benchmarks/bench_schedule.py RUN [--cores 2 4 8 16 64]
    [--configfile config/config.yaml] [--target all] [--workflow DIR] [--split RULE=N ...]
    [--overhead S] [--other-seconds S]
RUN: a finished run's results folder (``results/<run>``, holding ``benchmarks/<rule>/...tsv``,
written by every compute rule's ``benchmark:``), read only.

The DAG is Snakemake's: ``snakemake -n -F TARGET --cores C`` on the Snakefile of this
checkout (or of the checkout ``--workflow DIR``, e.g. the one RUN was made with) and
CONFIGFILE (with ``run`` set to a name of its own, so nothing of RUN is touched), once per
core count (a job's threads are capped at the cores); a job waits for the jobs that write
its inputs. The schedule (snakemake_logger_plugin_vines.schedule) is greedy, longest path first,
each job holding its threads' cores; Snakemake's own start-up, the numba warm-up and the
waits of a loaded machine are not in it. A job's seconds, three models side by side:
``ideal threads`` its measured ``cpu_time`` / threads (every thread busy: a lower bound),
``no thread speed-up`` its ``cpu_time`` (threads that do not help), ``as measured`` its wall
time ``s`` (on the measuring machine, under its load). Jobs without a benchmark file (the
figures) take ``--other-seconds`` on one thread (default: the mean figure job shipped for the
run's name in ``snakemake_logger_plugin_vines.measured``). ``--split RULE=N`` is a MODEL, not
a measurement: every job of RULE becomes N equal chunk jobs (same threads) and a one-thread
gather, each ``--overhead`` seconds longer (a job's start-up; default 1 s, about the CPU time
of the shortest jobs that load the compiled kernels), to see what chunking a stage would
give before rerunning it. A RUN made before a stage was split into chunk jobs (its entries
measured whole, ``benchmarks/<stage>/<entry>.tsv``) on a DAG that has them (rule
``<stage>_chunk``) is modelled the same way with the DAG's own chunk counts: each chunk job
1/n of its entry + ``--overhead``, the gather ``--overhead``. Nothing is asserted.
"""
from __future__ import annotations

import argparse
import csv
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from snakemake_logger_plugin_vines.measured import FIGURE_SECONDS  # noqa: E402
from snakemake_logger_plugin_vines.schedule import (  # noqa: E402
    Job,
    critical_path,
    jobs_from_dry_run,
    list_schedule,
    split,
)

#: the run name of the dry runs (their paths are mapped onto RUN)
DRY_RUN = "bench_schedule_dag"


class InputError(Exception):
    """A bad argument or run folder: one line, exit 2."""


def measured(run: Path) -> dict[str, dict[str, float]]:
    """{path below RUN: last row of the benchmark file} of every ``benchmarks/**/*.tsv``."""
    out = {}
    for tsv in sorted((run / "benchmarks").rglob("*.tsv")):
        with open(tsv) as fh:
            rows = list(csv.DictReader(fh, delimiter="\t"))
        if rows:
            out[str(tsv.relative_to(run))] = {k: float(rows[-1][k]) for k in ("s", "cpu_time")}
    return out


def dry_run(workflow: Path, configfile: str, target: str, cores: int) -> str:
    """Snakemake's plan of every job of ``target`` in the checkout ``workflow`` (forced: as
    if nothing existed)."""
    cmd = [sys.executable, "-m", "snakemake", "-n", "-F", target, "--cores", str(cores),
           "--workflow-profile", "none", "--configfile", configfile,
           "--config", f"run={DRY_RUN}"]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(workflow / "src")] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep)
                               if p]))
    r = subprocess.run(cmd, cwd=workflow, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise InputError(f"snakemake -n failed ({' '.join(cmd[1:])}): "
                         f"{(r.stderr or r.stdout).strip().splitlines()[-1:]}")
    return r.stdout + r.stderr


#: job seconds of each model from a job's measured (cpu_time, wall s) and its threads
MODELS = {
    "ideal threads": lambda cpu, wall, threads: cpu / threads,
    "no thread speed-up": lambda cpu, wall, threads: cpu,
    "as measured": lambda cpu, wall, threads: wall,
}


def _whole_entries(work, bench: dict, prefix: str) -> dict:
    """{(stage, entry): planned chunk jobs} of the entries whose chunk jobs (rule
    ``<stage>_chunk``, benchmark ``benchmarks/<stage>_chunk/<entry>/<k>.tsv``) were not
    measured but whose stage was, as one job (``benchmarks/<stage>/<entry>.tsv``): a run
    made before the stage was split into chunk jobs."""
    out = {}
    for p in work:
        rel = Path(p.benchmark.removeprefix(prefix)) if p.benchmark else None
        if p.rule.endswith("_chunk") and rel and str(rel) not in bench:
            stage, entry = p.rule.removesuffix("_chunk"), rel.parent.name
            if f"benchmarks/{stage}/{entry}.tsv" in bench:
                out[stage, entry] = out.get((stage, entry), 0) + 1
    return out


def run_jobs(text: str, bench: dict, other: float, overhead: float) -> tuple[dict, dict]:
    """{model: jobs with its seconds}, and counts of where the seconds came from. A chunk
    job of an entry measured whole (:func:`_whole_entries`) is modelled: 1/n of the entry
    and ``overhead``; its gather ``overhead``."""
    prefix = f"results/{DRY_RUN}/"
    planned = jobs_from_dry_run(text)
    ids = {p.jobid: f"{p.rule} {p.wildcards}".strip() for p in planned}
    work = [p for p in planned if p.outputs]    # a target rule (all, paper): no work of its own
    keep = {p.jobid for p in work}
    whole = _whole_entries(work, bench, prefix)
    found, missing, rows = {"benchmark": 0, "other": 0, "modelled": 0}, [], []
    for p in work:
        rel = Path(p.benchmark.removeprefix(prefix)) if p.benchmark else None
        n, extra = 1, 0.0
        if rel and p.rule.endswith("_chunk") and (p.rule[:-6], rel.parent.name) in whole:
            n, extra = whole[p.rule[:-6], rel.parent.name], overhead
            row = bench[f"benchmarks/{p.rule[:-6]}/{rel.parent.name}.tsv"]
            cpu, wall = row["cpu_time"], row["s"]
            found["modelled"] += 1
        elif rel and (p.rule, rel.stem) in whole:       # the gather of such an entry
            cpu = wall = 0.0
            extra = overhead
            found["modelled"] += 1
        elif rel:
            row = bench.get(str(rel))
            if row is None:
                missing.append(str(rel))
                continue
            found["benchmark"] += 1
            cpu, wall = row["cpu_time"], row["s"]
        else:
            found["other"] += 1
            cpu = wall = other
        rows.append((p, cpu, wall, n, extra))
    if missing:
        raise InputError(f"no benchmark file for {len(missing)} planned jobs (first: "
                         f"{missing[0]}): was RUN made with this config and target?")
    jobs = {model: [Job(ids[p.jobid], p.rule, seconds(cpu, wall, p.threads) / n + extra,
                        p.threads, tuple(ids[d] for d in p.deps if d in keep))
                    for p, cpu, wall, n, extra in rows]
            for model, seconds in MODELS.items()}
    return jobs, found


def parse_splits(items: list[str]) -> list[tuple[str, int]]:
    out = []
    for item in items:
        rule, _, n = item.partition("=")
        if not rule or not n.isdigit() or int(n) < 1:
            raise InputError(f"--split {item!r}: expected RULE=N with N a whole number >= 1")
        out.append((rule, int(n)))
    return out


def _minutes(seconds: float) -> str:
    return f"{int(seconds // 60)} min {seconds % 60:4.1f} s" if seconds >= 60 else \
        f"{seconds:.1f} s"


def report(args) -> None:
    run = Path(args.run)
    if not (run / "benchmarks").is_dir():
        raise InputError(f"RUN {run}: no benchmarks/ folder (expected a finished run's "
                         "results/<run>)")
    bench = measured(run)
    splits = parse_splits(args.split)
    other = args.other_seconds
    if other is None:
        other = FIGURE_SECONDS.get(run.name, sum(FIGURE_SECONDS.values()) / len(FIGURE_SECONDS))
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"run {run}: {len(bench)} benchmark files; DAG of `{args.target}` "
          f"({args.configfile}) from snakemake -n; load {load} (a computation, not a timing)")
    if splits:
        print("MODEL, not a measurement: " + ", ".join(f"{r} as {n} chunks" for r, n in splits)
              + f" (+{args.overhead:g} s start-up a chunk; a gather of {args.overhead:g} s)")
    rows = []
    for cores in args.cores:
        jobs, found = run_jobs(dry_run(args.workflow, args.configfile, args.target, cores), bench, other,
                               args.overhead)
        for rule, n in splits:
            if not any(j.rule == rule for j in jobs[next(iter(MODELS))]):
                raise InputError(f"--split {rule}={n}: no job of rule {rule!r} in the DAG")
            jobs = {m: split(js, rule, n, args.overhead) for m, js in jobs.items()}
        rows.append((cores, {m: (js, list_schedule(js, cores)) for m, js in jobs.items()}))
    _print(rows, found, other)


def _print(rows, found, other) -> None:
    cores, by_model = rows[-1]
    jobs, sched = by_model["ideal threads"]   # its core-seconds: the measured cpu_time
    print(f"jobs: {len(jobs)} ({found['benchmark']} with a benchmark file, {found['other']} "
          f"without, at {other:g} s on one thread)")
    if found["modelled"]:
        print(f"MODEL, not a measurement: {found['modelled']} jobs of stages that RUN measured "
              "as one job an entry: each chunk job 1/n of its entry + --overhead, the gather "
              "--overhead")
    print(f"total CPU: {sched.cpu:.0f} s ({sched.cpu / 60:.1f} min)")
    for model, (jobs, _) in by_model.items():
        path = critical_path(jobs)
        print(f"critical path ({model}, {cores} cores): "
              f"{_minutes(sum(j.seconds for j in path))}: "
              + ", ".join(f"{j.name} ({j.seconds:.0f} s on {j.threads})" for j in path))
    print("| cores | " + " | ".join(f"{m}: wall, efficiency" for m in MODELS) + " |")
    print("|---|" + "---|" * len(MODELS))
    for cores, by_model in rows:
        print(f"| {cores} | " + " | ".join(
            f"{_minutes(s.wall)}, {100 * s.efficiency:.0f} %" for _, s in by_model.values())
            + " |")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="a finished run's results/<run> folder (read only)")
    ap.add_argument("--cores", type=int, nargs="+", default=[2, 4, 8, 16, 64])
    ap.add_argument("--configfile", default="config/config.yaml",
                    help="the config the run was made with (default config/config.yaml)")
    ap.add_argument("--target", default="all", help="the run's target (default all)")
    ap.add_argument("--workflow", type=Path, default=ROOT,
                    help="the checkout whose Snakefile plans the DAG (default: this one)")
    ap.add_argument("--split", nargs="*", default=[], metavar="RULE=N")
    ap.add_argument("--overhead", type=float, default=1.0,
                    help="start-up seconds of a chunk or gather job (--split; default 1)")
    ap.add_argument("--other-seconds", type=float, default=None,
                    help="seconds of a job without a benchmark file (figures)")
    args = ap.parse_args(argv)
    try:
        if any(c < 1 for c in args.cores):
            raise InputError(f"--cores {args.cores}: every core count must be >= 1")
        if args.overhead < 0 or (args.other_seconds is not None and args.other_seconds < 0):
            raise InputError("--overhead and --other-seconds must be >= 0")
        if not (args.workflow / "Snakefile").is_file():
            raise InputError(f"--workflow {args.workflow}: no Snakefile there")
        report(args)
    except InputError as err:
        print(f"bench_schedule: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("bench_schedule: interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
