"""Snakemake logger plugin ``vines``: one line per finished job, failures with their log.

Selected by the workflow's default profile (profiles/default/config.yaml, ``logger:
[vines]``), so ``snakemake -c2`` prints, instead of every job's input and output lists::

    [12/83] simulate_grid grid=fig7_W1 key=ab06fb9422d530fa (2.1 s)

and for a failed job the rule, its wildcards, its log file and the last lines of that log.
Snakemake's other messages (the plan, warnings, errors, "Nothing to be done") pass
unchanged; its scheduling chatter ("Select jobs to execute...", "Execute 2 jobs...") is
left out. ``--quiet progress`` drops the job lines, ``--quiet all`` keeps errors only.
A run refused because another holds the directory's lock gets one line instead of
Snakemake's paragraph (``lock_message``): wait for the other run if one is working there,
else the ``--unlock`` command to type.
Snakemake finds the plugin by its module name (``snakemake_logger_plugin_<name>``) on
``sys.path`` when it parses the command line: it is installed with vines (``pip install
-e .``; ``src/`` on ``PYTHONPATH`` works too). Without it, ``--logger vines`` is refused:
``--workflow-profile none`` then runs with Snakemake's own output.

A dry run (``-n``) prints the job table once, why the jobs run (per reason the rules and
their numbers of jobs, in place of Snakemake's summary that points to the job displays
hidden here) and an estimate of the cost from measured job times (``cost``: the benchmark
files of the run, else the costs shipped in ``measured``).
"""
from __future__ import annotations

import logging
import os
import shlex
import sys
import textwrap
import time
from pathlib import Path

from snakemake_interface_logger_plugins.base import LogHandlerBase
from snakemake_interface_logger_plugins.common import LogEvent

from .cost import cores_of, estimate

#: messages without an event that say nothing to a user (prefixes)
CHATTER = ("Select jobs to execute", "Execute ", "Assuming unrestricted shared filesystem",
           "Using shell:", "Provided cores:", "Rules claiming more threads",
           "Building DAG of jobs", "host:",
           # the part files of chunk jobs (temp()), removed once their gather has run
           "Would remove temporary output", "Removing temporary output")
#: lines of a failed job's log shown on the console
LOG_TAIL = 15
#: references of Snakemake's dry-run messages to the job displays hidden here, and what
#: replaces them
HIDDEN_REFERENCES = (("see 'reason' section in the rule displays above",
                      "see the reasons above"),
                     ("\n    (check individual jobs above for details)", ""))


def job_line(done: int, total: int, rule: str, wildcards: dict, seconds: float | None) -> str:
    """``[ done/total] rule key=value ... (seconds)``."""
    wc = " ".join(f"{k}={v}" for k, v in wildcards.items())
    took = f" ({seconds:.1f} s)" if seconds is not None else ""
    width = len(str(total))
    return f"[{done:>{width}}/{total}] {rule}{' ' + wc if wc else ''}{took}"


def short_reason(reason: str) -> str:
    """Snakemake's reason of a job without its file lists: "missing output files; ..."."""
    heads = [part.split(":", 1)[0].strip() for part in str(reason or "").split("; ")]
    return "; ".join(h[:1].lower() + h[1:] for h in heads if h) or "no reason given"


#: how to see every job's display (files, reason) with the plan of the default profile
FULL_DISPLAY = "--workflow-profile none --rerun-triggers mtime params input software-env"


def reasons_block(planned) -> str:
    """Why the planned (rule, reason) jobs run: per reason, its rules with their numbers
    of jobs."""
    counts: dict[str, dict[str, int]] = {}
    for rule, reason in planned:
        per_rule = counts.setdefault(short_reason(reason), {})
        per_rule[rule] = per_rule.get(rule, 0) + 1
    lines = [f"Reasons (rules and their numbers of jobs; every job's files and reason: the "
             f"same command with {FULL_DISPLAY}):"]
    for why, rules in sorted(counts.items()):
        lines.append(f"    {why}:")
        lines += textwrap.wrap(", ".join(f"{r} ({n})" for r, n in sorted(rules.items())),
                               width=92, initial_indent=" " * 8, subsequent_indent=" " * 8)
    return "\n".join(lines)


def rerun_command(argv: list[str]) -> str:
    """The command line of this Snakemake run, to be typed again."""
    prog = "python -m snakemake" if Path(argv[0]).name == "__main__.py" else "snakemake"
    return " ".join([prog, *map(shlex.quote, argv[1:])])


def other_runs(directory: str) -> list[int] | None:
    """Pids of the other Snakemake processes working in ``directory`` (from /proc); None if
    that cannot be known (no /proc, a Snakemake process whose folder cannot be read)."""
    proc = Path("/proc")
    if not (proc / "self" / "cwd").exists():
        return None
    found = []
    for entry in proc.iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            argv = (entry / "cmdline").read_bytes().split(b"\0")[:3]
            if not any(Path(a.decode(errors="replace")).name == "snakemake" for a in argv):
                continue
            cwd = os.readlink(entry / "cwd")
        except FileNotFoundError:          # ended meanwhile, or a zombie
            continue
        except OSError:                    # another user's Snakemake
            return None
        if cwd == directory:
            found.append(int(entry.name))
    return found


