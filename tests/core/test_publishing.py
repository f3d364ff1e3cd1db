"""Nothing lost, nothing mixed (issue 25): SIGKILL at every step of publishing leaves exactly the old set or
exactly the new one, and batch resume agrees; files Hamta did not write are never replaced or removed
without ``--overwrite``; exit codes stay right when the standard streams are closed, full or abandoned."""
import errno
import hashlib
import json
import os
import pickle
import signal
import subprocess
import sys

import pytest

from hamta.cli.main import main
from hamta.core import register
from hamta.core.batch.jobs import Job
from hamta.core.batch.task import BatchSettings, finished_record
from hamta.core.outputs import OutputPaths, write_outputs
from hamta.core.outputs.atomic import JOURNAL, MANIFEST, STAGING_PREFIX, remove_leftovers
from hamta.core.reference import RasterReference
from hamta.core.runner import run_request

# Publishes the pickled result into the folder with os.replace killing the process at its K-th call
# from atomic publishing (K = 0: never), as a power cut or `kill -9` would.
KILLER = """
import os, pickle, signal, sys
import hamta.core.outputs.atomic as atomic
from hamta.core.outputs import OutputPaths, write_outputs
from hamta.core.runner import run_request
(result, options), folder, k = pickle.load(open(sys.argv[1], "rb")), sys.argv[2], int(sys.argv[3])
calls, real = [0], os.replace
class Os:
    def __getattr__(self, name):
        return getattr(os, name)
    def replace(self, a, b):
        calls[0] += 1
        if calls[0] == k:
            os.kill(os.getpid(), signal.SIGKILL)
        real(a, b)
atomic.os = Os()
write_outputs(result, OutputPaths.in_folder(folder), request=run_request("sift", None, options, False))
print(calls[0])
"""


def _state(folder):
    """{name: sha256} of the folder's files (not the lock), and its manifest's run id."""
    names = sorted(n for n in os.listdir(folder) if n != ".hamta.lock")
    files = {n: hashlib.sha256(open(os.path.join(folder, n), "rb").read()).hexdigest()
             for n in names if os.path.isfile(os.path.join(folder, n))}
    return files, json.load(open(os.path.join(folder, MANIFEST)))["run_id"]


@pytest.fixture(scope="module")
def results(tmp_path_factory, small_pair):
    """Two SIFT results of the small pair (different seeds, so different files) with their options, each
    also pickled for the process that is killed."""
    from hamta.core import RegisterOptions

    folder = tmp_path_factory.mktemp("results")
    out = []
    for seed in (1, 2):
        options = RegisterOptions(seed=seed)
        result = register(small_pair["target"], small_pair["reference"], "sift", options=options)
        path = folder / f"result{seed}.pkl"
        pickle.dump((result, options), open(path, "wb"))
        out.append((result, options, str(path)))
    return out


@pytest.mark.processes
def test_sigkill_at_every_step_of_publishing_leaves_the_old_set_or_the_new_one(tmp_path, results, small_pair):
    (old, old_options, _), (new, new_options, new_pickle) = results
    steps = None
    k = 1
    while steps is None or k <= steps:
        folder = tmp_path / f"k{k}"
        write_outputs(old, OutputPaths.in_folder(str(folder)), request=run_request("sift", None, old_options, False))
        before = _state(folder)
        proc = subprocess.run([sys.executable, "-c", KILLER, new_pickle, str(folder), str(k)], capture_output=True,
                              text=True)
        if proc.returncode == 0:  # fewer renames than k: this is the last step
            steps = int(proc.stdout.split()[-1])
            break
        assert proc.returncode == -signal.SIGKILL, proc.stderr
        remove_leftovers(str(folder))  # what the next run or a batch resuming this folder does first
        after = _state(folder)
        assert not os.path.exists(folder / JOURNAL)
        assert not any(n.startswith(STAGING_PREFIX) for n in os.listdir(folder))
        if after[1] == before[1]:
            assert after == before, f"killed at rename {k}: the old set changed"
        else:
            manifest = json.load(open(folder / MANIFEST))
            assert set(after[0]) == set(manifest["files"]) | {MANIFEST}, f"killed at rename {k}: mixed set"
            assert all(os.path.getsize(folder / n) == s for n, s in manifest["files"].items())
            assert json.load(open(folder / "report.json"))["run_id"] == after[1]
        job = Job(target=os.path.abspath(small_pair["target"]),
                  reference=RasterReference(os.path.abspath(small_pair["reference"])), out=str(folder))
        holds_old = after[1] == before[1]
        for options, expected in ((old_options, holds_old), (new_options, not holds_old)):
            record = finished_record(job, BatchSettings(method="sift", options=options))
            assert (record is not None) == expected, f"killed at rename {k}: resume disagrees with the folder"
            if record is not None:
                assert all(os.path.isfile(p) for p in record["outputs"].values())
        k += 1
    assert steps and steps >= 6 and k == steps + 1, (steps, k)


def test_every_file_reaches_the_disk_before_the_set_is_committed(tmp_path, results, monkeypatch):
    import hamta.core.outputs.atomic as atomic

    (result, options, _), _ = results
    events, sync, commit = [], atomic._sync, atomic._write_durably
    monkeypatch.setattr(atomic, "_sync", lambda path: (events.append(os.path.basename(path)), sync(path)))
    monkeypatch.setattr(atomic, "_write_durably", lambda path, journal: (events.append(journal), commit(path, journal)))
    write_outputs(result, OutputPaths.in_folder(str(tmp_path / "out")), request=run_request("sift", None, options,
                                                                                            False))
    journals = [e for e in events if isinstance(e, dict)]
    assert len(journals) == 1
    flushed = events[:events.index(journals[0])]
    assert set(journals[0]["files"]) | {MANIFEST} <= set(flushed) and flushed[-1].startswith(STAGING_PREFIX)


