"""Execution of stage tasks with dask: threaded scheduler on the job's threads, or a
dask.distributed scheduler given by address; progress as plain lines for job logs.

Tasks are computed independently and returned in order, so results never depend on the
number of workers or the scheduler.
"""
from __future__ import annotations

import sys
import threading
import time

import dask
import dask.threaded
from dask.callbacks import Callback


def compute(tasks: list, n_workers: int, scheduler: str | None, progress: bool):
    """Compute dask.delayed ``tasks`` in order; threaded, or on a distributed scheduler."""
    if scheduler:
        from dask.distributed import Client
        from dask.distributed import progress as dprogress
        with Client(scheduler) as client:
            futs = client.compute(tasks)
            if progress:
                dprogress(futs)
            return client.gather(futs)
    # the threaded scheduler passed as a function: by name ("threads"), dask first imports
    # dask.distributed to look for a client (~0.5 s in every job)
    if progress:
        with LineProgress(tasks):
            return list(dask.compute(*tasks, scheduler=dask.threaded.get,
                                     num_workers=n_workers))
    return list(dask.compute(*tasks, scheduler=dask.threaded.get, num_workers=n_workers))


class LineProgress(Callback):
    """Progress of the dask computation of ``tasks`` as plain lines (for job logs): every
    10 % of those tasks (the graph's other keys, e.g. their arguments, are not counted)."""

    def __init__(self, tasks: list, stream=None):
        super().__init__()
        self.keys = {t.key for t in tasks}
        self.n, self.done, self.next = len(self.keys), 0, 0.1
        self.stream = stream
        self.lock = threading.Lock()
        self.t0 = time.perf_counter()

    def _start(self, dsk):
        self.t0 = time.perf_counter()

    def _posttask(self, key, result, dsk, state, worker_id):
        if key not in self.keys:
            return
        with self.lock:
            self.done += 1
            frac = self.done / max(1, self.n)
            if frac >= self.next or self.done == self.n:
                while self.next <= frac:
                    self.next += 0.1
                print(f"[{time.perf_counter() - self.t0:8.1f} s] {self.done}/{self.n} tasks "
                      f"({100 * frac:.0f} %)", file=self.stream or sys.stdout, flush=True)
