"""The logger plugin of the default profile (snakemake_logger_plugin_vines): one line per
finished job with the count, rule and wildcards; a failed job with its log; Snakemake's
scheduling chatter left out. Fed the records Snakemake emits (event and fields as in
snakemake.jobs and snakemake.scheduling.job_scheduler)."""
import io
import logging
from types import SimpleNamespace

import pytest

pytest.importorskip("snakemake_interface_logger_plugins")
from snakemake_interface_logger_plugins.common import LogEvent  # noqa: E402
from snakemake_interface_logger_plugins.registry import LoggerPluginRegistry  # noqa: E402

import snakemake_logger_plugin_vines as plugin  # noqa: E402


def _handler(quiet=()):
    settings = SimpleNamespace(quiet=set(quiet), stdout=False, printshellcmds=False,
                               nocolor=True, debug_dag=False, verbose=False,
                               show_failed_logs=False, dryrun=False)
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
