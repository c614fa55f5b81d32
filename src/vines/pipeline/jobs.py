"""Running one Snakemake job: output in its log, every failure recorded there.

``run_job(snakemake, main)`` calls ``main()`` with stdout and stderr redirected to the job's
log file, where the progress of its long loops (``vines.progress``; those lasting over
JOB_QUIET_S) shows as a line every 10 % ("census 128/256 states (50 %)"). A failure writes
its traceback and a one-line summary to the log, and the summary (naming the job and the
log) to the console, then exits with status 1: the log of a failed job always holds its
error.
"""
from __future__ import annotations

import sys
import traceback
from pathlib import Path

from .. import progress

#: loops of a job that end within this many seconds leave no progress line in its log
JOB_QUIET_S = 5.0


def _job_name(sm) -> str:
    wc = ", ".join(f"{k}={v}" for k, v in dict(sm.wildcards).items())
    return f"{sm.rule}[{wc}]" if wc else str(sm.rule)


def check_code_version(expected: str | None) -> None:
    """Refuse to run when the imported vines is not the code the workflow hashed.

    ``expected`` is the rule's ``code`` param (``vines.pipeline.codeversion``); the sources
    actually imported must hash to it for one of the rule kinds, else the dataset would be
    attributed to the wrong code.
    """
    if not expected:
        return
    from .codeversion import KINDS, PKG_DIR, code_version
    if expected not in {code_version(kind) for kind in KINDS}:
        raise RuntimeError(f"this job imports vines from {PKG_DIR}, whose sources differ from "
                           f"the code version {expected} the workflow computed: run the "
                           "workflow of the checkout whose sources should run")


def run_job(sm, main) -> None:
    """Call ``main()`` with output in ``sm.log[0]``; on failure log it and exit(1).

    Before ``main`` the job checks that it runs the code its ``code`` param names."""
    console, stdout = sys.stderr, sys.stdout
    log_path = Path(sm.log[0])
    log_path.parent.mkdir(parents=True, exist_ok=True)
    with open(log_path, "w", buffering=1) as log:
        sys.stdout = sys.stderr = log
        try:
            check_code_version(getattr(getattr(sm, "params", None), "code", None))
            with progress.reporting(progress.LineReporter(lambda line: print(line, file=log),
                                                          quiet_s=JOB_QUIET_S)):
                main()
        except BaseException as exc:      # incl. KeyboardInterrupt: the log says why it stopped
            traceback.print_exc(file=log)
            line = f"vines {_job_name(sm)}: {type(exc).__name__}: {exc}".splitlines()[0]
            print(line, file=log, flush=True)
            print(f"{line} (log: {log_path})", file=console, flush=True)
            sys.exit(1)
        finally:
            sys.stdout, sys.stderr = stdout, console
