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
from hamta.core.reference import RasterReference, ServiceReference, resolve_reference

SIFT = BatchSettings(method="sift")


def _targets(tmp_path, small_pair, n):
    folder = tmp_path / "targets"
    folder.mkdir()
    for i in range(n):
        shutil.copy(small_pair["target"], folder / f"t{i:02d}.tif")
    return folder


def test_job_lists_from_csv_geopackage_and_a_pattern(tmp_path, small_pair):
    folder = _targets(tmp_path, small_pair, 2)
    (tmp_path / "jobs.csv").write_text("Target,reference,method,output\n"
                                       f"targets/t00.tif,{small_pair['reference']},sift,\n"
                                       f"targets/t01.tif,{small_pair['reference']},,custom\n")
    jobs = read_jobs(str(tmp_path / "jobs.csv"), str(tmp_path / "out"))
    assert [j.target for j in jobs] == [str(folder / "t00.tif"), str(folder / "t01.tif")]
    assert jobs[0].method == "sift" and jobs[1].method is None
    assert jobs[0].out == str(tmp_path / "out" / "t00") and jobs[1].out == str(tmp_path / "out" / "custom")
    pattern = read_jobs(str(folder / "*.tif"), str(tmp_path / "o"), small_pair["reference"])
    assert [j.name for j in pattern] == ["t00", "t01"] and len({j.key for j in pattern}) == 2
    with sqlite3.connect(tmp_path / "jobs.gpkg") as con:
        con.execute("CREATE TABLE gpkg_contents (table_name TEXT, data_type TEXT)")
        con.execute("INSERT INTO gpkg_contents VALUES ('jobs', 'attributes')")
        con.execute("CREATE TABLE jobs (fid INTEGER PRIMARY KEY, target TEXT, reference TEXT)")
        con.execute("INSERT INTO jobs (target, reference) VALUES (?, ?)", (str(folder / "t01.tif"),
                                                                             small_pair["reference"]))
    assert [j.name for j in read_jobs(str(tmp_path / "jobs.gpkg"), str(tmp_path / "o"))] == ["t01"]
    (tmp_path / "bad.csv").write_text("image\nx.tif\n")
    with pytest.raises(InputError, match="no 'target' column"):
        read_jobs(str(tmp_path / "bad.csv"), str(tmp_path / "o"))
    with pytest.raises(InputError, match="need a reference"):
        read_jobs(str(folder), str(tmp_path / "o"))


def test_a_local_cluster_registers_records_failures_and_resumes(tmp_path, small_pair):
    folder = _targets(tmp_path, small_pair, 2)
    (folder / "broken.tif").write_text("not a raster")
    jobs = read_jobs(str(folder), str(tmp_path / "out"), small_pair["reference"])
    result = run_batch(jobs, SIFT, workers=2)
    assert [r["status"] for r in result.records] == ["failed", "verified", "verified"]
    assert "broken.tif" in result.records[0]["message"] and result.workers == 2
    for r in result.records[1:]:
        assert sorted(os.listdir(r["out"])) == sorted([".hamta-manifest.json", ".hamta.lock", "gcps.gpkg",
                                                       "gcps.points", "registered.tif", "report.html", "report.json"])
        assert r["footprint"] and r["error_bound_px"] < 3 and r["method_used"] == "sift"
    tables = write_results(str(tmp_path / "out"), result.records)
    with sqlite3.connect(tables["gpkg"]) as con:
        rows = con.execute("SELECT name, status, geom IS NOT NULL FROM pairs ORDER BY fid").fetchall()
    assert rows == [("broken", "failed", 0), ("t00", "verified", 1), ("t01", "verified", 1)]
    again = run_batch(jobs, SIFT, workers=1)
    assert [r["resumed"] for r in again.records] == [False, True, True]
    assert again.counts() == {"pairs": 3, "verified": 2, "unverified": 0, "failed": 1, "resumed": 2}


XYZ = "https://tiles.example.com/{z}/{x}/{y}.png"


