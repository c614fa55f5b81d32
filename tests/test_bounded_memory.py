"""Long runs in bounded memory: streamed impact counts equal those of the kept list."""
import math

import numpy as np
import pytest

import vines
from vines.core import exact
from vines.core.params import ModelParams, SolverSettings
from vines.core.regime import longest_same_wall_run, strobe_times
from vines.core.tally import ImpactTally


def test_tally_in_blocks_equals_whole_list():
    rng = np.random.default_rng(3)
    # runs of one wall of random lengths, as in chatter, cut into blocks at random places
    walls = np.repeat(rng.choice([-1, 1], 400), rng.integers(1, 9, 400)).astype(np.int8)
    t = np.sort(rng.uniform(0.0, 100.0, walls.size))
    lo, hi, t_tr = 60.0, 90.0, 20.0
    whole = walls[t >= t_tr]
    in_span = (t >= lo) & (t < hi)
    for n_cuts in (0, 1, 7, 200):
        tally = ImpactTally(t_tr, (lo, hi))
        cuts = np.sort(rng.integers(0, walls.size, n_cuts))
        for tb, wb in zip(np.split(t, cuts), np.split(walls, cuts), strict=True):
            tally.add(tb, wb)
        assert tally.n_window == whole.size
        assert tally.longest_run == longest_same_wall_run(whole)
        assert tally.n_span_L == np.count_nonzero(walls[in_span] > 0)
        assert tally.n_span_R == np.count_nonzero(walls[in_span] < 0)


def test_tally_refuses_impacts_out_of_time_order():
    """The run lengths and the slices by binary search need time order: a block before the
    last one added, or unordered inside, is refused and leaves the counts as they were."""
    tally = ImpactTally(0.0, (-math.inf, math.inf))
    tally.add(np.array([1.0, 2.0, 2.0]), np.array([1, 1, -1], dtype=np.int8))
    counts = (tally.n_window, tally.longest_run, tally.n_span_L, tally.n_span_R)
    with pytest.raises(ValueError, match="before the last impact added"):
        tally.add(np.array([1.5, 3.0]), np.array([1, 1], dtype=np.int8))
    with pytest.raises(ValueError, match="within a block: t = 3.0 after t = 4.0"):
        tally.add(np.array([2.5, 4.0, 3.0]), np.array([1, 1, 1], dtype=np.int8))
    assert (tally.n_window, tally.longest_run, tally.n_span_L, tally.n_span_R) == counts
    tally.add(np.array([2.0, 5.0]), np.array([-1, 1], dtype=np.int8))   # equal time: in order
    assert (tally.n_window, tally.longest_run) == (5, 2)


@pytest.mark.parametrize("shortcut", [False, True])
def test_streamed_run_keeps_bounded_records(monkeypatch, shortcut):
    """A run of ~10^4 impacts through a 64-row impact buffer: the buffers never grow, only
    the segments from the first stroboscopic time on are kept, and every measure equals
    the one computed from the whole impact list."""
    monkeypatch.setattr(exact, "STREAM_ROWS", 64)
    sizes = []
    flush = exact.KernelRun._flush

    def spy(run):
        sizes.append((run.imp.shape[0], run.seg.shape[0]))
        flush(run)
    monkeypatch.setattr(exact.KernelRun, "_flush", spy)
    kw = dict(t_end=1500.0, t_transient=300.0, periodic_shortcut=shortcut)
    for point in ((0.2, 0.9, 0.4), (0.1, 1.0, 0.4)):      # chatter; period-2 (shortcut)
        kept = vines.simulate(*point, **kw)
        sizes.clear()
        streamed = vines.simulate(*point, keep_impacts=False, **kw)
        p = ModelParams(eta=point[0], omega=point[1], F=point[2])
        ts = strobe_times(p.period, kw["t_transient"], kw["t_end"])
        # the impact buffer never grows; the segment buffer holds at most the segments
        # of the last stroboscopic periods (doubled when full), not those of the run
        n_tail = np.count_nonzero(kept._state_at.segments[:, 0] >= ts[0]) + 1
        assert len(sizes) > 10 or shortcut
        assert max(n for n, _ in sizes) == 64
        assert max(m for _, m in sizes) <= 2 * max(2 * 64 + 16, n_tail)
        assert n_tail < kept._state_at.segments.shape[0] / 3
        assert streamed.impacts.size == 0 and kept.impacts.size > 1000
        a, b = kept.to_dict(), streamed.to_dict()
        for k in a:
            same = a[k] == b[k] or (isinstance(a[k], float) and math.isnan(a[k])
                                    and math.isnan(b[k]))
            assert same, (point, k, a[k], b[k])
        np.testing.assert_array_equal(streamed.state_at(ts), kept.state_at(ts))
        with pytest.raises(ValueError, match="recorded span"):
            streamed.state_at(ts[0] - p.period)     # before the kept segments


def test_run_exact_without_records_has_tally():
    p = ModelParams(eta=0.2, omega=0.9, F=0.4)
    st = SolverSettings(t_end=400.0, t_transient=200.0)
    raw = exact.run_exact(p, st, keep_records=False)
    ref = exact.run_exact(p, st)
    assert raw.impacts.size == 0 and ref.impact_tally is None
    assert raw.impact_tally.n_window == np.count_nonzero(ref.impacts["t"] >= 200.0)
    assert raw.n_impacts == ref.n_impacts
