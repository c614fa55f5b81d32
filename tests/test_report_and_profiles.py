"""`snakemake --report`, the default profile and the SLURM profile (no SLURM needed).

`work_precision` takes every core of a local run; commands without a core count (--report,
--profile profiles/slurm) must still parse. Runs on a copy of the workflow in tmp_path (the
helpers of tests/test_pipeline.py), never in results/.
"""
import re
import shutil
import subprocess

import pytest
import yaml
from test_pipeline import ROOT, SNAKEMAKE, TINY, _copy_workflow, _smk, needs_snakemake

# one figure (fig2) and one tiny work-precision case: the report holds their captions
REPORT_CFG = dict(
    TINY, run="report", grids={"fig2_F0.05": {"axes": {"eta": [0.05, 0.1]},
                                              "fixed": {"omega": 1.0, "F": 0.05}}},
    sweeps={}, timehistories={},
    work_precision={"cases": {"tiny": {"eta": 0.05, "omega": 1.0, "F": 0.05, "t_end": 20.0,
                                       "t_transient": 10.0}},
                    "root_tols": [1e-9], "rk_methods": ["RK45"], "rtols": [1e-6],
                    "min_time": 0.001, "dps": 20})


#: the default profile (profiles/default) hides the job blocks `_threads` reads
JOB_BLOCKS = ("--workflow-profile", "none")


def _blocks(out: str, rule: str) -> list:
    """The job blocks a dry-run prints for `rule` (indented inside a group job)."""
    return re.findall(rf"\n *rule {rule}:\n(.*?)(?:\n\n|\Z)", out, re.S)


def _threads(out: str, rule: str) -> set:
    """Thread counts a dry-run prints for the jobs of `rule` (1 is not printed)."""
    blocks = _blocks(out, rule)
    assert blocks, out
    return {int(m.group(1)) if (m := re.search(r"threads: (\d+)", b)) else 1 for b in blocks}


def _copy_with_profiles(dst):
    _copy_workflow(dst)
    shutil.copytree(ROOT / "profiles", dst / "profiles", dirs_exist_ok=True)


def _rule_blocks() -> dict[str, str]:
    """{rule: its text} of the rules of workflow/rules/*.smk."""
    blocks = {}
    for smk in (ROOT / "workflow" / "rules").glob("*.smk"):
        for block in re.split(r"\n(?=rule )", smk.read_text()):
            if m := re.match(r"rule (\w+):", block):
                blocks[m.group(1)] = block
    return blocks


def _rules_with(directive: str) -> set:
    """Rules that have ``directive:`` (e.g. ``threads``: the multi-threaded rules)."""
    return {r for r, b in _rule_blocks().items() if re.search(rf"^    {directive}:", b, re.M)}


def _declared(rule: str) -> dict:
    """{resource: value} of a rule's ``resources:`` (``name=per_attempt(value)``)."""
    found = re.findall(r"^        (\w+)=per_attempt\((\d+)\),", _rule_blocks()[rule], re.M)
    return {k: int(v) for k, v in found}


def _resources(out: str, rule: str) -> set:
    """(mem_mb, runtime) a dry-run prints for the jobs of `rule`."""
    blocks = _blocks(out, rule)
    assert blocks, out
    return {tuple(int(re.search(rf"\b{k}=(\d+)", b).group(1)) for k in ("mem_mb", "runtime"))
            for b in blocks}


def test_slurm_profile_sets_threads_of_every_multithreaded_rule():
    profile = yaml.safe_load((ROOT / "profiles" / "slurm" / "config.yaml").read_text())
    rules = _rules_with("threads")
    assert {"simulate_grid", "robust_map_chunk", "basin_slice", "convergence"} <= rules
    assert set(profile["set-threads"]) == rules


def test_every_compute_rule_declares_memory_and_time():
    """Every rule that computes (a ``benchmark:`` file: every stage, the multi-threaded ones
    among them) declares mem_mb and runtime; the SLURM profile repeats no per-rule value
    and sets no mem_mb_per_cpu (the plugin would pass that instead of the rules' mem_mb)."""
    compute = _rules_with("benchmark")
    assert _rules_with("threads") <= compute and len(compute) >= 14
    for rule in compute:
        got = _declared(rule)
        assert set(got) == {"mem_mb", "runtime"} and min(got.values()) > 0, (rule, got)
    profile = yaml.safe_load((ROOT / "profiles" / "slurm" / "config.yaml").read_text())
    assert "mem_mb_per_cpu" not in profile["default-resources"]
    assert "set-resources" not in profile


@needs_snakemake
def test_default_profile_shortens_the_output(tmp_path):
    """profiles/default is used without being named: a dry run shows the job counts but
    not every job's block."""
    _copy_with_profiles(tmp_path)
    smoke = str(tmp_path / "config" / "smoke.yaml")
    r = _run(tmp_path, "-n", "-c2", "--configfile", smoke)
    assert r.returncode == 0, r.stdout + r.stderr
    out = r.stdout + r.stderr
    assert "profiles/default" in out and "Job stats:" in out
    assert "\nrule simulate_grid:" not in out and "    output: " not in out
    r = _run(tmp_path, "-n", "-c2", "--configfile", smoke, "--workflow-profile", "none")
    assert "\nrule simulate_grid:" in r.stdout + r.stderr        # the full plan on demand


