"""Batch throughput (issue 16): 20 pairs on a 2-worker Dask cluster against the same pairs in turn.

``hamta bench --families batch``. Twenty copies of the demo pair (760 x 700 target, 1000 px reference)
are registered with SIFT and all their outputs written: first one after the other in one process
(which may use every core for the threaded parts), then by ``hamta.core.batch.run_batch`` on a
cluster of a scheduler and two single-threaded workers, each started as its own process
(``python -m distributed.cli.dask_scheduler`` / ``dask_worker``), as on a real cluster. Same total
cores; the ratio of throughputs is the goal (within 10 %).
"""
from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import time

from ..study import Study

PAIRS = 20


def units(config):
    return ["batch"]


def run_unit(unit, config) -> list:
    """One row: the pairs registered in turn, then on a 2-worker cluster: seconds of each, verified counts."""
    from ...core.batch import read_jobs, run_batch
    from ...core.batch.task import BatchSettings, register_job
    from ..sample import make_demo_pair

    folder = os.path.join(config.out_dir, "cases", "batch")
    shutil.rmtree(folder, ignore_errors=True)
    pair = make_demo_pair(os.path.join(folder, "sample"))
    targets = os.path.join(folder, "targets")
    os.makedirs(targets)
    for i in range(PAIRS):
        shutil.copy(pair["target"], os.path.join(targets, f"t{i:02d}.tif"))
    settings = BatchSettings(method="sift")
    jobs = read_jobs(targets, os.path.join(folder, "sequential"), pair["reference"])
    t0 = time.perf_counter()
    sequential = [register_job(job, settings) for job in jobs]
    seq_s = time.perf_counter() - t0
    jobs = read_jobs(targets, os.path.join(folder, "cluster"), pair["reference"])
    with DaskProcesses(2, folder) as address:
        t0 = time.perf_counter()
        result = run_batch(jobs, settings, scheduler=address)
        cluster_s = time.perf_counter() - t0
    ok = sum(r["status"] == "verified" for r in sequential), result.counts()["verified"]
    return [{"unit": unit, "pairs": PAIRS, "sequential_s": seq_s, "cluster_s": cluster_s, "verified": ok,
             "workers": result.workers}]


class DaskProcesses:
    """A local scheduler and ``n`` single-threaded workers, each its own process (as on a real
    cluster); ``procs`` holds the scheduler's process, then the workers'. Also the test suite's."""

    def __init__(self, n: int, folder: str):
        self.n, self.folder = n, folder

    def __enter__(self):
        """Start the processes; the scheduler's address once the ``n`` workers have joined it."""
        from distributed import Client

        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        address = f"tcp://127.0.0.1:{port}"
        quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                        "--port", str(port), "--no-dashboard"], **quiet)]
        time.sleep(2)
        self.procs += [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads",
                                         "1", "--no-nanny", "--no-dashboard", "--local-directory",
                                         os.path.join(self.folder, f"worker{i}")], **quiet) for i in range(self.n)]
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(self.n, timeout=120)
        return address

    def __exit__(self, *exc):
        for p in self.procs:
            p.kill()
            p.wait()
        return False


def tables(rows) -> list:
    body = []
    for r in rows:
        seq, clu = 60 * r["pairs"] / r["sequential_s"], 60 * r["pairs"] / r["cluster_s"]
        body.append([r["pairs"], f"{r['sequential_s']:.1f}", f"{seq:.1f}", f"{r['cluster_s']:.1f}", f"{clu:.1f}",
                     f"{clu / seq:.2f}", f"{r['verified'][0]} / {r['verified'][1]}"])
    return [{"title": "batch: 20 pairs one after the other vs on a 2-worker Dask cluster (separate processes)",
             "columns": ["pairs", "in turn s", "in turn pairs/min", "cluster s", "cluster pairs/min",
                         "cluster / in turn", "verified (in turn / cluster)"], "rows": body,
             "note": "Goal: the cluster's throughput within 10 % of the pairs run in turn with the same total cores "
                     "(ratio >= 0.9). The cluster time includes scheduling and result gathering, not its start-up."}]


STUDY = Study("batch", ("sift",), ("batch",), units, run_unit, tables)
