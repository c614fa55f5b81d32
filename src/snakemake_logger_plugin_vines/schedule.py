"""A run's DAG as a schedule: total CPU, critical path and a simulated list schedule.

Jobs are :class:`Job` records (seconds of wall time on their own ``threads`` cores, and the
names of the jobs they wait for). :func:`list_schedule` runs them on ``cores`` cores as
Snakemake's local scheduler does, greedily: whenever cores are free it starts the ready
jobs that fit, longest remaining path first (a job's path: its own seconds plus the longest
path of the jobs waiting for it), a job that does not fit letting smaller ones past. Nothing
else is modelled: no start-up of Snakemake, no waiting for the machine, no slower job when
its neighbours share the memory bus. :func:`jobs_from_dry_run` reads the jobs and their
dependencies from ``snakemake -n`` output; :func:`split` models a rule's jobs as chunks.
Standard library only (used by ``benchmarks/bench_schedule.py``).
"""
from __future__ import annotations

import heapq
import re
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Job:
    """One job: ``seconds`` of wall time on ``threads`` cores, after the jobs ``deps``."""

    name: str
    rule: str
    seconds: float
    threads: int = 1
    deps: tuple = ()

    @property
    def cpu(self) -> float:
        """Core-seconds the job holds."""
        return self.seconds * self.threads


@dataclass
class Schedule:
    """A simulated run: its wall seconds, on how many cores, and each job's start."""

    wall: float
    cores: int
    cpu: float
    start: dict = field(default_factory=dict)

    @property
    def efficiency(self) -> float:
        """Busy share of the cores over the run: cpu / (cores x wall)."""
        return self.cpu / (self.cores * self.wall) if self.wall > 0 else 1.0


def _check(jobs: list[Job]) -> dict[str, Job]:
    """{name: job}; ValueError for a duplicate name or an unknown dependency."""
    by_name = {}
    for job in jobs:
        if job.name in by_name:
            raise ValueError(f"job {job.name!r} given twice")
        by_name[job.name] = job
    for job in jobs:
        for dep in job.deps:
            if dep not in by_name:
                raise ValueError(f"job {job.name!r} waits for unknown job {dep!r}")
    return by_name


def _waiting(jobs: list[Job]) -> dict[str, list]:
    """{name: names of the jobs that wait for it}."""
    waiting = {job.name: [] for job in jobs}
    for job in jobs:
        for dep in job.deps:
            waiting[dep].append(job.name)
    return waiting


def _topological(by_name: dict[str, Job]) -> list[str]:
    """Names in an order where every job comes after its deps; ValueError on a cycle."""
    order, state = [], {}

    def visit(name):
        stack = [(name, iter(by_name[name].deps))]
        state[name] = 1
        while stack:
            node, deps = stack[-1]
            for dep in deps:
                if state.get(dep) == 1:
                    raise ValueError(f"dependency cycle through job {dep!r}")
                if dep not in state:
                    state[dep] = 1
                    stack.append((dep, iter(by_name[dep].deps)))
                    break
            else:
                stack.pop()
                state[node] = 2
                order.append(node)

    for name in sorted(by_name):
        if name not in state:
            visit(name)
    return order


def path_lengths(jobs: list[Job]) -> dict[str, float]:
    """{name: seconds of the longest path from the job's start to the end of the DAG}."""
    by_name = _check(jobs)
    waiting = _waiting(jobs)
    length = {}
    for name in reversed(_topological(by_name)):
        length[name] = by_name[name].seconds + max((length[w] for w in waiting[name]),
                                                    default=0.0)
    return length


def critical_path(jobs: list[Job]) -> list[Job]:
    """The jobs of the longest path through the DAG, in order (no job: ``[]``)."""
    by_name = _check(jobs)
    length = path_lengths(jobs)
    waiting = _waiting(jobs)
    roots = [j.name for j in jobs if not j.deps]
    path, nxt = [], max(roots, key=lambda n: (length[n], n), default=None)
    while nxt is not None:
        path.append(by_name[nxt])
        nxt = max(waiting[nxt], key=lambda n: (length[n], n), default=None)
    return path