def _run(cwd, *args):
    return subprocess.run([SNAKEMAKE, "--directory", str(cwd), "--snakefile",
                           str(cwd / "Snakefile"), *args],
                          capture_output=True, text=True, cwd=cwd, timeout=600)


@needs_snakemake
def test_work_precision_takes_the_cores_of_a_local_run(tmp_path):
    _copy_workflow(tmp_path)
    smoke = str(tmp_path / "config" / "smoke.yaml")
    # the default profile hides the job blocks that list the threads: plain output here
    plain = ("--workflow-profile", "none")
    r = _smk(tmp_path, "-n", "all", *plain, "--configfile", smoke)   # _smk runs with -c2
    assert _threads(r.stdout, "work_precision") == {2}
    r = _run(tmp_path, "-n", "-c1", "all", *plain, "--configfile", smoke)
    assert r.returncode == 0, r.stderr
    assert _threads(r.stdout, "work_precision") == {1}


@needs_snakemake
def test_profile_dry_run_without_cores(tmp_path):
    """`--profile profiles/slurm` needs no -c; here with the local executor (no plugin)."""
    _copy_with_profiles(tmp_path)
    smoke = str(tmp_path / "config" / "smoke.yaml")
    r = _run(tmp_path, "-n", "all", "--profile", str(tmp_path / "profiles" / "slurm"),
             "--executor", "local", "--configfile", smoke, *JOB_BLOCKS)
    assert r.returncode == 0, r.stdout + r.stderr
    assert _threads(r.stdout, "work_precision") == {8}            # profile set-threads
    for rule in ("simulate_grid", "robust_map_chunk", "basin_slice", "convergence"):
        assert _threads(r.stdout, rule) == {8}, rule
    assert _threads(r.stdout, "robust_map") == {1}        # a gather that only assembles
    for rule in ("simulate_grid", "robust_map_chunk", "robust_map", "stability_map",
                 "work_precision"):
        d = _declared(rule)                     # the rule's own resources reach its jobs
        assert _resources(r.stdout, rule) == {(d["mem_mb"], d["runtime"])}, rule
    _check_groups(r.stdout)


def _check_groups(out: str):
    """The profile's groups: every job of a grouped rule runs inside a group job, at most
    `group-components` of them a group job; every figure rule is grouped, no other rule."""
    profile = yaml.safe_load((ROOT / "profiles" / "slurm" / "config.yaml").read_text())
    groups, per_job = profile["groups"], profile["group-components"]
    assert set(groups.values()) == set(per_job) and min(per_job.values()) > 1
    planned = set(re.findall(r"^ *rule (\w+):$", out, re.M))
    assert set(groups) <= planned                     # no name of a rule that is not there
    assert {r for r in planned if r.startswith("fig")} <= set(groups)
    seen = set()
    for job in re.split(r"\n(?=\[)", out):       # a job or group job: "[date] ..." at column 0
        if m := re.match(r"\[[^]]*\] Group job (\w+) ", job):
            rules = re.findall(r"^    rule (\w+):$", job, re.M)
            assert 1 <= len(rules) <= per_job[m.group(1)], (m.group(1), rules)
            assert {groups[r] for r in rules} == {m.group(1)}, rules
            seen.add(m.group(1))
        else:                                         # a SLURM job of its own
            assert not set(re.findall(r"^rule (\w+):$", job, re.M)) & set(groups), job
    assert seen == set(per_job)


def test_the_default_profile_has_no_groups():
    """Groups are the SLURM profile's: a local run runs the same jobs as before."""
    profile = yaml.safe_load((ROOT / "profiles" / "default" / "config.yaml").read_text())
    assert not {"groups", "group-components"} & set(profile)


@needs_snakemake
def test_slurm_profile_dry_run(tmp_path):
    pytest.importorskip("snakemake_executor_plugin_slurm")
    _copy_with_profiles(tmp_path)
    smoke = str(tmp_path / "config" / "smoke.yaml")
    profile = str(tmp_path / "profiles" / "slurm")
    r = _run(tmp_path, "-n", "all", "--profile", profile, "--configfile", smoke, *JOB_BLOCKS)
    assert r.returncode == 0, r.stdout + r.stderr
    assert _threads(r.stdout, "work_precision") == {8}
    # --cores caps every job (a small node), as in tests/slurm/run_single_node.sh
    r = _run(tmp_path, "-n", "all", "--profile", profile, "--cores", "2",
             "--slurm-status-command", "squeue", "--configfile", smoke, *JOB_BLOCKS)
    assert r.returncode == 0, r.stdout + r.stderr
    assert _threads(r.stdout, "work_precision") == {2}
    assert _threads(r.stdout, "simulate_grid") == {2}


@needs_snakemake
def test_report_of_a_finished_run(tmp_path):
    _copy_workflow(tmp_path)
    _smk(tmp_path, "all", cfg=REPORT_CFG)
    assert (tmp_path / "results" / "report" / "figures" / "workprecision.png").exists()
    report = tmp_path / "report.html"
    # the README's command (no -c) with the target `all` (the figures beyond the paper too)
    r = _run(tmp_path, "all", "--report", str(report), "--configfile", str(tmp_path / "cfg.yaml"))
    assert r.returncode == 0, r.stdout + r.stderr
    html = report.read_text()
    # the captions state the run's initial condition and window from its config
    assert "from rest" in html
    assert "[t_transient, t_end] = [60.0, 120.0]" in html                   # fig2
    assert "[t_transient, t_end] = [10.0, 20.0]" in html                    # work precision
