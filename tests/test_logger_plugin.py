"""The logger plugin of the default profile (snakemake_logger_plugin_vines): one line per
finished job with the count, rule and wildcards; a failed job with its log; Snakemake's
scheduling chatter left out. Fed the records Snakemake emits (event and fields as in
snakemake.jobs and snakemake.scheduling.job_scheduler)."""
import io
import logging
import os
import shutil
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

pytest.importorskip("snakemake_interface_logger_plugins")
from snakemake_interface_logger_plugins.common import LogEvent  # noqa: E402
from snakemake_interface_logger_plugins.registry import LoggerPluginRegistry  # noqa: E402

import snakemake_logger_plugin_vines as plugin  # noqa: E402
from snakemake_logger_plugin_vines import cost  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _handler(quiet=(), dryrun=False):
    settings = SimpleNamespace(quiet=set(quiet), stdout=False, printshellcmds=False,
                               nocolor=True, debug_dag=False, verbose=False,
                               show_failed_logs=False, dryrun=dryrun)
    h = plugin.LogHandler(settings, None)
    h.stream = io.StringIO()
    return h


def _record(msg=None, level=logging.INFO, **extra):
    rec = logging.LogRecord("snakemake", level, __file__, 0, msg, None, None)
    rec.__dict__.update(extra)
    return rec


def _finish(h, jobid, done, total):
    h.handle(_record(f"Finished jobid: {jobid}", event=LogEvent.JOB_FINISHED, job_id=jobid))
    h.handle(_record(None, event=LogEvent.PROGRESS, done=done, total=total))


def test_snakemake_finds_the_plugin():
    assert "vines" in LoggerPluginRegistry().plugins


def test_one_line_per_finished_job_with_count_rule_and_wildcards():
    h = _handler()
    h.handle(_record(" Rule: simulate_grid, Jobid: 7", event=LogEvent.JOB_INFO, jobid=7,
                     rule_name="simulate_grid", wildcards={"grid": "fig2", "key": "ab12"}))
    h.handle(_record(" Rule: all, Jobid: 0", event=LogEvent.JOB_INFO, jobid=0,
                     rule_name="all", wildcards={}))
    h.handle(_record("Select jobs to execute..."))
    h.handle(_record("Execute 2 jobs..."))
    _finish(h, 7, 12, 83)
    _finish(h, 0, 83, 83)
    lines = h.stream.getvalue().splitlines()
    assert len(lines) == 2, lines
    assert lines[0].startswith("[12/83] simulate_grid grid=fig2 key=ab12 (")
    assert lines[0].endswith(" s)")
    assert lines[1].startswith("[83/83] all (")


def test_a_failed_job_names_its_log_and_shows_its_end(tmp_path):
    log = tmp_path / "chunk.log"
    log.write_text("".join(f"line {i}\n" for i in range(40)) + "ValueError: bad chunk\n")
    h = _handler()
    h.handle(_record(" Rule: simulate_grid, Jobid: 3", event=LogEvent.JOB_INFO, jobid=3,
                     rule_name="simulate_grid", wildcards={"grid": "fig2", "key": "ab12"}))
    h.handle(_record("Error in rule simulate_grid, jobid: 3", level=logging.ERROR,
                     event=LogEvent.JOB_ERROR, jobid=3, rule_name="simulate_grid",
                     rule_msg=None, log=[str(log)], input=[], output=[]))
    out = h.stream.getvalue().splitlines()
    assert out[0] == f"FAILED simulate_grid grid=fig2 key=ab12: log {log}"
    assert out[-1] == "    | ValueError: bad chunk"
    assert len(out) == 1 + plugin.LOG_TAIL