def test_a_reference_path_is_relative_to_the_job_list_and_a_service_or_gdal_string_is_kept(tmp_path, monkeypatch):
    base = str(tmp_path / "lists")
    assert resolve_reference(" ref.tif ", base) == RasterReference(str(tmp_path / "lists" / "ref.tif"))
    assert resolve_reference("../ref.tif", base) == RasterReference(str(tmp_path / "ref.tif"))
    assert resolve_reference("/data/ref.tif", base) == RasterReference("/data/ref.tif")
    for text in ("/vsicurl/https://example.com/ref.tif", "WMTS:https://example.com/wmts?layer=a",
                 "https://example.com/ref.tif"):
        assert resolve_reference(text, base) == RasterReference(text)
    service = resolve_reference(f" {XYZ} ", base)
    assert isinstance(service, ServiceReference) and service.service.kind == "xyz" and service.text == XYZ
    assert resolve_reference("ref.tif") == RasterReference("ref.tif")
    assert resolve_reference(service, base) is service

    (tmp_path / "lists").mkdir()
    jobs_csv = tmp_path / "lists" / "jobs.csv"
    jobs_csv.write_text(f"target,reference\na.tif,ref.tif\nb.tif,/vsicurl/https://example.com/ref.tif\nc.tif,{XYZ}\n"
                        "d.tif,\n")
    monkeypatch.chdir(tmp_path)
    jobs = read_jobs(str(jobs_csv), str(tmp_path / "out"), "default.tif")
    assert [j.reference for j in jobs] == [RasterReference(str(tmp_path / "lists" / "ref.tif")),
                                           RasterReference("/vsicurl/https://example.com/ref.tif"), service,
                                           RasterReference(str(tmp_path / "default.tif"))]


def test_a_batch_resolves_reference_text_once_where_it_enters(tmp_path, small_pair, monkeypatch):
    import hamta.core.reference as reference_module
    from hamta.core.batch.task import register_job

    parse, calls = reference_module.parse_service, []
    monkeypatch.setattr(reference_module, "parse_service", lambda text: calls.append(text) or parse(text))
    reference = os.path.abspath(small_pair["reference"])
    folder = _targets(tmp_path, small_pair, 3)
    jobs = read_jobs(str(folder), str(tmp_path / "out"), reference)
    assert calls == [reference] and {j.reference for j in jobs} == {RasterReference(reference)}
    (tmp_path / "jobs.csv").write_text(f"target,reference\ntargets/t00.tif,{reference}\ntargets/t01.tif,{XYZ}\n")
    listed = read_jobs(str(tmp_path / "jobs.csv"), str(tmp_path / "listed"), reference)
    assert calls == [reference, reference, reference, XYZ]  # --reference once, then each row's own
    assert isinstance(listed[1].reference, ServiceReference)
    assert register_job(jobs[0], SIFT)["status"] == "verified"
    assert register_job(jobs[0], SIFT)["resumed"]
    assert len(calls) == 4  # neither the run nor the resume looked at the text again


def test_a_job_pickles_with_its_typed_reference_and_keeps_its_key():
    import hashlib
    import pickle

    from hamta.core.batch.jobs import Job

    for reference in (RasterReference("/data/ref.tif"), resolve_reference(XYZ)):
        job = Job("/data/t.tif", reference, "/out/t", "sift", None, "1,2,3,4,EPSG:4326")
        again = pickle.loads(pickle.dumps(job))
        text = "|".join(["/data/t.tif", reference.text, "/out/t", "sift", "", "1,2,3,4,EPSG:4326"])
        assert again == job and again.key == job.key == hashlib.sha1(text.encode()).hexdigest()[:16]


@pytest.fixture
def cluster(tmp_path):
    """A scheduler and two single-threaded workers, each its own process (as on a real cluster)."""
    from hamta.bench.goals.batch import DaskProcesses

    processes = DaskProcesses(2, str(tmp_path))
    with processes as address:
        yield address, processes.procs[1:]


@pytest.mark.processes
def test_a_worker_killed_mid_batch_loses_no_pair_and_corrupts_no_output(tmp_path, small_pair, cluster):
    address, workers = cluster
    folder = _targets(tmp_path, small_pair, 5)
    jobs = read_jobs(str(folder), str(tmp_path / "out"), small_pair["reference"])
    seen = []

    def kill_after_two(fraction, message):
        seen.append(message)
        if sum("pairs," in m for m in seen) == 2 and workers[0].poll() is None:
            workers[0].send_signal(signal.SIGKILL)

    result = run_batch(jobs, SIFT, scheduler=address, progress=kill_after_two)
    assert workers[0].poll() is not None  # the worker really died mid-batch
    assert result.counts()["verified"] == 5, [r["message"] for r in result.records if r["status"] != "verified"]
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


def _listening(pid):
    """(host, port) of every TCP socket the process ``pid`` and its children listen on."""
    import psutil

    out = []
    for proc in [psutil.Process(pid)] + psutil.Process(pid).children(recursive=True):
        conns = proc.net_connections(kind="inet") if hasattr(proc, "net_connections") else proc.connections("inet")
        out += [c.laddr[:2] for c in conns if c.status == psutil.CONN_LISTEN]
    return out


INTRUDER = """
import gc, sys
from distributed import Client
from distributed.security import Security

address = sys.argv[1]
for kwargs in (dict(address=address), dict(address=address.replace("tls://", "tcp://")),
               dict(address=address, security=Security.temporary())):
    try:
        Client(timeout="3s", **kwargs).close()
        print("admitted")
    except Exception:
        print("refused")
    gc.collect()  # a failed client collected while the next one starts would deadlock Dask's loop
"""


