"""Impact statistics of the measurement window, accumulated in blocks of impacts.

The measures need from the impacts only counts: impacts in the window, the longest run of
consecutive impacts on one wall, and the impacts on each wall over the stroboscopic span
(``regime.classify``). ``ImpactTally`` adds them up block by block, in time order, so a
long run need not keep its impact list (``exact.KernelRun.stream``): memory then does not
grow with t_end or max_impacts. The numbers equal those computed from the whole list.
"""
from __future__ import annotations

import math

import numpy as np


class ImpactTally:
    """Counts over the impacts with t >= t_transient, added in time order (``add``).

    span = (lo, hi): the impacts per wall are counted over lo <= t < hi (the stroboscopic
    span of ``regime.classify``; (-inf, inf) when it has fewer than two times).
    """

    def __init__(self, t_transient: float, span: tuple[float, float]):
        self.t_transient = float(t_transient)
        self.lo, self.hi = span
        self.n_window = 0          # impacts in the window
        self.longest_run = 0       # longest run of consecutive impacts on one wall
        self._last_wall = 0        # wall of the last impact added, and its run so far
        self._run = 0
        self.n_span_L = 0          # impacts on wall L (+1) and R (-1) over the span
        self.n_span_R = 0
        self.t_last = -math.inf    # time of the last impact added (blocks come in time order)

    @classmethod
    def for_window(cls, t_transient: float, strobe_t: np.ndarray) -> ImpactTally:
        """Tally for the window from t_transient with the stroboscopic times strobe_t."""
        span = (strobe_t[0], strobe_t[-1]) if strobe_t.size >= 2 else (-math.inf, math.inf)
        return cls(t_transient, span)

    def add(self, t: np.ndarray, wall: np.ndarray) -> None:
        """Add a block of impacts (times t in time order, walls +-1), later than every block
        before (equal times allowed); a block out of order raises ValueError (the counts of
        runs and slices need the order). The window and the span are slices of the block,
        found by one binary search (a short run's measures cost mostly numpy calls: no
        masks)."""
        if t.size:
            self._check_order(t)
        i0, lo, hi = t.searchsorted((self.t_transient, self.lo, self.hi))
        wall = wall[i0:]
        if wall.size == 0:
            return
        self.n_window += int(wall.size)
        change = (wall[1:] != wall[:-1]).nonzero()[0]
        lengths = np.diff(np.concatenate(([-1], change, [wall.size - 1])))
        if wall[0] == self._last_wall:
            lengths[0] += self._run
        self.longest_run = max(self.longest_run, int(lengths.max()))
        self._last_wall, self._run = int(wall[-1]), int(lengths[-1])
        span = wall[max(lo - i0, 0):max(hi - i0, 0)]       # lo <= t < hi
        self.n_span_L += int(np.count_nonzero(span > 0))
        self.n_span_R += int(np.count_nonzero(span < 0))

    def _check_order(self, t: np.ndarray) -> None:
        """ValueError unless t is non-decreasing and starts at or after ``t_last``; then
        t_last = t[-1]. One comparison of neighbours: ~3 us a block of 1000 impacts (a
        tenth of ``add``, which runs once a block, not once an impact)."""
        if not t[0] >= self.t_last:
            raise ValueError(f"impacts out of time order: a block starts at t = {float(t[0])!r}, "
                             f"before the last impact added (t = {self.t_last!r})")
        if t.size > 1 and not (t[1:] >= t[:-1]).all():
            k = int(np.argmin(t[1:] >= t[:-1]))
            raise ValueError(f"impacts out of time order within a block: t = {float(t[k + 1])!r} "
                             f"after t = {float(t[k])!r}")
        self.t_last = float(t[-1])
