"""What a command says on stderr besides its answer: log messages and progress.

* Messages go through the ``logging`` logger ``vines`` (and its children), one line each,
  ``vines <command>: <message>``: warnings and errors by default, also progress lines
  and timings with ``-v``, debugging detail with ``-vv``, errors only with ``--quiet``.
* Progress (``vines.progress``) shows as a ``tqdm`` bar on stderr when stderr is a
  terminal and ``--quiet`` is not given; bars are removed when their loop ends. Without a
  terminal, ``-v`` logs a line every 10 % instead. stdout is never touched.
"""
from __future__ import annotations

import argparse
import logging
import sys

from .. import progress
from .common import PROG

LOG = logging.getLogger("vines")


def add_flags(parser: argparse.ArgumentParser) -> None:
    """``-q/--quiet`` and ``-v/--verbose`` (a command's own group)."""
    group = parser.add_argument_group("messages on stderr")
    group.add_argument("-q", "--quiet", action="store_true",
                       help="no progress bars, errors only")
    group.add_argument("-v", "--verbose", action="count", default=0,
                       help="more messages: timings and progress lines (-vv: debugging)")


class _StderrHandler(logging.StreamHandler):
    """A handler writing to the *current* sys.stderr (tests and redirections replace it)."""

    def __init__(self):
        super().__init__(sys.stderr)

    def emit(self, record):
        self.setStream(sys.stderr)
        super().emit(record)


def setup_logging(command: str | None = None, verbose: int = 0, quiet: bool = False) -> None:
    """One handler on the ``vines`` logger: ``vines <command>: message`` on stderr."""
    level = logging.ERROR if quiet else (logging.WARNING, logging.INFO)[min(verbose, 1)]
    if verbose >= 2 and not quiet:
        level = logging.DEBUG
    where = f"{PROG} {command}" if command else PROG
    handler = _StderrHandler()
    handler.setFormatter(logging.Formatter(f"{where}: %(message)s"))
    for old in list(LOG.handlers):
        LOG.removeHandler(old)
    LOG.addHandler(handler)
    LOG.setLevel(level)
    LOG.propagate = False


#: the bar of a task counted in a continuous quantity (time, a parameter): 4 digits
FLOAT_BAR = "{desc}: {percentage:3.0f}%|{bar}| {n:.4g}/{total:.4g}{unit} [{elapsed}<{remaining}]"


class TqdmReporter(progress.Reporter):
    """The outermost task as a tqdm bar on ``stream`` (removed at its end, which is logged
    at INFO level with the time taken)."""

    def __init__(self, stream):
        super().__init__()
        self.stream, self.bar = stream, None

    def show_start(self, t: progress.Task) -> None:
        from tqdm import tqdm
        self.close()
        self.bar = tqdm(total=t.total, desc=t.desc, unit=f" {t.unit}", file=self.stream,
                        leave=False, dynamic_ncols=True, mininterval=0.25,
                        bar_format=FLOAT_BAR if isinstance(t.total, float) else None)

    def show_advance(self, t: progress.Task) -> None:
        bar = self.bar
        if bar is not None:
            bar.update(t.count - bar.n)

    def show_end(self, t: progress.Task) -> None:
        self.close()
        if not self.cancelled:
            LOG.info("%s: %s %s in %.1f s", t.desc, _num(t.count), t.unit, t.elapsed)

    def close(self) -> None:
        """Remove the bar from the terminal (before a message, or at the end)."""
        bar, self.bar = self.bar, None
        if bar is not None:
            bar.close()


def _num(x) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


def reporter_for(args: argparse.Namespace) -> progress.Reporter:
    """A bar on a terminal, log lines with -v elsewhere, else silent (every one of them can
    be cancelled on Ctrl-C)."""
    if getattr(args, "quiet", False):
        return progress.Reporter()
    if sys.stderr.isatty():
        return TqdmReporter(sys.stderr)
    if getattr(args, "verbose", 0):
        return progress.LineReporter(LOG.info)
    return progress.Reporter()


def close(reporter: progress.Reporter) -> None:
    """Remove a reporter's bar, if any (before a message on stderr)."""
    if isinstance(reporter, TqdmReporter):
        reporter.close()