def list_schedule(jobs: list[Job], cores: int) -> Schedule:
    """Greedy list schedule of ``jobs`` on ``cores`` cores, longest path first (ties: more
    threads, then name). ValueError if a job asks for more threads than there are cores."""
    by_name = _check(jobs)
    for job in jobs:
        if not 1 <= job.threads <= cores:
            raise ValueError(f"job {job.name!r} asks for {job.threads} threads on "
                             f"{cores} cores")
    length = path_lengths(jobs)
    waiting = _waiting(jobs)
    missing = {j.name: len(set(j.deps)) for j in jobs}
    ready = [n for n, k in missing.items() if k == 0]
    running, start, now, free = [], {}, 0.0, cores
    while ready or running:
        ready.sort(key=lambda n: (-length[n], -by_name[n].threads, n))
        for name in list(ready):
            if by_name[name].threads <= free:
                ready.remove(name)
                free -= by_name[name].threads
                start[name] = now
                heapq.heappush(running, (now + by_name[name].seconds, name))
        now = running[0][0]
        while running and running[0][0] == now:
            _, name = heapq.heappop(running)
            free += by_name[name].threads
            for other in waiting[name]:
                missing[other] -= 1
                if missing[other] == 0:
                    ready.append(other)
    wall = max((start[j.name] + j.seconds for j in jobs), default=0.0)
    return Schedule(wall, cores, sum(j.cpu for j in jobs), start)


def split(jobs: list[Job], rule: str, n: int, overhead: float = 0.0) -> list[Job]:
    """A model of chunking ``rule``: each of its jobs becomes ``n`` chunk jobs of
    seconds / n + ``overhead`` on the same threads, after the job's deps, and a gather
    job of ``overhead`` seconds on one thread under the job's name (so the jobs that
    waited for it now wait for the gather). ``overhead``: a job's start-up seconds."""
    if n < 1:
        raise ValueError(f"split {rule}={n}: the number of chunks must be >= 1")
    out = []
    for job in jobs:
        if job.rule != rule or n == 1:
            out.append(job)
            continue
        chunks = [Job(f"{job.name} [chunk {k + 1}/{n}]", rule, job.seconds / n + overhead,
                      job.threads, job.deps) for k in range(n)]
        out += chunks
        out.append(Job(job.name, f"{rule} (gather)", overhead, 1,
                       tuple(c.name for c in chunks)))
    return out


# ------------------------------------------------------------------ snakemake -n output
_BLOCK = re.compile(r"^ *(?:local)?(?:rule|checkpoint) (\S+):$")
_ITEM = re.compile(r"^ +(input|output|jobid|benchmark|wildcards|threads): (.*)$")


@dataclass
class PlannedJob:
    """A job as ``snakemake -n`` prints it (Snakemake's own output, not the vines logger's:
    ``--workflow-profile none``)."""

    jobid: str
    rule: str
    inputs: tuple
    outputs: tuple
    benchmark: str | None
    wildcards: str
    threads: int
    deps: tuple = ()


def jobs_from_dry_run(text: str) -> list[PlannedJob]:
    """The jobs of a dry run's output and their dependencies: a job waits for the jobs that
    write its inputs. Group jobs' members count as jobs."""
    jobs, cur = [], None
    for line in text.splitlines():
        if m := _BLOCK.match(line):
            cur = {"rule": m.group(1)}
            jobs.append(cur)
        elif cur is not None and (m := _ITEM.match(line)):
            cur[m.group(1)] = m.group(2)
        elif not line.strip() or not line.startswith(" "):
            cur = None
    planned = [PlannedJob(j.get("jobid", ""), j["rule"], _files(j.get("input")),
                          _files(j.get("output")), j.get("benchmark"),
                          j.get("wildcards", ""), int(j.get("threads", 1)))
               for j in jobs]
    writer = {f: p.jobid for p in planned for f in p.outputs}
    for p in planned:
        p.deps = tuple(sorted({writer[f] for f in p.inputs if f in writer}))
    return planned


def _files(value: str | None) -> tuple:
    return tuple(v for v in (value or "").split(", ") if v)