def test_messages_and_errors_pass_and_quiet_all_keeps_errors_only():
    h = _handler()
    h.handle(_record("Nothing to be done (all requested files are present and up to date)."))
    h.handle(_record("MissingInputException in rule x", level=logging.ERROR))
    h.handle(_record("WorkflowError: bad input", level=logging.ERROR, event=LogEvent.ERROR,
                     exception="WorkflowError"))
    h.handle(_record("Provided cores: 2", event=LogEvent.RESOURCES_INFO))
    assert h.stream.getvalue().splitlines() == [
        "Nothing to be done (all requested files are present and up to date).",
        "MissingInputException in rule x", "WorkflowError: bad input"]
    h = _handler(quiet={"all"})
    h.handle(_record("Building DAG of jobs..."))
    h.handle(_record("Nothing to be done."))
    _finish(h, 1, 1, 2)
    h.handle(_record("MissingInputException in rule x", level=logging.ERROR))
    assert h.stream.getvalue().splitlines() == ["MissingInputException in rule x"]


# ------------------------------------------------------------------ dry run (-n)

TABLE = "Job stats:\njob    count\n-----  -----\nsimulate_grid  2\nfig7  1\ntotal  3\n"
REASONS = ("Reasons:\n    (check individual jobs above for details)\n    output files have to be"
           " generated:\n        fig7, simulate_grid")
PROVENANCE = ("Some jobs were triggered by provenance information, see 'reason' section in "
              "the rule displays above.\nIf you prefer that only modification time is used ...")


def _job(h, jobid, rule, reason, benchmark=None, output=None, threads=1):
    output = f"results/tiny/{rule}/{jobid}.nc" if output is None else output
    h.handle(_record(f" Rule: {rule}, Jobid: {jobid}", event=LogEvent.JOB_INFO, jobid=jobid,
                     rule_name=rule, wildcards={"k": str(jobid)}, reason=reason,
                     benchmark=benchmark, output=[output] if output else [], threads=threads))


def _bench(path, cpu, wall):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("s\th:m:s\tmax_rss\tcpu_time\n"
                    f"{wall}\t0:00:01\t10.0\t{cpu}\n")


def _dry_run(h, jobs):
    h.handle(_record(TABLE, event=LogEvent.RUN_INFO))            # before scheduling
    for k, job in enumerate(jobs):
        _job(h, k, *job)
    h.handle(_record(TABLE, event=LogEvent.RUN_INFO))            # and again after it
    h.handle(_record(REASONS))
    h.handle(_record(PROVENANCE))
    h.handle(_record("This was a dry-run (flag -n). The order of jobs does not reflect ..."))
    return h.stream.getvalue()