def _first_bytes(address, context):
    """What the scheduler at ``address`` (tls://host:port) first sends over TLS with ``context``
    (b"" when it refuses the handshake)."""
    import socket
    import ssl

    host, port = address.split("://")[1].rsplit(":", 1)
    try:
        with socket.create_connection((host, int(port)), timeout=10) as raw, context.wrap_socket(raw) as s:
            return s.recv(64)
    except (ssl.SSLError, ConnectionError):
        return b""


@pytest.mark.parametrize("processes", [True, False], ids=["processes", "threads"])
def test_the_local_cluster_admits_only_its_own_client(processes):
    """The batch's own cluster (as run_batch and Processing start it): TLS on 127.0.0.1 with
    credentials of its own, no dashboard; clients without those credentials are refused."""
    import socket
    import ssl
    import subprocess
    import sys
    import warnings

    from hamta.core.batch.runner import _client

    with socket.socket() as busy, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:  # Dask's dashboard port taken, as by another cluster: no warning about it either way
            busy.bind(("127.0.0.1", 8787))
            busy.listen()
        except OSError:
            pass
        with _client(None, 1, processes) as client:
            address = client.scheduler.address
            assert address.startswith("tls://127.0.0.1:")
            assert client.submit(sum, [1, 2]).result() == 3
            assert {host for host, _ in _listening(os.getpid())} == {"127.0.0.1"}
            intruder = subprocess.run([sys.executable, "-c", INTRUDER, address], capture_output=True, text=True,
                                      timeout=120)
            assert intruder.stdout.split() == ["refused"] * 3, intruder.stderr
            no_certificate = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
            no_certificate.check_hostname, no_certificate.verify_mode = False, ssl.CERT_NONE
            assert _first_bytes(address, no_certificate) == b""
            assert _first_bytes(address, client.security.get_connection_args("client")["ssl_context"])
    assert not [w for w in caught if "8787" in str(w.message) or "already in use" in str(w.message)]


@pytest.fixture
def tls_scheduler(tmp_path):
    """A scheduler and one worker thread on 127.0.0.1 that speak only TLS, with certificates in
    files; yields its address and the Dask configuration of a client holding them."""
    from distributed import LocalCluster
    from distributed.security import Security

    made = Security.temporary()
    cert, key = tmp_path / "cert.pem", tmp_path / "key.pem"
    cert.write_text(made.tls_ca_file)
    key.write_text(made.tls_client_key)
    roles = {f"tls_{role}_{part}": str(path) for role in ("scheduler", "worker", "client")
             for part, path in (("cert", cert), ("key", key))}
    security = Security(tls_ca_file=str(cert), require_encryption=True, **roles)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, host="127.0.0.1", security=security,
                      dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                      worker_dashboard_address="127.0.0.1:0") as cluster:
        yield cluster.scheduler_address, {"distributed.comm.tls.ca-file": str(cert),
                                          "distributed.comm.tls.client.cert": str(cert),
                                          "distributed.comm.tls.client.key": str(key)}


def test_a_tls_scheduler_takes_the_client_credentials_from_dask_configuration(tls_scheduler):
    import time

    import dask

    from hamta.core.batch.runner import SchedulerError, scheduler_map

    address, credentials = tls_scheduler
    with dask.config.set(credentials):
        with scheduler_map(address) as map_chunks:
            assert map_chunks(abs, [-1, -2]) == [1, 2]
        t0 = time.perf_counter()
        with pytest.raises(SchedulerError, match="tls://127.0.0.1:1 did not accept a connection"):
            scheduler_map("tls://127.0.0.1:1").__enter__()
        assert time.perf_counter() - t0 < 15
    with pytest.raises(SchedulerError, match=f"{address} needs TLS credentials.*distributed.comm.tls.ca-file"):
        scheduler_map(address).__enter__()


def test_an_unreachable_or_plain_tcp_scheduler_is_named_plainly(caplog, monkeypatch):
    import time

    from hamta.core.batch import runner
    from hamta.core.batch.runner import SchedulerError

    monkeypatch.setattr(runner, "CONNECT_TIMEOUT_S", 1)  # the wait is the only cost: 5 s by default
    t0 = time.perf_counter()
    with pytest.raises(SchedulerError, match="tcp://127.0.0.1:1 did not accept a connection within 1 s"):
        run_batch([_job("t", "/nowhere")], SIFT, scheduler="tcp://127.0.0.1:1")
    assert time.perf_counter() - t0 < 15
    assert "tcp://127.0.0.1:1 is unauthenticated" in caplog.text


