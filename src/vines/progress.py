"""Progress of long loops and their cancellation, without any argument in the numerics.

The numerics mark their long loops, and nothing else::

    for res in progress.track(pool.map(work, items), len(items), "census"):
        ...                                   # or, around a loop of unknown length:
    with progress.task(None, "continuation"):
        while ...:
            progress.advance()                # once per item (n items: advance(n))

Whoever runs them chooses how progress shows by installing a ``Reporter`` for the current
context (``with progress.reporting(reporter): ...``): the command line a progress bar on a
terminal (``vines.cli.reporting``), a pipeline job a line in its log every ~10 %
(``LineReporter``). Without a reporter every call is a context-variable lookup and nothing
else. The reporter is context-local (``contextvars``): threads started by a thread pool do
not see it, so loops over a pool's results report from the thread that collects them.

Only the outermost task of a reporter shows; tasks opened inside it (the census of each
point of a design, the branches of a boundary scan) count silently. ``Reporter.cancel``
(e.g. on Ctrl-C) makes the next ``advance``, ``check`` or ``task`` of that context raise
``Cancelled``: a loop stops between two items and ``track`` cancels the pending futures of
the pool whose results it walks.
"""
from __future__ import annotations

import contextlib
import contextvars
import threading
import time
from collections.abc import Callable, Iterable, Iterator

__all__ = ["Cancelled", "LineReporter", "Reporter", "Task", "advance", "check", "reporting",
           "task", "track"]


class Cancelled(KeyboardInterrupt):
    """Raised inside a loop whose reporter was cancelled (a KeyboardInterrupt: no
    ``except Exception`` of the numerics stops it)."""


class Task:
    """One marked loop: its description, total (None: unknown) in ``unit`` (e.g. states,
    points, dimensionless time t), count so far, nesting depth (0: outermost) and start
    time (perf_counter, s)."""

    __slots__ = ("desc", "total", "unit", "count", "depth", "t_start")

    def __init__(self, desc: str, total: float | None, unit: str, depth: int):
        self.desc, self.total, self.unit, self.count, self.depth = desc, total, unit, 0, depth
        self.t_start = time.perf_counter()

    @property
    def elapsed(self) -> float:
        """Seconds since the task started."""
        return time.perf_counter() - self.t_start

    @property
    def fraction(self) -> float | None:
        """count / total (at most 1), None when the total is unknown or 0."""
        return min(1.0, self.count / self.total) if self.total else None


class Reporter:
    """Keeps the stack of open tasks and the stop flag; shows the outermost task through
    ``show_start``, ``show_advance`` and ``show_end`` (no-ops here: a silent reporter that
    can still cancel)."""

    def __init__(self):
        self.tasks: list[Task] = []
        self._stop = threading.Event()

    # -- control (any thread)
    def cancel(self) -> None:
        """Make the loops of this reporter stop at their next ``advance`` or ``check``."""
        self._stop.set()

    @property
    def cancelled(self) -> bool:
        return self._stop.is_set()

    def check(self) -> None:
        if self._stop.is_set():
            raise Cancelled("cancelled")

    # -- the numerics' side (the collecting thread)
    def start(self, desc: str, total: float | None, unit: str = "it") -> Task:
        self.check()
        t = Task(desc, total, unit, len(self.tasks))
        self.tasks.append(t)
        if t.depth == 0:
            self.show_start(t)
        return t

    def advance(self, n: float = 1) -> None:
        self.check()
        if self.tasks:
            t = self.tasks[-1]
            t.count += n
            if t.depth == 0:
                self.show_advance(t)

    def end(self, t: Task) -> None:
        if t in self.tasks:
            del self.tasks[self.tasks.index(t):]
        if t.depth == 0:
            self.show_end(t)

    # -- display of the outermost task (subclasses)
    def show_start(self, t: Task) -> None:
        pass

    def show_advance(self, t: Task) -> None:
        pass

    def show_end(self, t: Task) -> None:
        pass


class LineReporter(Reporter):
    """Plain lines through ``write`` (e.g. a log's ``print`` or ``logging.info``) about the
    outermost task: every ``step`` of its total ("census 128/256 states (50 %)"), at most
    every ``every_s`` seconds when its total is unknown, and its end with the time taken.
    A task that ends within ``quiet_s`` seconds writes nothing (many short tasks, e.g. one
    census per point, would fill a log)."""

    def __init__(self, write: Callable[[str], object], step: float = 0.1,
                 every_s: float = 30.0, quiet_s: float = 0.0):
        super().__init__()
        self.write, self.step, self.every_s, self.quiet_s = write, step, every_s, quiet_s
        self._next, self._shown = 0.0, False

    def show_start(self, t: Task) -> None:
        self._next, self._shown = (self.step if t.total else self.every_s), False
        if self.quiet_s <= 0:
            self._show(f"{t.desc}: started ({_size(t)})")

    def show_advance(self, t: Task) -> None:
        f = t.fraction
        if t.elapsed < self.quiet_s:
            return
        if f is not None:
            if f + 1e-12 >= self._next and f < 1.0:
                self._show(f"{t.desc} {_num(t.count)}/{_num(t.total)} {t.unit} "
                           f"({100 * f:.0f} %)")
                self._next = (int(f / self.step + 1e-9) + 1) * self.step
        elif t.elapsed >= self._next:
            self._show(f"{t.desc} {_num(t.count)} {t.unit}")
            self._next = t.elapsed + self.every_s

    def show_end(self, t: Task) -> None:
        if self._shown and not self.cancelled:
            self.write(f"{t.desc}: {_num(t.count)} {t.unit} in {t.elapsed:.1f} s")

    def _show(self, line: str) -> None:
        self._shown = True
        self.write(line)


def _size(t: Task) -> str:
    return f"{_num(t.total)} {t.unit}" if t.total is not None else "size unknown"


def _num(x) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


_current: contextvars.ContextVar[Reporter | None] = contextvars.ContextVar(
    "vines_progress_reporter", default=None)


@contextlib.contextmanager
def reporting(reporter: Reporter | None) -> Iterator[Reporter | None]:
    """Install ``reporter`` for the loops run in this context (None: none)."""
    token = _current.set(reporter)
    try:
        yield reporter
    finally:
        _current.reset(token)


def current() -> Reporter | None:
    """The reporter of this context (None: progress is not reported)."""
    return _current.get()


@contextlib.contextmanager
def task(total: float | None, desc: str, unit: str = "it") -> Iterator[None]:
    """Mark a loop of ``total`` (None: unknown) ``unit`` called ``desc``."""
    r = _current.get()
    if r is None:
        yield
        return
    t = r.start(desc, total, unit)
    try:
        yield
    finally:
        r.end(t)


def advance(n: float = 1) -> None:
    """``n`` more items of the innermost task done; raises Cancelled after a cancel."""
    r = _current.get()
    if r is not None:
        r.advance(n)


def check() -> None:
    """Raise Cancelled if the reporter was cancelled (for loops inside another's task)."""
    r = _current.get()
    if r is not None:
        r.check()


def track(items: Iterable, total: float | None, desc: str, unit: str = "it") -> Iterator:
    """Yield ``items`` as a task of ``total`` items; closes ``items`` when stopped early
    (the generator of ``Executor.map`` then cancels its pending futures)."""
    try:
        with task(total, desc, unit):
            for item in items:
                yield item
                advance()
    finally:
        close = getattr(items, "close", None)
        if close is not None:
            close()