def test_dry_run_prints_one_table_and_the_reasons_it_does_not_hide(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = _dry_run(_handler(dryrun=True), [
        ("simulate_grid", "Missing output files: a.nc, b.nc", "results/tiny/benchmarks/s/1.tsv"),
        ("simulate_grid", "Missing output files: c.nc", "results/tiny/benchmarks/s/2.tsv"),
        ("fig7", "Params have changed since last execution: code, colormap")])
    assert out.count("Job stats:") == 1
    assert "above for details" not in out and "rule displays above" not in out
    assert "see the reasons above" in out
    lines = out.splitlines()
    k = lines.index("    missing output files:")
    assert lines[k + 1] == "        simulate_grid (2)"
    k = lines.index("    params have changed since last execution:")
    assert lines[k + 1] == "        fig7 (1)"
    assert "--workflow-profile none" in out        # where every job's display is
    assert out.rstrip().splitlines()[-1].startswith("This was a dry-run")


def test_dry_run_estimate_from_the_benchmark_files_of_the_run(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bench = Path("results/tiny/benchmarks")
    _bench(bench / "simulate_grid" / "g" / "k1.tsv", cpu=300.0, wall=160.0)   # own last run
    _bench(bench / "simulate_grid" / "g" / "k0.tsv", cpu=100.0, wall=60.0)
    monkeypatch.setattr(cost, "FIGURE_SECONDS", {"tiny": 30.0})
    monkeypatch.setattr(sys, "argv", ["snakemake", "-c2", "-n", "all"])
    out = _dry_run(_handler(dryrun=True), [
        ("simulate_grid", "Params have changed", str(bench / "simulate_grid/g/k1.tsv"), None, 2),
        ("simulate_grid", "Missing output files", str(bench / "simulate_grid/g/k9.tsv"), None, 2),
        ("fig7", "Missing output files", None, "results/tiny/figures/fig7.png", 1),
        ("all", "Input files updated by another job", None, "")])      # a target: no cost
    line = next(ln for ln in out.splitlines() if ln.startswith("Cost estimate"))
    # two 2-thread jobs of 160 s (own file) and 110 s (mean of the rule's files) take both
    # cores, the figure (30 s, 1 thread) one: (320 + 220 + 30) / 2 = 285 s
    assert line.startswith("Cost estimate: about 5 min on 2 cores for 3 jobs, from their ")
    assert ("benchmark files of results/tiny (1 jobs from their own last run, 1 at the "
            "mean of their rule there)") in line
    assert "the mean figure job for 1 figures" in line and "An estimate" in line


def test_estimate_without_benchmark_files_uses_shipped_costs_or_says_none(tmp_path,
                                                                         monkeypatch):
    monkeypatch.chdir(tmp_path)
    jobs = [("simulate_grid", "results/paper/benchmarks/simulate_grid/g/k.tsv", None, 1)] * 4
    shipped = {"paper": {"simulate_grid": (12, 45.0, 50.0)}}
    line = cost.estimate(jobs, cores=2, measured=shipped, figures={})
    assert line.startswith("Cost estimate: about 90 s on 2 cores for 4 jobs")   # 4 x 45 / 2
    assert "costs shipped with vines for 4 jobs" in line
    assert cost.estimate(jobs, cores=2, measured={}, figures={}).startswith(
        "Cost estimate: none")
    # the longest job bounds the estimate from below
    long = {"paper": {"simulate_grid": (1, 600.0, 600.0)}}
    assert "about 10 min on 4 cores" in cost.estimate(jobs[:1], 4, measured=long, figures={})


def test_estimate_spreads_a_stage_measured_whole_over_its_chunk_jobs(tmp_path, monkeypatch):
    """Shipped costs measured before a stage was split: its chunk jobs share the entry's
    time, its gather costs a gather of grid chunks (extract_measures)."""
    monkeypatch.chdir(tmp_path)
    b = "results/paper/benchmarks"
    jobs = [("robust_map_chunk", f"{b}/robust_map_chunk/r/{k}.tsv", None, 1) for k in range(3)]
    jobs += [("robust_map", f"{b}/robust_map/r.tsv", None, 1)]
    shipped = {"paper": {"robust_map": (3, 600.0, 604.0), "extract_measures": (9, 2.0, 4.4)}}
    whole = {"paper": ("robust_map",)}
    # 3 x 200 s + 2 s on one core; on three cores the chunks run side by side: 202 s / 3
    # cores bounded below by the longest job, 200 s
    line = cost.estimate(jobs, cores=1, measured=shipped, figures={}, whole=whole)
    assert line.startswith("Cost estimate: about 10 min on 1 cores for 4 jobs")
    line = cost.estimate(jobs, cores=3, measured=shipped, figures={}, whole=whole)
    assert line.startswith("Cost estimate: about 3 min on 3 cores for 4 jobs")
    # measured after the split (not whole): the shipped rules as they are
    after = {"paper": {"robust_map_chunk": (63, 30.0, 90.0), "robust_map": (3, 1.0, 1.0)}}
    line = cost.estimate(jobs, cores=1, measured=after, figures={}, whole={})
    assert line.startswith("Cost estimate: about 91 s on 1 cores for 4 jobs")


def test_shipped_costs_cover_the_rules_with_benchmarks():
    from snakemake_logger_plugin_vines.measured import FIGURE_SECONDS, MEASURED
    for run in ("paper", "smoke"):
        assert run in MEASURED and run in FIGURE_SECONDS
        assert all(n >= 1 and 0 < mean <= longest for n, mean, longest in MEASURED[run].values())
    rules = {p.stem for p in (ROOT / "workflow" / "rules").glob("*.smk")
             if "benchmark:" in p.read_text()}
    assert rules <= set(MEASURED["paper"]) and rules <= set(MEASURED["smoke"])


@pytest.mark.parametrize("argv, cores", [(["-c2"], 2), (["--cores", "3", "-n"], 3),
                                         (["-j", "4"], 4), (["--cores=5"], 5),
                                         (["-n", "--configfile", "c.yaml"], None)])
def test_cores_of_the_command_line(argv, cores):
    assert cost.cores_of(["snakemake", *argv]) == (cores or os.cpu_count())


@pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")
def test_snakemake_dry_run_of_the_smoke_config_explains_itself(tmp_path):
    # the real dry run: one table, no reference to the hidden displays, a cost estimate
    from test_pipeline import _copy_workflow, _smk
    _copy_workflow(tmp_path)
    smoke = ["--configfile", str(tmp_path / "config" / "smoke.yaml")]
    r = _smk(tmp_path, "-n", "all", *smoke)
    out = r.stdout + r.stderr
    assert out.count("Job stats:") == 1
    assert "above for details" not in out and "displays above" not in out
    assert "\n    missing output files:\n" in out
    line = next(ln for ln in out.splitlines() if ln.startswith("Cost estimate"))
    assert line.startswith("Cost estimate: about ") and "on 2 cores" in line
    assert "costs shipped with vines" in line
    # after a run, from its benchmark files (here one made up for a lyapunov job)
    bench = tmp_path / "results" / "smoke" / "benchmarks" / "lyapunov"
    _bench(bench / "fig3.tsv", cpu=7200.0, wall=3700.0)
    out = _smk(tmp_path, "-n", "all", *smoke).stdout
    line = next(ln for ln in out.splitlines() if ln.startswith("Cost estimate"))
    assert ("benchmark files of results/smoke (1 jobs from their own last run, 3 at the "
            "mean of their rule there)") in line
    assert line.startswith("Cost estimate: about ") and " min on 2 cores" in line


def test_lock_error_is_one_line_with_what_to_do(monkeypatch, tmp_path):
    """Snakemake's paragraph for a locked directory becomes one line: wait for the run that
    works there, or the command that lifts a killed run's lock (the user's command with
    ``--unlock``, then the command again); both when it cannot be known."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(plugin.sys, "argv", ["/env/bin/snakemake", "-c2", "all",
                                             "--configfile", "my config.yaml"])
    cmd = "snakemake -c2 all --configfile 'my config.yaml'"
    for running, expected in (
            ([41], f"vines pipeline: another Snakemake run is working in {tmp_path} (pid 41); "
                   f"wait for it to end, then run the same command again: {cmd}"),
            ([], f"vines pipeline: {tmp_path} is locked by a run that was stopped (killed or "
                 f"lost); unlock it and run the same command again: {cmd} --unlock && {cmd}"),
            (None, f"vines pipeline: {tmp_path} is locked by another Snakemake run; if one is "
                   "still working there, wait for it to end; if not (it was killed): "
                   f"{cmd} --unlock && {cmd}")):
        monkeypatch.setattr(plugin, "other_runs", lambda directory, r=running: r)
        h = _handler(quiet={"all"})
        h.handle(_record("LockException:\nError: Directory cannot be locked. ...",
                         level=logging.ERROR, event=LogEvent.ERROR, exception="LockException"))
        assert h.stream.getvalue().splitlines() == [expected]


def test_other_runs_finds_no_snakemake_in_a_fresh_folder(tmp_path):
    assert plugin.other_runs(str(tmp_path)) in ([], None)
    assert plugin.rerun_command(["/x/snakemake/__main__.py", "-n"]) == "python -m snakemake -n"
