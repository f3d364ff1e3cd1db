"""The function every pair of a batch runs as, on whichever worker Dask gives it.

:func:`register_job` registers one :class:`~hamta.core.batch.jobs.Job` with :func:`hamta.core.runner.run`
into the job's own output folder (published whole or not at all, so a worker killed mid-write
leaves nothing half-written) and returns a plain record (JSON-able) of what happened; it never
raises for a pair that fails, so one bad pair never stops a batch. A job whose folder already holds
a whole set published for the same inputs and request is not run again (:func:`finished_record`).

A record's ``status`` is the pair's outcome: 'verified'; 'unverified' when a model was found but the
independent check did not verify it (its ``verdict`` then says 'suspect' or 'failed', the check's
own words, as ``hamta register`` exits 3 for both); 'failed' when no model was found (``verdict``
None). ``error_bound_px`` (reference px) is given only for a verified pair, since the check bounds
the error of nothing else.
"""
from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass, replace
from typing import Optional

from ..basemap.redact import redact
from ..coords import raster_outline
from ..errors import HamtaError, MethodCrashed, UnverifiedResult
from ..options import OutputOptions, RegisterOptions
from ..reference import Reference, ServiceReference
from .jobs import Job


@dataclass(frozen=True)
class BatchSettings:
    """What every pair shares: the method (a job's own overrides it), options and output options,
    whether unverified results are written, and whether a pair's local correction may spread its
    windows over the cluster's workers."""

    method: str = "auto"
    options: RegisterOptions = RegisterOptions()
    output: OutputOptions = OutputOptions()
    accept_unverified: bool = False
    spread_local: bool = True
    overwrite: bool = False


def register_job(job: Job, settings: BatchSettings) -> dict:
    """Register ``job``; return its record (status 'verified', 'unverified' or 'failed')."""
    from ..outputs import OutputPaths
    from ..runner import run

    method, options = job_request(job, settings)
    done = finished_record(job, settings)
    if done is not None:
        return done
    t0 = time.perf_counter()
    try:
        paths = OutputPaths.in_folder(job.out, raster_format=settings.output.format, overwrite=settings.overwrite)
        run(job.target, job.reference, paths, method=method, options=options, output=settings.output,
            params=_grid_params(job), accept_unverified=settings.accept_unverified,
            map_chunks=_cluster_map() if settings.spread_local else None)
    except UnverifiedResult:
        pass  # its report says why; the record reads it
    except (HamtaError, MethodCrashed, ValueError, ArithmeticError, MemoryError) as exc:  # this pair fails
        lines = str(exc).strip().splitlines() or [type(exc).__name__]
        return failed_record(job, method, time.perf_counter() - t0, lines[0])
    return from_report(job, method, time.perf_counter() - t0)


def job_request(job: Job, settings: BatchSettings):
    """(method, RegisterOptions) of ``job``: the batch's, with the job's own method, model and extent; a sheet by
    its own grid: 'grid'."""
    options = settings.options if job.model is None else replace(settings.options, model=job.model)
    options = options if job.extent is None else replace(options, extent=job.extent)
    return ("grid" if job.reference is None else job.method or settings.method), options


def _grid_params(job: Job) -> Optional[dict]:
    return None if job.reference is not None else {"sheet_crs": job.sheet_crs, "hints": job.hints}


