"""Many pairs at once: ``hamta batch`` and Processing's "Batch register", on Dask distributed.

:mod:`.jobs` reads what to register (a CSV or GeoPackage list, or targets matched against one
reference), :mod:`.task` is the function each pair runs as (the same on a local cluster and on a
remote one), :mod:`.runner` schedules the pairs on a Dask client and gathers their records, and
:mod:`.table` writes the results table. Dask is imported only when a batch runs.
"""
from .jobs import Job, read_jobs
from .runner import BatchResult, run_batch

__all__ = ["Job", "read_jobs", "run_batch", "BatchResult"]
