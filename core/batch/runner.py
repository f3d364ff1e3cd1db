"""Schedule a batch's pairs on Dask distributed and gather their records.

By default a ``LocalCluster`` sized to the machine (one single-threaded worker process per core:
the registration itself uses native threads where it pays); with ``scheduler`` an existing cluster
(``tcp://host:port``), whose workers need the installed package and access to the paths. Each pair
is one task (:func:`hamta.core.batch.task.register_job`); a pair that fails is recorded, never stops
the batch; a worker that dies has its pairs run again elsewhere (Dask's own rescheduling), and since
outputs are published whole, nothing half-written is left. Pairs already finished in an earlier run
are taken from their folders without scheduling them (resumable).
"""
from __future__ import annotations

import logging
import os
import time
import uuid
from dataclasses import dataclass, field
from typing import Callable, List, Optional

from ..errors import RegistrationCanceled
from ..progress import Monitor
from .jobs import Job
from .task import BatchSettings, failed_record, finished_record, register_job


@dataclass(frozen=True)
class BatchResult:
    """Every job's record (in the jobs' order) and the batch's wall time."""

    records: List[dict]
    seconds: float
    workers: int = 0
    notes: List[str] = field(default_factory=list)

    def counts(self) -> dict:
        out = {"pairs": len(self.records), "verified": 0, "unverified": 0, "failed": 0, "resumed": 0}
        for r in self.records:
            out[r["status"]] += 1
            out["resumed"] += bool(r.get("resumed"))
        return out

    def summary(self) -> str:
        c = self.counts()
        ran = c["pairs"] - c["resumed"]
        rate = f"; {60.0 * ran / self.seconds:.1f} pairs per minute" if ran and self.seconds > 0 else ""
        return (f"{c['pairs']} pairs: {c['verified']} verified, {c['unverified']} not verified, {c['failed']} failed "
                f"({c['resumed']} already done in an earlier run); {self.seconds:.1f} s on {self.workers} workers"
                f"{rate}")


def run_batch(jobs: List[Job], settings: BatchSettings = BatchSettings(), *, scheduler: Optional[str] = None,
              workers: Optional[int] = None, processes: bool = True, progress: Optional[Callable] = None,
              is_canceled: Optional[Callable] = None) -> BatchResult:
    """Register every job; see the module docstring. ``workers`` sizes the local cluster (default:
    the CPU count); ``processes=False`` runs its workers as threads of this process (inside QGIS)."""
    monitor = Monitor(progress, is_canceled)
    t0 = time.perf_counter()
    records = {j.key: finished_record(j, settings) for j in jobs}
    todo = [j for j in jobs if records[j.key] is None]
    monitor.report(0.0, f"{len(jobs) - len(todo)} of {len(jobs)} pairs already done")
    n_workers, notes = 0, []
    if todo and scheduler is None and not _dask_installed():
        notes.append("Dask distributed is not installed: the pairs ran one after the other in this process")
        n_workers = 1
        for i, job in enumerate(todo):
            monitor.report((len(jobs) - len(todo) + i) / len(jobs), f"{job.name}")
            records[job.key] = register_job(job, settings)
    elif todo:
        with _client(scheduler, workers, processes) as client:
            n_workers = len(client.scheduler_info().get("workers", {}))
            for record in _gather(client, todo, settings, monitor, len(jobs) - len(todo), len(jobs), t0):
                records[record["key"]] = record
    monitor.report(1.0, "done")
    return BatchResult([records[j.key] for j in jobs], time.perf_counter() - t0, n_workers, notes)


class scheduler_map:
    """``with scheduler_map("tcp://host:port") as map_chunks:`` a ``map_chunks(fn, chunks)`` for
    :func:`hamta.core.register` that measures a big scene's local-correction windows on a cluster."""

    def __init__(self, scheduler: str):
        self.inner = _client(scheduler, None, True)

    def __enter__(self):
        client = self.inner.__enter__()
        return lambda fn, chunks: client.gather(client.map(fn, chunks, pure=False))

    def __exit__(self, *exc):
        return self.inner.__exit__(*exc)


def _dask_installed() -> bool:
    import importlib.util

    return importlib.util.find_spec("distributed") is not None


def _gather(client, todo: List[Job], settings: BatchSettings, monitor: Monitor, done: int, total: int, t0: float):
    from distributed import wait

    nonce = uuid.uuid4().hex[:8]  # a rerun on the same cluster must not reuse the scheduler's cached results
    futures = {client.submit(register_job, job, settings, key=f"hamta-{job.name}-{job.key}-{nonce}", pure=False,
                             retries=1): job for job in todo}
    pending, failed, started = set(futures), 0, time.perf_counter()
    while pending:
        if monitor.canceled():
            client.cancel(list(pending))
            raise RegistrationCanceled("Batch canceled; finished pairs keep their outputs, the others have none.")
        try:
            finished, pending = wait(list(pending), timeout=0.5, return_when="FIRST_COMPLETED")
        except TimeoutError:  # nothing finished in the last half second: look for a cancel again
            continue
        for fut in finished:
            record = _result(fut, futures[fut])
            failed += record["status"] == "failed"
            done += 1
            left = (time.perf_counter() - started) / max(done - (total - len(todo)), 1) * len(pending)
            monitor.report(done / total, f"{done}/{total} pairs, {failed} failed, ~{left:.0f} s left")
            yield record


def _result(future, job: Job) -> dict:
    try:
        return future.result()
    except Exception as exc:  # the task itself never raises: a lost worker, a cancellation, a pickling error
        return failed_record(job, job.method or "", 0.0, f"{type(exc).__name__}: {exc}".strip())


class _client:
    """A Dask client: on ``scheduler`` if given, else on a new LocalCluster closed afterwards."""

    def __init__(self, scheduler, workers, processes):
        self.scheduler, self.workers, self.processes = scheduler, workers, processes

    def __enter__(self):
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            from ..errors import InputError

            raise InputError("Batches run on Dask distributed, which is not installed (pip install distributed; "
                             "Debian: apt install python3-distributed).") from None
        if self.scheduler:
            self.client, self.cluster = Client(self.scheduler, timeout="30s"), None
        else:
            n = self.workers or os.cpu_count() or 1
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=self.processes,
                                        dashboard_address=None, silence_logs=logging.ERROR)
            self.client = Client(self.cluster)
        return self.client

    def __exit__(self, *exc):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()
        return False
