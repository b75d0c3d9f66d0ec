"""Running independent tasks in this process or on dask.distributed, with a progress bar.

Every task gives one row (a dict); a task that raises, or whose worker dies, gives a row made by
`failed(index, message)`, so a sweep never loses its other rows.
"""
import contextlib
import logging
import sys
import time
import uuid


class Progress:
    """One line on stderr, redrawn as runs finish: bar, runs done, failures, elapsed time."""

    def __init__(self, total, label, enabled, stream=None):
        self.total, self.label, self.enabled = total, label, enabled
        self.stream = stream or sys.stderr
        self.done = self.failed = 0
        self.start = time.perf_counter()
        self._draw()

    def update(self, row):
        self.done += 1
        self.failed += row.get("status") != "ok"
        self._draw()

    def _draw(self):
        if not self.enabled:
            return
        width = 30
        filled = width * self.done // max(self.total, 1)
        end = "\n" if self.done >= self.total else ""
        self.stream.write(f"\r[{'#' * filled}{' ' * (width - filled)}] {self.done}/{self.total} "
                          f"{self.label}, {self.failed} not ok, "
                          f"{time.perf_counter() - self.start:.1f} s{end}")
        self.stream.flush()


@contextlib.contextmanager
def dask_client(workers, scheduler, client):
    """A dask.distributed Client: `client` itself, one connected to `scheduler` (an address), or
    one on a new LocalCluster of `workers` single-threaded worker processes on 127.0.0.1."""
    if client is not None:
        yield client
        return
    try:
        from distributed import Client, LocalCluster
    except ImportError as e:
        raise RuntimeError("sweeps on workers need dask.distributed (Debian: python3-distributed; "
                           "workers=0 runs serially without it)") from e
    if scheduler is not None:
        with Client(scheduler) as c:
            yield c
        return
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
            Client(cluster) as c:
        yield c


def run_tasks(function, tasks, failed, *, workers=2, scheduler=None, client=None, progress=True,
              label="runs"):
    """[function(task) for task in tasks], each in this process (workers=0 and no scheduler or
    client) or on Dask; a task that fails gives failed(index, message) instead."""
    if not isinstance(workers, int) or workers < 0:
        raise ValueError(f"workers: must be an integer >= 0, got {workers!r}")
    if scheduler is not None and client is not None:
        raise ValueError("scheduler, client: give one, not both")
    bar = Progress(len(tasks), label, progress)
    rows = [None] * len(tasks)
    if workers == 0 and scheduler is None and client is None:
        for i, task in enumerate(tasks):
            try:
                rows[i] = function(task)
            except Exception as e:  # noqa: BLE001  (a failed run is a row, not a lost sweep)
                rows[i] = failed(i, f"{type(e).__name__}: {e}")
            bar.update(rows[i])
        return rows
    from distributed import as_completed
    with dask_client(workers, scheduler, client) as c:
        token = uuid.uuid4().hex[:8]
        futures = {c.submit(function, task, key=f"superdex-{label}-{token}-{i}", pure=False): i
                   for i, task in enumerate(tasks)}
        for future in as_completed(list(futures)):
            i = futures[future]
            try:
                rows[i] = future.result()
            except Exception as e:  # noqa: BLE001  (raised in the task, or its worker died)
                rows[i] = failed(i, f"{type(e).__name__}: {e}")
            future.release()
            bar.update(rows[i])
    return rows
