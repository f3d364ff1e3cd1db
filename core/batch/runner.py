"""Schedule a batch's pairs on Dask distributed and gather their records.

By default a ``LocalCluster`` sized to the machine (one single-threaded worker process per core:
the registration itself uses native threads where it pays). Its scheduler, nanny and worker
listeners are on 127.0.0.1 only and speak TLS with credentials made for that cluster and held in
memory (mutual authentication: a process without them can neither connect nor submit work), and it
has no dashboard. With ``scheduler`` an existing cluster: ``tls://host:port`` with the client
credentials of Dask's own configuration (``distributed.comm.tls.ca-file``,
``distributed.comm.tls.client.cert``, ``distributed.comm.tls.client.key``), or ``tcp://host:port``,
which is unauthenticated and logged as such; its workers need the installed package and access to
the paths. A scheduler that does not answer within ``CONNECT_TIMEOUT_S`` raises
:class:`SchedulerError`. Each pair is one task (:func:`hamta.core.batch.task.register_job`); a pair
that fails is recorded, never stops the batch; a worker that dies has its pairs run again elsewhere
(Dask's own rescheduling), and since outputs are published whole, nothing half-written is left.
Pairs already finished in an earlier run are taken from their folders without scheduling them
(resumable).
"""
from __future__ import annotations

import logging
import os
import time
import uuid
from dataclasses import dataclass, field
from typing import Callable, List, Optional

from ..errors import HamtaError, InputError, RegistrationCanceled, UsageError
from ..progress import Monitor
from .jobs import Job
from .task import BatchSettings, failed_record, finished_record, register_job

CONNECT_TIMEOUT_S = 5
logger = logging.getLogger(__name__)


class SchedulerError(HamtaError):
    """The Dask scheduler cannot be reached, or this client has no credentials for it."""


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
    if workers is not None and workers < 1:
        raise UsageError(f"workers must be a whole number of at least 1 (default: the CPU count), got {workers!r}")
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
    """``with scheduler_map("tls://host:port") as map_chunks:`` a ``map_chunks(fn, chunks)`` for
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
            record = _result(fut, futures[fut], settings)
            failed += record["status"] == "failed"
            done += 1
            left = (time.perf_counter() - started) / max(done - (total - len(todo)), 1) * len(pending)
            monitor.report(done / total, f"{done}/{total} pairs, {failed} failed, ~{left:.0f} s left")
            yield record


def _result(future, job: Job, settings: BatchSettings) -> dict:
    try:
        return future.result()
    except Exception as exc:  # the task itself never raises: a lost worker, a cancellation, a pickling error
        return failed_record(job, job.method or settings.method, 0.0, f"{type(exc).__name__}: {exc}".strip())


def unauthenticated_warning(scheduler: Optional[str]) -> Optional[str]:
    """What to tell the user about a scheduler address other than ``tls://`` (None for ``tls://``)."""
    scheme = scheduler.split("://")[0].lower() if scheduler and "://" in scheduler else "tcp"
    if not scheduler or scheme == "tls":
        return None
    return (f"Warning: the Dask scheduler {scheduler} is unauthenticated ({scheme}://): anyone who can reach it can "
            "run code as its workers' user. Use tls://HOST:PORT with certificates (see README).")


class _client:
    """A Dask client: on ``scheduler`` if given, else on a new LocalCluster closed afterwards."""

    def __init__(self, scheduler, workers, processes):
        self.scheduler, self.workers, self.processes = scheduler, workers, processes

    def __enter__(self):
        if not _dask_installed():
            raise InputError("Batches run on Dask distributed, which is not installed (pip install distributed; "
                             "Debian: apt install python3-distributed).")
        from distributed import Client

        if self.scheduler:
            self.client, self.cluster = _connect(self.scheduler), None
        else:
            self.cluster = _local_cluster(self.workers or os.cpu_count() or 1, self.processes)
            self.client = Client(self.cluster)
        return self.client

    def __exit__(self, *exc):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()
        return False


def _local_cluster(n: int, processes: bool):
    """A LocalCluster reachable only with the credentials it makes (TLS on 127.0.0.1), without a
    dashboard. Dask always starts HTTP servers too: on 127.0.0.1 (given explicitly, since older Dask
    binds a worker's to every interface otherwise), answering health checks only (and a worker's
    read-only status pages when bokeh is installed)."""
    import importlib.util

    import dask
    from distributed import LocalCluster

    if importlib.util.find_spec("cryptography") is None:
        raise InputError("The local Dask cluster authenticates with TLS credentials made for each batch, which "
                         "needs the cryptography package (pip install cryptography; Debian: apt install "
                         "python3-cryptography).")
    health_only = {"distributed.scheduler.http.routes": ["distributed.http.health"],
                   "distributed.worker.http.routes": ["distributed.http.health"]}
    with dask.config.set(health_only):
        return LocalCluster(n_workers=n, threads_per_worker=1, processes=processes, host="127.0.0.1", security=True,
                            dashboard_address=None, worker_dashboard_address="127.0.0.1:0",
                            scheduler_kwargs={"dashboard_address": "127.0.0.1:0", "dashboard": False},
                            silence_logs=logging.ERROR)


def _connect(address: str):
    """A client of the scheduler at ``address``, or :class:`SchedulerError` within ``CONNECT_TIMEOUT_S``."""
    from distributed import Client
    from distributed.security import Security

    warning = unauthenticated_warning(address)
    if warning:
        logger.warning(warning)
    if address.lower().startswith("tls://") and Security().get_connection_args("client")["ssl_context"] is None:
        raise SchedulerError(f"The Dask scheduler {address} needs TLS credentials, and Dask's configuration has none: "
                             "set distributed.comm.tls.ca-file, distributed.comm.tls.client.cert and "
                             "distributed.comm.tls.client.key (for example DASK_DISTRIBUTED__COMM__TLS__CA_FILE=ca.pem "
                             "and the like, or ~/.config/dask/distributed.yaml).")
    try:
        return Client(address, timeout=f"{CONNECT_TIMEOUT_S}s")
    except OSError as exc:  # refused, timed out, or a TLS handshake the scheduler rejected
        raise SchedulerError(f"The Dask scheduler {address} did not accept a connection within {CONNECT_TIMEOUT_S} s "
                             f"({exc}); check the address, that the scheduler runs, and for tls:// the "
                             "credentials.") from None