def _job(name, out):
    from hamta.core.batch.jobs import Job

    return Job(f"/nowhere/{name}.tif", RasterReference("/nowhere/reference.tif"), os.path.join(out, name))


@pytest.mark.parametrize("workers", [0, -2])
def test_a_local_cluster_of_no_workers_is_refused(workers):
    with pytest.raises(ValueError, match="workers must be a whole number of at least 1"):
        run_batch([_job("t", "/nowhere")], SIFT, workers=workers)


def _job_list(tmp_path, small_pair, *outputs):
    path = tmp_path / "jobs.csv"
    path.write_text("target,reference,output\n" + "".join(f"{small_pair['target']},{small_pair['reference']},{o}\n"
                                                          for o in outputs))
    return str(path)


@pytest.mark.parametrize("output", ["../../escape", "/tmp/outside", "a/../../escape", ".", "a/.."])
def test_a_job_list_output_outside_out_is_refused(output, tmp_path, small_pair):
    jobs = _job_list(tmp_path, small_pair, "fine", output)
    with pytest.raises(InputError, match=rf"Row 2 of the job list '{jobs}': the output '{output}' is not a folder "
                                         rf"inside the output folder '{tmp_path / 'out'}'"):
        read_jobs(jobs, str(tmp_path / "out"))


def test_two_rows_with_one_output_are_refused_and_named_names_avoid_outputs(tmp_path, small_pair):
    jobs = _job_list(tmp_path, small_pair, "a", "b", "x/../a/")
    with pytest.raises(InputError, match=rf"Rows 1 and 3 of the job list '{jobs}' have the same output folder "
                                         rf"'{tmp_path / 'out' / 'a'}'"):
        read_jobs(jobs, str(tmp_path / "out"))
    jobs = _job_list(tmp_path, small_pair, "", "target", "deep/inside")
    assert [j.out for j in read_jobs(jobs, str(tmp_path / "out"))] == [
        str(tmp_path / "out" / "target-2"), str(tmp_path / "out" / "target"), str(tmp_path / "out" / "deep/inside")]


def test_a_csv_row_with_more_fields_than_the_header_is_named(tmp_path, small_pair):
    jobs = tmp_path / "jobs.csv"
    jobs.write_text(f"target,reference\n{small_pair['target']},{small_pair['reference']}\n"
                    f"{small_pair['target']},{small_pair['reference']},sift,oops\n")
    with pytest.raises(InputError, match=rf"Row 2 \(line 3\) of the job list '{jobs}' has 4 fields, more than the 2 "
                                         "columns of its header"):
        read_jobs(str(jobs), str(tmp_path / "out"))


def test_only_a_verified_pair_carries_an_error_bound(tmp_path, small_pair, monkeypatch):
    import importlib

    from hamta.core.batch.jobs import jobs_for_targets
    from hamta.core.batch.task import failed_record, from_report, register_job

    job = jobs_for_targets([small_pair["target"]], small_pair["reference"], str(tmp_path / "out"))[0]
    verified = register_job(job, SIFT)
    assert verified["status"] == "verified" and 0 < verified["error_bound_px"] < 3
    path = os.path.join(job.out, "report.json")
    report = json.loads(open(path).read())
    for verdict in ("suspect", "failed"):
        report["quality"].update(verdict=verdict, error_bound_px=0.97)
        with open(path, "w") as f:
            json.dump(report, f)
        record = from_report(job, "sift", 1.0)
        assert (record["status"], record["verdict"], record["error_bound_px"]) == ("unverified", verdict, None)
    failed = failed_record(job, "sift", 1.0, "no luck")
    assert (failed["status"], failed["verdict"], failed["error_bound_px"]) == ("failed", None, None)

    def silent_failure(*args, **kwargs):
        raise ValueError()

    monkeypatch.setattr(importlib.import_module("hamta.core.runner"), "run", silent_failure)
    other = jobs_for_targets([small_pair["target"]], small_pair["reference"], str(tmp_path / "other"))[0]
    record = register_job(other, SIFT)
    assert (record["status"], record["message"], record["error_bound_px"]) == ("failed", "ValueError", None)


def test_a_bug_in_a_method_fails_its_pair_naming_the_method(tmp_path, small_pair, raising_method):
    from hamta.core.batch.jobs import jobs_for_targets
    from hamta.core.batch.task import register_job

    name = raising_method(ZeroDivisionError("division by zero"))
    job = jobs_for_targets([small_pair["target"]], small_pair["reference"], str(tmp_path / "out"))[0]
    record = register_job(job, BatchSettings(method=name))
    assert record["status"] == "failed"
    assert record["message"] == f"internal error in method '{name}' (ZeroDivisionError: division by zero)"
