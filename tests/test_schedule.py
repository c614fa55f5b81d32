"""The schedule model of benchmarks/bench_schedule.py (snakemake_logger_plugin_vines.schedule):
list schedules of small DAGs worked out by hand, the bounds every greedy list schedule
obeys, the chunking model, and the DAG read from a real ``snakemake -n``."""
import random
import shutil
import subprocess
import sys

import pytest

from snakemake_logger_plugin_vines.schedule import (
    Job,
    critical_path,
    jobs_from_dry_run,
    list_schedule,
    split,
)

# A (4 s) and B (3 s on 2 threads) feed C (2 s); D (1 s) stands alone.
DIAMOND = [Job("A", "a", 4.0), Job("B", "b", 3.0, threads=2),
           Job("C", "c", 2.0, deps=("A", "B")), Job("D", "d", 1.0)]


def test_two_cores_a_job_that_does_not_fit_lets_a_smaller_one_past():
    # t=0: A (longest path 6) starts, B (2 threads) does not fit, D does; t=4: B; t=7: C
    s = list_schedule(DIAMOND, 2)
    assert s.start == {"A": 0.0, "D": 0.0, "B": 4.0, "C": 7.0}
    assert s.wall == 9.0
    assert s.efficiency == pytest.approx(13.0 / 18.0)      # 4 + 2*3 + 2 + 1 core-seconds


def test_three_cores_reach_the_critical_path():
    # t=0: A and B fill 3 cores; t=3: D; t=4: C after A and B
    s = list_schedule(DIAMOND, 3)
    assert s.start == {"A": 0.0, "B": 0.0, "D": 3.0, "C": 4.0}
    assert s.wall == 6.0
    assert [j.name for j in critical_path(DIAMOND)] == ["A", "C"]


def test_longest_path_first():
    # X (1 s) -> Y (10 s), Z1, Z2 (5 s each) on 2 cores: X before the Zs, then Y before Z2,
    # 11 s (the path X, Y); shortest-first would take 16 s
    jobs = [Job("X", "x", 1.0), Job("Y", "y", 10.0, deps=("X",)),
            Job("Z1", "z", 5.0), Job("Z2", "z", 5.0)]
    s = list_schedule(jobs, 2)
    assert s.start == {"X": 0.0, "Z1": 0.0, "Y": 1.0, "Z2": 5.0}
    assert s.wall == 11.0


def test_bad_dags_are_refused():
    with pytest.raises(ValueError, match="threads on 1 cores"):
        list_schedule(DIAMOND, 1)
    with pytest.raises(ValueError, match="unknown job 'Q'"):
        list_schedule([Job("P", "p", 1.0, deps=("Q",))], 2)
    with pytest.raises(ValueError, match="cycle"):
        list_schedule([Job("P", "p", 1.0, deps=("Q",)), Job("Q", "q", 1.0, deps=("P",))], 2)


def test_graham_bounds_on_random_dags():
    """max(CPU / cores, path) <= wall <= CPU / cores + path for one-thread jobs (Graham's
    bound of any greedy list schedule)."""
    rng = random.Random(7)
    for _ in range(200):
        n, cores = rng.randint(1, 25), rng.randint(1, 6)
        jobs = [Job(str(k), "r", rng.choice([0.5, 1.0, 2.0, 7.0]),
                    deps=tuple(str(d) for d in range(k) if rng.random() < 0.15))
                for k in range(n)]
        s = list_schedule(jobs, cores)
        path = sum(j.seconds for j in critical_path(jobs))
        cpu = sum(j.seconds for j in jobs)
        assert max(cpu / cores, path) - 1e-9 <= s.wall <= cpu / cores + path + 1e-9


def test_split_into_chunks_and_a_gather():
    # S (8 s) -> T (1 s); S as 4 chunks of 8/4 + 0.5 s and a gather of 0.5 s
    jobs = split([Job("S", "s", 8.0), Job("T", "t", 1.0, deps=("S",))], "s", 4, 0.5)
    assert len(jobs) == 6 and sum(j.seconds for j in jobs) == 4 * 2.5 + 0.5 + 1.0
    assert list_schedule(jobs, 4).wall == 4.0         # chunks 0-2.5, gather, T 3-4
    assert list_schedule(jobs, 2).wall == 6.5         # two rounds of chunks: 5, +0.5, +1
    assert list_schedule(jobs, 1).wall == 11.5
    with pytest.raises(ValueError, match=">= 1"):
        split(jobs, "s", 0)


SNAKEFILE = """
rule all:
    input: "c.txt"

rule a:
    output: "a.txt"
    benchmark: "bench/a.tsv"
    threads: 2
    shell: "touch {output}"

rule b:
    input: "a.txt"
    output: "b.txt"
    shell: "touch {output}"

rule c:
    input: "a.txt", "b.txt"
    output: "c.txt"
    shell: "touch {output}"
"""


@pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")
@pytest.mark.parametrize("groups", [(), ("--groups", "b=g", "c=g")])
def test_dag_from_a_real_dry_run(tmp_path, groups):
    """Edges, threads and benchmark paths as Snakemake plans them; jobs inside a group job
    (printed indented) count as jobs."""
    (tmp_path / "Snakefile").write_text(SNAKEFILE)
    r = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-F", "all", "--cores", "4",
                        "--workflow-profile", "none", *groups], cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    out = r.stdout + r.stderr
    if groups:
        assert "Group job g" in out
    jobs = {p.rule: p for p in jobs_from_dry_run(out)}
    assert set(jobs) == {"all", "a", "b", "c"}
    assert jobs["a"].threads == 2 and jobs["b"].threads == 1
    assert jobs["a"].benchmark == "bench/a.tsv" and jobs["b"].benchmark is None
    ids = {p.jobid: rule for rule, p in jobs.items()}
    assert {ids[d] for d in jobs["c"].deps} == {"a", "b"}
    assert {ids[d] for d in jobs["b"].deps} == {"a"} and jobs["a"].deps == ()
    assert {ids[d] for d in jobs["all"].deps} == {"c"}