def finished_record(job: Job, settings: BatchSettings) -> Optional[dict]:
    """The record of an earlier run of ``job`` asked the same (inputs, method, options, output options,
    accepting unverified results) whose published set is whole (every file its manifest lists, at its
    size, after finishing a publication a killed run committed), else None."""
    from dataclasses import asdict

    from ..outputs.atomic import published_files, recover
    from ..runner import run_request

    method, options = job_request(job, settings)
    report = os.path.join(job.out, "report.json")
    try:
        recover(job.out)
        files = published_files(job.out)
        whole = bool(files) and all(os.path.getsize(os.path.join(job.out, n)) == size for n, size in files.items())
        if not whole or "report.json" not in files:
            return None
        with open(report, encoding="utf-8") as f:
            rep = json.load(f)
        same = (os.path.abspath(rep["target"]["path"]) == job.target
                and (job.reference is None or _same_reference(rep["reference"], job.reference))
                and rep.get("request") == run_request(method, _request_params(job), options,
                                                      settings.accept_unverified)
                and rep.get("output_options") == json.loads(json.dumps(asdict(settings.output))))
    except (OSError, ValueError, KeyError, TypeError, HamtaError):
        return None
    if not same:
        return None
    record = from_report(job, method, rep.get("timings_s", {}).get("total", 0.0), rep)
    record["resumed"] = True
    return record


def _request_params(job: Job):
    """A job's method parameters as its run's request keeps them."""
    if job.reference is None:
        from ..grid.register import GridParams

        return GridParams.make(_grid_params(job), OutputOptions())
    return None


def _same_reference(described: dict, reference: Reference) -> bool:
    """Whether ``report.json``'s reference (a file, a GDAL string without credentials, or a map service
    recognised by its digest) is ``reference``."""
    service = described.get("service")
    if isinstance(reference, ServiceReference):
        return bool(service) and reference.service.id == service.get("id")
    path = reference.path
    return not service and (described["path"] in (path, redact(path)) or os.path.abspath(described["path"]) == path)


def from_report(job: Job, method: str, seconds: float, rep: Optional[dict] = None) -> dict:
    """A job's record from the ``report.json`` its run wrote (``rep``: that report, already read)."""
    from ..mapping import map_points_from_report

    path = os.path.join(job.out, "report.json")
    if rep is None:
        with open(path, encoding="utf-8") as f:
            rep = json.load(f)
    quality = rep.get("quality") or {}
    verdict = quality.get("verdict")
    border = raster_outline(rep["target"]["width"], rep["target"]["height"], 9, ends=True)
    try:
        footprint = [p["map"] for p in map_points_from_report(path, border)]
    except HamtaError:
        footprint = None
    status = "verified" if verdict == "verified" else "unverified"
    stats = rep.get("stats", {})
    bound = quality.get("error_bound_px") if status == "verified" else None
    return _record(job, method, status, seconds, method_used=rep.get("method"), verdict=verdict, error_bound_px=bound,
                   rmse_px=stats.get("rmse_px"), n_gcps=stats.get("n_gcps"),
                   outputs=rep.get("outputs") or {"report": path}, footprint=footprint,
                   crs=rep["reference"].get("crs"), pixel_mode=bool(rep["reference"].get("pixel_mode")),
                   message="; ".join(quality.get("reasons") or []))


def failed_record(job: Job, method: str, seconds: float, message: str) -> dict:
    """The record of a pair that produced no registration (no verdict, no error figures)."""
    return _record(job, method, "failed", seconds, message=message)


def _record(job: Job, method: str, status: str, seconds: float, **fields) -> dict:
    record = {"key": job.key, "name": job.name, "target": job.target, "reference": job.reference_label,
              "out": job.out,
              "method": method, "status": status, "time_s": round(float(seconds), 3), "method_used": None,
              "verdict": None, "error_bound_px": None, "rmse_px": None, "n_gcps": None, "outputs": {},
              "footprint": None, "crs": None, "pixel_mode": False, "message": "", "resumed": False}
    record.update(fields)
    return record


def _cluster_map():
    """Inside a Dask worker: spread a pair's local-correction windows over the cluster (the task
    leaves its worker slot while it waits); elsewhere None (the windows are measured in place)."""
    try:
        from distributed import get_worker, worker_client
        get_worker()
    except (ImportError, ValueError):
        return None

    def map_chunks(fn, chunks):
        with worker_client() as client:
            return client.gather(client.map(fn, chunks, pure=False))

    return map_chunks