def lock_message(directory: str, argv: list[str], running: list[int] | None) -> str:
    """One line for a run refused by the directory's lock, with what to do."""
    cmd = rerun_command(argv)
    unlock = f"{cmd} --unlock && {cmd}"
    if running:
        return (f"vines pipeline: another Snakemake run is working in {directory} (pid "
                f"{', '.join(map(str, running))}); wait for it to end, then run the same "
                f"command again: {cmd}")
    if running is not None:
        return (f"vines pipeline: {directory} is locked by a run that was stopped (killed or "
                f"lost); unlock it and run the same command again: {unlock}")
    return (f"vines pipeline: {directory} is locked by another Snakemake run; if one is still "
            f"working there, wait for it to end; if not (it was killed): {unlock}")


def log_tail(paths, n: int = LOG_TAIL) -> list[str]:
    """The last ``n`` lines of each existing log in ``paths``, indented."""
    out = []
    for path in paths:
        try:
            lines = Path(path).read_text(errors="replace").splitlines()[-n:]
        except OSError:
            continue
        out += [f"    | {line}" for line in lines]
    return out


class LogHandler(LogHandlerBase):
    """Console handler: one line per finished job, failures with their log."""

    def __post_init__(self) -> None:
        self.jobs: dict[int, tuple[str, dict, float]] = {}   # jobid -> rule, wildcards, start
        self.finished: list[int] = []                          # finished, not yet counted
        quiet = {str(q).lower() for q in (self.common_settings.quiet or ())}
        self.errors_only = "all" in quiet                       # --quiet all
        self.no_progress = self.errors_only or "progress" in quiet
        self.stream = sys.stdout if self.common_settings.stdout else sys.stderr
        self.dryrun = bool(getattr(self.common_settings, "dryrun", False))
        self.planned: list[tuple] = []   # dry run: rule, reason, benchmark, output, threads
        self.table_shown = False

    # the plugin interface's properties
    @property
    def writes_to_stream(self) -> bool:
        return True

    @property
    def writes_to_file(self) -> bool:
        return False

    @property
    def has_filter(self) -> bool:
        return True

    @property
    def has_formatter(self) -> bool:
        return True

    @property
    def needs_rulegraph(self) -> bool:
        return False

    def _print(self, text: str) -> None:
        print(text, file=self.stream, flush=True)

    def emit(self, record: logging.LogRecord) -> None:
        try:
            self._emit(record)
        except Exception:          # a logging failure must not stop the workflow
            self.handleError(record)

    def _emit(self, record: logging.LogRecord) -> None:
        event = getattr(record, "event", None)
        if event == LogEvent.JOB_INFO:
            self.jobs[record.jobid] = (record.rule_name, dict(record.wildcards or {}),
                                       time.monotonic())
            if self.dryrun:
                outputs = list(getattr(record, "output", None) or [None])
                self.planned.append((record.rule_name, getattr(record, "reason", ""),
                                     getattr(record, "benchmark", None), outputs[0],
                                     getattr(record, "threads", 1)))
        elif event == LogEvent.JOB_FINISHED:
            self.finished.append(record.job_id)
        elif event == LogEvent.PROGRESS:
            self._progress(record.done, record.total)
        elif event in (LogEvent.JOB_ERROR, LogEvent.GROUP_ERROR):
            self._error(record)
        elif event == LogEvent.RUN_INFO:
            if not self.errors_only and record.levelno >= logging.INFO:
                self._info(record.getMessage())
        elif event is None:
            self._message(record)
        elif event == LogEvent.ERROR and getattr(record, "exception", None) == "LockException":
            self._print(lock_message(os.getcwd(), sys.argv, other_runs(os.getcwd())))
        elif record.levelno >= logging.WARNING:     # e.g. an exception (event ERROR)
            self._print(record.getMessage())

    def _progress(self, done: int, total: int) -> None:
        if self.no_progress:
            self.finished.clear()
            return
        first = done - len(self.finished) + 1
        for k, jobid in enumerate(self.finished):
            rule, wildcards, start = self.jobs.pop(jobid, (f"job {jobid}", {}, None))
            seconds = time.monotonic() - start if start is not None else None
            self._print(job_line(first + k, total, rule, wildcards, seconds))
        self.finished.clear()

    def _error(self, record: logging.LogRecord) -> None:
        infos = getattr(record, "job_error_info", None) or [record.__dict__]
        for info in infos:
            rule = info.get("rule_name", "?")
            _, wildcards, _ = self.jobs.get(info.get("jobid"), (rule, {}, None))
            wc = " ".join(f"{k}={v}" for k, v in wildcards.items())
            logs = list(info.get("log") or [])
            self._print(f"FAILED {rule}{' ' + wc if wc else ''}"
                        + (f": log {', '.join(logs)}" if logs else ""))
            if info.get("rule_msg"):
                self._print(f"    {info['rule_msg']}")
            for line in log_tail(logs):
                self._print(line)

    def _message(self, record: logging.LogRecord) -> None:
        text = record.getMessage() if record.msg is not None else ""
        if not text:
            return
        chatter = self.errors_only or text.startswith(CHATTER)
        if record.levelno >= logging.WARNING:
            self._print(text)
        elif record.levelno >= logging.INFO and not chatter:
            self._info(text)

    def _info(self, text: str) -> None:
        """An info message: the job table once, a dry run's reasons and cost estimate in
        place of the references to the hidden job displays."""
        if text.startswith("Job stats:"):
            if self.table_shown:
                return
            self.table_shown = True
        elif text.startswith("Reasons:") and self.planned:
            text = reasons_block((job[0], job[1]) for job in self.planned)
        elif text.startswith("This was a dry-run") and self.planned:
            self._print(estimate([(job[0], *job[2:]) for job in self.planned],
                                 cores_of(sys.argv)))
        for old, new in HIDDEN_REFERENCES:
            text = text.replace(old, new)
        self._print(text)