@pytest.mark.parametrize("err", [errno.EIO, errno.ENOSPC, errno.EINVAL])
def test_a_file_that_cannot_reach_the_disk_publishes_nothing(tmp_path, results, monkeypatch, err):
    """A disk error surfacing at fsync (delayed allocation on a full disk) leaves the folder as it was; a file
    system without fsync (EINVAL) publishes as usual."""
    from hamta.core.errors import OutputError

    (result, options, _), _ = results

    def fsync(fd):
        raise OSError(err, os.strerror(err))

    monkeypatch.setattr(os, "fsync", fsync)
    out = tmp_path / "out"
    paths, request = OutputPaths.in_folder(str(out)), run_request("sift", None, options, False)
    if err == errno.EINVAL:
        write_outputs(result, paths, request=request)
        assert (out / "registered.tif").is_file() and (out / MANIFEST).is_file()
        return
    with pytest.raises(OutputError, match="to the disk"):
        write_outputs(result, paths, request=request)
    assert not out.exists() or os.listdir(out) == []


def test_a_publication_that_fails_at_its_last_step_leaves_the_old_set_and_its_manifest(tmp_path, results,
                                                                                    monkeypatch):
    """A disk error while the journal is removed, the last step of publishing: the run rolls back to exactly
    the old files and the old manifest (which a batch resume reads)."""
    import hamta.core.outputs.atomic as atomic
    from hamta.core.errors import OutputError

    (old, old_options, _), (new, new_options, _) = results
    folder = tmp_path / "out"
    write_outputs(old, OutputPaths.in_folder(str(folder)), request=run_request("sift", None, old_options, False))
    before = _state(folder)
    failed = []

    class Os:
        def __getattr__(self, name):
            return getattr(os, name)

        def remove(self, path):
            if path.endswith(JOURNAL) and not failed:
                failed.append(path)
                raise OSError(28, "No space left on device")
            os.remove(path)

    monkeypatch.setattr(atomic, "os", Os())
    with pytest.raises(OutputError, match="left as it was"):
        write_outputs(new, OutputPaths.in_folder(str(folder)), request=run_request("sift", None, new_options, False))
    assert failed and _state(folder) == before


def _register(small_pair, out, *extra):
    return ["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out", str(out),
            "--method", "sift", "--quiet", *extra]


def test_files_hamta_did_not_write_are_never_replaced_or_removed_without_overwrite(tmp_path, small_pair, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "gcps.vrt").write_text("mine")
    (out / "report.json").write_text("mine too")
    assert main(_register(small_pair, out)) == 1
    err = capsys.readouterr().err
    assert "holds report.json, which Hamta did not write" in err and "(--overwrite)" in err, err
    assert sorted(os.listdir(out)) == ["gcps.vrt", "report.json"] and (out / "report.json").read_text() == "mine too"
    assert main(_register(small_pair, out, "--overwrite")) == 0  # replaces report.json, leaves gcps.vrt alone
    assert (out / "gcps.vrt").read_text() == "mine" and json.load(open(out / "report.json"))["method"] == "sift"
    assert main(_register(small_pair, out)) == 0  # a rerun replaces its own set, still not the user's file
    assert (out / "gcps.vrt").read_text() == "mine"
    assert main(_register(small_pair, out, "--vrt")) == 1  # writing gcps.vrt would replace the user's


def test_a_batch_row_into_a_folder_of_the_users_files_fails_that_row_only(tmp_path, small_pair):
    from hamta.core.batch import run_batch

    out = tmp_path / "pair"
    out.mkdir()
    (out / "registered.tif").write_bytes(b"mine")
    job = Job(target=os.path.abspath(small_pair["target"]),
              reference=RasterReference(os.path.abspath(small_pair["reference"])), out=str(out))
    record = run_batch([job], BatchSettings(method="sift"), workers=1, processes=False).records[0]
    assert record["status"] == "failed" and "did not write" in record["message"]
    assert (out / "registered.tif").read_bytes() == b"mine"


def test_batch_resume_runs_a_pair_again_when_the_request_changed(tmp_path, small_pair):
    from hamta.core import RegisterOptions

    job = Job(target=os.path.abspath(small_pair["target"]),
              reference=RasterReference(os.path.abspath(small_pair["reference"])), out=str(tmp_path / "pair"))
    first = BatchSettings(method="sift")
    from hamta.core.batch.task import register_job

    assert register_job(job, first)["status"] == "verified"
    assert finished_record(job, first)["resumed"]
    assert finished_record(job, BatchSettings(method="auto")) is None
    assert finished_record(job, BatchSettings(method="sift", options=RegisterOptions(model="projective"))) is None
    assert finished_record(job, BatchSettings(method="sift", accept_unverified=True)) is None
    os.remove(tmp_path / "pair" / "registered.tif")
    assert finished_record(job, first) is None  # the set is no longer whole


@pytest.mark.processes
@pytest.mark.parametrize("redirect,code", [(">&-", 0), (">/dev/full", 0), ("2>&-", 0), ("| head -c 10", 3)])
def test_exit_codes_do_not_depend_on_the_standard_streams(tmp_path, small_pair, redirect, code):
    tolerance = "0.001" if code == 3 else "3"
    cmd = " ".join([sys.executable, "-m", "hamta.cli.main", *_register(small_pair, tmp_path / "out"), "--tolerance",
                    tolerance, redirect])
    proc = subprocess.run(["bash", "-o", "pipefail", "-c", cmd], capture_output=True, text=True)
    assert proc.returncode == code, proc.stderr
    if code == 0:
        assert "registered.tif" in os.listdir(tmp_path / "out")
