"""Execution of stage tasks with dask: threaded scheduler on the job's threads, or a
dask.distributed scheduler given by address; progress as plain lines for job logs.

Tasks are computed independently and returned in order, so results never depend on the
number of workers or the scheduler.
"""
from __future__ import annotations


def compute(tasks: list, n_workers: int, scheduler: str | None, progress: bool):
    """Compute dask.delayed ``tasks`` in order; threaded, or on a distributed scheduler."""
    import dask
    if scheduler:
        from dask.distributed import Client
        from dask.distributed import progress as dprogress
        with Client(scheduler) as client:
            futs = client.compute(tasks)
            if progress:
                dprogress(futs)
            return client.gather(futs)
    if progress:
        with _LineProgress(len(tasks)):
            return list(dask.compute(*tasks, scheduler="threads", num_workers=n_workers))
    return list(dask.compute(*tasks, scheduler="threads", num_workers=n_workers))


def _progress_callback_class():
    from dask.callbacks import Callback

    class LineProgress(Callback):
        """Progress of a dask computation as plain lines (for job logs): every 10 %."""

        def __init__(self, n_tasks, stream=None):
            super().__init__()
            self.n, self.done, self.next = n_tasks, 0, 0.1
            self.stream = stream
            self.lock = __import__("threading").Lock()

        def _start(self, dsk):
            import time
            self.t0 = time.perf_counter()

        def _posttask(self, key, result, dsk, state, worker_id):
            import sys
            import time
            name = key[0] if isinstance(key, tuple) else key
            if not str(name).startswith(("_batch_block", "_sweep_line", "_robust_block")):
                return
            with self.lock:
                self.done += 1
                frac = self.done / max(1, self.n)
                if frac >= self.next or self.done == self.n:
                    while self.next <= frac:
                        self.next += 0.1
                    print(f"[{time.perf_counter() - self.t0:8.1f} s] {self.done}/{self.n} tasks "
                          f"({100 * frac:.0f} %)", file=self.stream or sys.stdout, flush=True)

    return LineProgress


def _LineProgress(n_tasks, stream=None):
    return _progress_callback_class()(n_tasks, stream)
