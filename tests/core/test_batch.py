"""Batches on Dask: job lists, a local cluster, resuming, and a real scheduler with a worker killed mid-batch."""
import json
import os
import shutil
import signal
import sqlite3

import pytest

from hamta.core.batch import read_jobs, run_batch
from hamta.core.batch.table import write_results
from hamta.core.batch.task import BatchSettings
from hamta.core.errors import InputError

SIFT = BatchSettings(method="sift")


def _targets(tmp_path, demo_pair, n):
    folder = tmp_path / "targets"
    folder.mkdir()
    for i in range(n):
        shutil.copy(demo_pair["target"], folder / f"t{i:02d}.tif")
    return folder


def test_job_lists_from_csv_geopackage_and_a_pattern(tmp_path, demo_pair):
    folder = _targets(tmp_path, demo_pair, 2)
    (tmp_path / "jobs.csv").write_text("Target,reference,method,output\n"
                                       f"targets/t00.tif,{demo_pair['reference']},sift,\n"
                                       f"targets/t01.tif,{demo_pair['reference']},,custom\n")
    jobs = read_jobs(str(tmp_path / "jobs.csv"), str(tmp_path / "out"))
    assert [j.target for j in jobs] == [str(folder / "t00.tif"), str(folder / "t01.tif")]
    assert jobs[0].method == "sift" and jobs[1].method is None
    assert jobs[0].out == str(tmp_path / "out" / "t00") and jobs[1].out == str(tmp_path / "out" / "custom")
    pattern = read_jobs(str(folder / "*.tif"), str(tmp_path / "o"), demo_pair["reference"])
    assert [j.name for j in pattern] == ["t00", "t01"] and len({j.key for j in pattern}) == 2
    with sqlite3.connect(tmp_path / "jobs.gpkg") as con:
        con.execute("CREATE TABLE gpkg_contents (table_name TEXT, data_type TEXT)")
        con.execute("INSERT INTO gpkg_contents VALUES ('jobs', 'attributes')")
        con.execute("CREATE TABLE jobs (fid INTEGER PRIMARY KEY, target TEXT, reference TEXT)")
        con.execute("INSERT INTO jobs (target, reference) VALUES (?, ?)", (str(folder / "t01.tif"),
                                                                             demo_pair["reference"]))
    assert [j.name for j in read_jobs(str(tmp_path / "jobs.gpkg"), str(tmp_path / "o"))] == ["t01"]
    (tmp_path / "bad.csv").write_text("image\nx.tif\n")
    with pytest.raises(InputError, match="no 'target' column"):
        read_jobs(str(tmp_path / "bad.csv"), str(tmp_path / "o"))
    with pytest.raises(InputError, match="need a reference"):
        read_jobs(str(folder), str(tmp_path / "o"))


def test_a_local_cluster_registers_records_failures_and_resumes(tmp_path, demo_pair):
    folder = _targets(tmp_path, demo_pair, 3)
    (folder / "broken.tif").write_text("not a raster")
    jobs = read_jobs(str(folder), str(tmp_path / "out"), demo_pair["reference"])
    result = run_batch(jobs, SIFT, workers=2)
    assert [r["status"] for r in result.records] == ["failed", "verified", "verified", "verified"]
    assert "broken.tif" in result.records[0]["message"] and result.workers == 2
    for r in result.records[1:]:
        assert sorted(os.listdir(r["out"])) == sorted([".hamta-manifest.json", ".hamta.lock", "gcps.gpkg",
                                                       "gcps.points", "registered.tif", "report.html", "report.json"])
        assert r["footprint"] and r["error_bound_px"] < 3 and r["method_used"] == "sift"
    tables = write_results(str(tmp_path / "out"), result.records)
    with sqlite3.connect(tables["gpkg"]) as con:
        rows = con.execute("SELECT name, status, geom IS NOT NULL FROM pairs ORDER BY fid").fetchall()
    assert rows == [("broken", "failed", 0), ("t00", "verified", 1), ("t01", "verified", 1), ("t02", "verified", 1)]
    again = run_batch(jobs, SIFT, workers=1)
    assert [r["resumed"] for r in again.records] == [False, True, True, True]
    assert again.counts() == {"pairs": 4, "verified": 3, "unverified": 0, "failed": 1, "resumed": 3}


@pytest.fixture
def cluster(tmp_path):
    """A scheduler and two single-threaded workers, each its own process (as on a real cluster)."""
    from hamta.bench.reproductions.batch import DaskProcesses

    processes = DaskProcesses(2, str(tmp_path))
    with processes as address:
        yield address, processes.procs[1:]


def test_a_worker_killed_mid_batch_loses_no_pair_and_corrupts_no_output(tmp_path, demo_pair, cluster):
    address, workers = cluster
    folder = _targets(tmp_path, demo_pair, 20)
    jobs = read_jobs(str(folder), str(tmp_path / "out"), demo_pair["reference"])
    seen = []

    def kill_after_three(fraction, message):
        seen.append(message)
        if sum("pairs," in m for m in seen) == 3 and workers[0].poll() is None:
            workers[0].send_signal(signal.SIGKILL)

    result = run_batch(jobs, SIFT, scheduler=address, progress=kill_after_three)
    assert workers[0].poll() is not None  # the worker really died mid-batch
    assert result.counts()["verified"] == 20, [r["message"] for r in result.records if r["status"] != "verified"]
    for r in result.records:
        manifest = json.loads(open(os.path.join(r["out"], ".hamta-manifest.json")).read())
        report = json.loads(open(os.path.join(r["out"], "report.json")).read())
        assert report["run_id"] == manifest["run_id"]
        assert all(os.path.getsize(os.path.join(r["out"], n)) == size for n, size in manifest["files"].items())
        assert not [n for n in os.listdir(r["out"]) if n.startswith(".hamta-staging-")]


def test_a_big_scene_measures_its_local_windows_on_the_cluster(tmp_path, demo_pair, cluster):
    import psutil

    from hamta.cli.main import main

    address, workers = cluster
    busy = lambda: sum(psutil.Process(w.pid).cpu_times().user for w in workers)  # noqa: E731
    before = busy()
    out = tmp_path / "out"
    rc = main(["register", "--reference", demo_pair["reference"], "--target", demo_pair["target"], "--out", str(out),
               "--method", "sift", "--local", "--scheduler", address, "--quiet"])
    report = json.loads((out / "report.json").read_text())
    assert rc == 0 and report["model"]["type"] == "tps" and report["local"]["n_kept"] >= 40
    assert busy() - before > 0.3  # the windows were measured by the cluster's workers
