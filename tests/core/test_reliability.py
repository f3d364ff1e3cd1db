"""The bad-input matrix: every case through the CLI, with its exit code, its message, no partial or
mixed output set and byte-identical inputs. One table row per case; README lists the exit codes."""
import errno
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest
import rasterio

from hamta.cli.main import main

OUT_SET = {"registered.tif", "gcps.points", "gcps.gpkg", "report.json", "report.html"}


def _hashes(*paths):
    return {p: hashlib.sha256(open(p, "rb").read()).hexdigest() for p in paths if os.path.isfile(p)}


def _write(path, data, **profile):
    data = np.asarray(data)
    data = data[None] if data.ndim == 2 else data
    prof = dict(driver="GTiff", width=data.shape[2], height=data.shape[1], count=data.shape[0], dtype=data.dtype.name)
    prof.update(profile)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with rasterio.open(path, "w", **prof) as dst:
            dst.write(data)
    return str(path)


@pytest.fixture(scope="module")
def pair(tmp_path_factory, small_pair):
    """A private copy of the small pair (inputs hashed before and after every case)."""
    folder = tmp_path_factory.mktemp("inputs")
    return {k: shutil.copy(small_pair[k], folder / os.path.basename(small_pair[k])) for k in ("target", "reference")}


def _register(pair, out, *extra, target=None, reference=None):
    return ["register", "--reference", str(reference or pair["reference"]), "--target", str(target or pair["target"]),
            "--out", str(out), "--quiet", *extra]


def _bad_target(kind, folder, pair):
    """A broken target of ``kind``: returns its path."""
    path = folder / f"{kind}.tif"
    if kind == "missing":
        return folder / "nope.tif"
    if kind == "folder":
        path.mkdir()
    elif kind == "empty-file":
        path.write_bytes(b"")
    elif kind == "text-file":
        path.write_text("not a raster\n")
    elif kind == "truncated":
        data = open(pair["target"], "rb").read()
        path.write_bytes(data[: len(data) * 6 // 10])
    elif kind == "self-vrt":
        path = folder / "self.vrt"
        path.write_text(f'<VRTDataset rasterXSize="64" rasterYSize="64"><VRTRasterBand dataType="Byte" band="1">'
                        f'<SimpleSource><SourceFilename relativeToVRT="0">{path}</SourceFilename>'
                        '<SourceBand>1</SourceBand></SimpleSource></VRTRasterBand></VRTDataset>')
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "constant":
        _write(path, np.full((200, 200), 9, np.uint8))
    elif kind == "all-nodata":
        _write(path, np.zeros((200, 200), np.uint8), nodata=0)
    elif kind == "too-small":
        _write(path, np.random.default_rng(0).integers(1, 255, (12, 600), dtype=np.uint8))
    return path


# case -> (exit code, message pattern)
INPUT_CASES = {
    "missing": (1, "does not exist"),
    "folder": (1, "is a folder"),
    "empty-file": (1, "not a raster GDAL can read"),
    "text-file": (1, "not a raster GDAL can read"),
    "truncated": (1, "truncated or corrupt"),
    "self-vrt": (1, "not a raster GDAL can read|could not be read"),
    "constant": (1, "is constant"),
    "all-nodata": (1, "no valid pixels"),
    "too-small": (1, "too small to register"),
    "fifo": (1, "not a regular file"),
}


@pytest.mark.parametrize("kind", sorted(INPUT_CASES))
def test_bad_inputs_exit_with_a_message_and_leave_nothing(kind, tmp_path, pair, capsys):
    before = _hashes(*pair.values())
    target = _bad_target(kind, tmp_path, pair)
    out = tmp_path / "out"
    code, pattern = INPUT_CASES[kind]
    rc = main(_register(pair, out, target=target))
    err = capsys.readouterr().err
    assert rc == code, err
    assert "Traceback" not in err and str(target) in err and __import__("re").search(pattern, err), err
    assert not out.exists()  # checked before any output folder is made
    assert _hashes(*pair.values()) == before


# CLI arguments -> (exit code, message pattern); usage errors are 2.
PARAMETER_CASES = {
    "nan-rotation": (["--method", "cfog", "--param", "max_rotation_deg=nan"], 2, "max_rotation_deg must be a finite"),
    "nan-ratio": (["--method", "sift", "--param", "ratio=nan"], 2, "ratio must be a finite"),
    "text-number": (["--method", "sift", "--param", "n_features=many"], 2, "parameter n_features expects a number"),
    "fraction-for-whole": (["--method", "sift", "--param", "n_features=12.5"], 2, "n_features expects a whole"),
    "unknown-param": (["--method", "sift", "--param", "colour=red"], 2, "has no parameter"),
    "auto-with-param": (["--param", "ratio=0.7"], 2, "takes no method parameters"),
    "nan-threshold": (["--ransac-threshold", "nan"], 2, "--ransac-threshold must be a finite"),
    "inf-threshold": (["--ransac-threshold", "inf"], 2, "--ransac-threshold must be a finite"),
    "negative-seed": (["--seed", "-1"], 2, "seed must be a whole number of at least 0"),
    "zero-gcps": (["--max-gcps", "0"], 2, "--max-gcps must be a whole number of at least 3"),
    "nan-tolerance": (["--tolerance", "nan"], 2, "--tolerance must be a finite"),
    "unknown-method": (["--method", "magic"], 2, "unknown method 'magic'"),
    "unknown-model": (["--model", "wobbly"], 2, "unknown model 'wobbly'"),
}


@pytest.mark.parametrize("case", sorted(PARAMETER_CASES))
def test_bad_parameters_are_usage_errors_named_before_any_work(case, tmp_path, pair, capsys):
    extra, code, pattern = PARAMETER_CASES[case]
    t0 = time.perf_counter()
    rc = main(_register(pair, tmp_path / "out", *extra))
    err = capsys.readouterr().err
    assert rc == code and pattern in err and "Traceback" not in err, err
    assert not (tmp_path / "out").exists() and time.perf_counter() - t0 < 30


def test_a_whole_number_written_as_a_float_is_accepted(tmp_path, pair):
    assert main(_register(pair, tmp_path / "o", "--method", "sift", "--param", "n_features=4e3")) == 0


@pytest.mark.parametrize("where", ["registered.tif", "gcps.vrt"])
def test_an_output_that_is_an_input_is_refused_and_the_input_kept(where, tmp_path, pair, capsys):
    out = tmp_path / "out"
    out.mkdir()
    copy = shutil.copy if where.endswith(".tif") else _vrt_over
    target = copy(pair["target"], out / where)
    before = _hashes(target, pair["target"])
    rc = main(_register(pair, out, "--vrt", target=target))
    err = capsys.readouterr().err
    assert rc == 1 and "is one of the input files" in err, err
    assert _hashes(target, pair["target"]) == before and sorted(os.listdir(out)) == [where]


def _vrt_over(source, path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rasterio.shutil.copy(source, path, driver="VRT")
    return str(path)


def test_a_rerun_replaces_the_set_whole(tmp_path, pair):
    out = tmp_path / "out"
    assert main(_register(pair, out, "--vrt")) == 0
    assert set(os.listdir(out)) >= OUT_SET | {"gcps.vrt"}
    assert main(_register(pair, out)) == 0  # without --vrt: the old gcps.vrt is not left behind
    files = {f for f in os.listdir(out) if not f.startswith(".")}
    assert files == OUT_SET
    _assert_one_set(out)


def _assert_one_set(out):
    """Every published file belongs to the run the manifest names."""
    manifest = json.loads((out / ".hamta-manifest.json").read_text())
    run = manifest["run_id"]
    assert json.loads((out / "report.json").read_text())["run_id"] == run
    with rasterio.open(out / "registered.tif") as ds:
        assert ds.tags()["HAMTA_RUN_ID"] == run
    assert run.encode() in (out / "gcps.gpkg").read_bytes()
    for name, size in manifest["files"].items():
        assert os.path.getsize(out / name) == size
    assert not [f for f in os.listdir(out) if f.startswith(".hamta-staging-")]


def test_a_path_too_long_fails_before_the_work(tmp_path, pair, capsys):
    out = tmp_path / ("x" * 250) / ("y" * 250)
    t0 = time.perf_counter()
    rc = main(_register(pair, out))
    assert rc == 1 and "too long" in capsys.readouterr().err
    assert time.perf_counter() - t0 < 10


def test_an_unwritable_folder_fails_clearly(tmp_path, pair, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    rc = main(_register(pair, blocker / "out"))
    assert rc == 1 and "Cannot create the output folder" in capsys.readouterr().err


def test_a_full_disk_publishes_nothing(tmp_path, pair, capsys, monkeypatch):
    import hamta.core.outputs as outputs

    def full(path, result):
        raise OSError(errno.ENOSPC, "No space left on device")

    out = tmp_path / "out"
    assert main(_register(pair, out)) == 0
    before = _hashes(*(out / f for f in OUT_SET))
    monkeypatch.setattr(outputs, "write_points", full)
    rc = main(_register(pair, out))
    assert rc == 1 and "the disk is full" in capsys.readouterr().err
    assert _hashes(*(out / f for f in OUT_SET)) == before  # the previous set is untouched
    _assert_one_set(out)


def test_a_vrt_mosaic_target_is_warped_from_all_its_tiles(tmp_path, pair):
    """The VRT carrying the model keeps each source of the target: two tiles, each its own half."""
    with rasterio.open(pair["target"]) as ds:
        data = ds.read()
    h, w = data.shape[1:]
    left = _write(tmp_path / "left.tif", data[:, :, : w // 2])
    right = _write(tmp_path / "right.tif", data[:, :, w // 2:])
    stack = tmp_path / "stack.vrt"
    bands = "".join(
        f'<VRTRasterBand dataType="Byte" band="{b}">' + "".join(
            f'<SimpleSource><SourceFilename relativeToVRT="1">{os.path.basename(f)}</SourceFilename>'
            f'<SourceBand>{b}</SourceBand><SrcRect xOff="0" yOff="0" xSize="{cw}" ySize="{h}"/>'
            f'<DstRect xOff="{x0}" yOff="0" xSize="{cw}" ySize="{h}"/></SimpleSource>'
            for f, x0, cw in ((left, 0, w // 2), (right, w // 2, w - w // 2)))
        + "</VRTRasterBand>" for b in (1, 2, 3))
    stack.write_text(f'<VRTDataset rasterXSize="{w}" rasterYSize="{h}">{bands}</VRTDataset>')
    out_vrt, out_tif = tmp_path / "via-vrt", tmp_path / "via-tif"
    assert main(_register(pair, out_vrt, "--method", "sift", target=stack)) == 0
    assert main(_register(pair, out_tif, "--method", "sift", target=_write(tmp_path / "whole.tif", data))) == 0
    with rasterio.open(out_vrt / "registered.tif") as a, rasterio.open(out_tif / "registered.tif") as b:
        x, y = _sampled_alike(a, b)
    both = (x > 0) & (y > 0)
    assert (x > 0).mean() > 0.95 * (y > 0).mean()  # both halves
    assert both.mean() > 0.3 and np.abs(x - y)[both].mean() < 2.0  # the same picture
    assert np.abs(x[0] - x[1])[both[0]].mean() > 1.0  # three distinct bands, not three copies of band 1


def _sampled_alike(a, b, n=80):
    """Both rasters' bands at the same n x n map points of their common extent (their grids differ where their
    models do)."""
    left, right = max(a.bounds.left, b.bounds.left), min(a.bounds.right, b.bounds.right)
    bottom, top = max(a.bounds.bottom, b.bounds.bottom), min(a.bounds.top, b.bounds.top)
    assert right > left and top > bottom
    mx, my = np.meshgrid(np.linspace(left, right, n + 2)[1:-1], np.linspace(bottom, top, n + 2)[1:-1])
    out = []
    for ds in (a, b):
        rows, cols = rasterio.transform.rowcol(ds.transform, mx.ravel(), my.ravel())
        out.append(ds.read().astype(float)[:, np.asarray(rows), np.asarray(cols)])
    return out


def test_broken_pipe_exits_quietly():
    proc = subprocess.Popen([sys.executable, "-m", "hamta.cli.main", "methods"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    proc.stdout.read(20)
    proc.stdout.close()
    assert proc.wait(timeout=120) == 0 and proc.stderr.read() == b""


@pytest.mark.processes
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_interrupt_exits_130_and_leaves_no_staging(sig, tmp_path, pair):
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "hamta.cli.main", *_register(pair, out, "--method", "cfog",
                                                                                 "--param", "max_rotation_deg=180")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    time.sleep(4)
    proc.send_signal(sig)
    assert proc.wait(timeout=120) == 130
    err = proc.stderr.read().decode()
    assert "Traceback" not in err and "interrupted" in err
    assert not out.exists() or not [f for f in os.listdir(out) if not f.startswith(".hamta")]


def test_leftovers_of_a_killed_run_are_removed_by_the_next(tmp_path, pair):
    out = tmp_path / "out"
    out.mkdir()
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    zombie = subprocess.Popen([sys.executable, "-c", "pass"])
    os.waitid(os.P_PID, zombie.pid, os.WEXITED | os.WNOWAIT)  # ended, not yet reaped: a zombie
    leftovers = [out / f".hamta-staging-{dead.pid}-deadbeef", out / f".hamta-staging-{zombie.pid}-deadbeef"]
    old_foreign, new_foreign = (out / f".hamta-staging-{os.getpid()}-cafe-{h}" for h in ("0badc0de", "1badc0de"))
    for folder in leftovers + [old_foreign, new_foreign]:
        folder.mkdir()
        (folder / "registered.tif").write_bytes(b"half")
    os.utime(old_foreign, (time.time() - 2 * 86400,) * 2)
    assert main(_register(pair, out)) == 0
    zombie.wait()
    assert not any(f.exists() for f in leftovers + [old_foreign])
    assert new_foreign.exists()  # another host's run may still be writing: kept until a day old
    shutil.rmtree(new_foreign)
    _assert_one_set(out)


@pytest.mark.processes
def test_concurrent_runs_into_one_folder_never_mix(tmp_path, pair):
    out = tmp_path / "out"
    procs = [subprocess.Popen([sys.executable, "-m", "hamta.cli.main", *_register(pair, out, "--method", "sift",
                                                                                  "--seed", str(k))],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for k in range(3)]
    assert [p.wait(timeout=600) for p in procs] == [0, 0, 0]
    _assert_one_set(out)


# map-points: the report and the coordinates
MAP_CASES = {
    "missing": (None, 1, "does not exist"),
    "folder": ("folder", 1, "is a folder"),
    "not-json": ("not json", 1, "not readable JSON"),
    "not-object": ([1, 2], 1, "not a Hamta report"),
    "no-model": ({"reference": {"transform": [0, 1, 0, 0, 0, -1]}}, 1, "not a Hamta report"),
    "bad-matrix": ({"model": {"type": "affine", "target_px_to_reference_px": [[1, 0, 0], [0, 1, 0]]},
                    "reference": {"transform": [0, 1, 0, 0, 0, -1]}}, 1, "not a Hamta report|cannot be evaluated"),
    "zero-matrix": ({"model": {"type": "affine", "target_px_to_reference_px": [[0] * 3] * 3},
                     "reference": {"transform": [0, 1, 0, 0, 0, -1]}}, 1, "finite coordinates|cannot be evaluated"),
    "nan-matrix": ({"model": {"type": "affine", "target_px_to_reference_px": [[float("nan")] * 3] * 3},
                    "reference": {"transform": [0, 1, 0, 0, 0, -1]}}, 1, "finite coordinates|cannot be evaluated"),
    "deeply-nested": ("[" * 100000 + "]" * 100000, 1, "not readable JSON|not a Hamta report"),
    "bad-crs": ({"model": {"type": "affine", "frame": "target_crs", "frame_crs": "EPSG:nope",
                           "frame_transform": [0, 1, 0, 0, 0, -1], "target_px_to_frame_px": np.eye(3).tolist()},
                 "reference": {"transform": [0, 1, 0, 0, 0, -1], "crs": "EPSG:32639"}}, 1, "report"),
}


@pytest.mark.parametrize("case", sorted(MAP_CASES))
def test_map_points_names_the_report_and_the_problem(case, tmp_path, capsys):
    content, code, pattern = MAP_CASES[case]
    path = tmp_path / "report.json"
    if content == "folder":
        path.mkdir()
    elif isinstance(content, str):
        path.write_text(content)
    elif content is not None:
        path.write_text(json.dumps(content))
    rc = main(["map-points", str(path), "1", "2"])
    err = capsys.readouterr().err
    assert rc == code and str(path) in err and __import__("re").search(pattern, err) and "Traceback" not in err, err


def test_map_points_with_a_huge_spline_stays_within_memory(monkeypatch):
    from hamta.core.estimation import tps as spline

    n = 200_000
    rng = np.random.default_rng(0)
    tps = spline.ThinPlateSplineModel(rng.uniform(0, 1e4, (n, 2)), np.zeros(2), 1e4, rng.normal(0, 1e-6, (n, 2)),
                                      np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]))
    widest = []
    real = spline._tps_kernel
    monkeypatch.setattr(spline, "_tps_kernel", lambda r2: widest.append(r2.size) or real(r2))
    out = tps.apply(rng.uniform(0, 1e4, (50, 2)))
    assert out.shape == (50, 2) and np.isfinite(out).all() and max(widest) <= 250_000


def test_an_interrupt_during_publishing_waits_for_the_set_to_be_whole():
    from hamta.core.outputs.atomic import signals_deferred

    steps = []
    with pytest.raises(KeyboardInterrupt):
        with signals_deferred():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)
            steps.append("published")
    assert steps == ["published"]


STRIPS = [("sibrif", (25, 586), "found only"), ("sibrif", (12, 600), "too small"), ("orb", (1, 100000), "too small"),
          ("rilbp", (30, 600), "found only")]


@pytest.mark.parametrize("method,shape,pattern", STRIPS)
def test_thin_strips_end_with_a_message(method, shape, pattern, tmp_path, pair, capsys):
    strip = _write(tmp_path / "strip.tif", np.random.default_rng(0).integers(0, 255, shape, dtype=np.uint8))
    rc = main(_register(pair, tmp_path / "out", "--method", method, target=strip))
    err = capsys.readouterr().err
    assert rc == 1 and pattern in err and strip in err and "Traceback" not in err, err


def test_a_complex_int16_target_is_registered_and_warped(tmp_path, pair, capsys):
    with rasterio.open(pair["target"]) as ds:
        amplitude = ds.read(1).astype(np.complex64)
    target = _write(tmp_path / "cint16.tif", amplitude, dtype="complex_int16")
    rc = main(_register(pair, tmp_path / "out", "--method", "sift", target=target))
    assert rc == 0, capsys.readouterr().err
    with rasterio.open(tmp_path / "out" / "registered.tif") as ds:
        assert ds.dtypes[0] == "complex_int16" and ds.crs is not None


def test_a_reference_georeferenced_beyond_the_pole_is_refused(tmp_path, pair, capsys):
    from affine import Affine

    with rasterio.open(pair["reference"]) as ds:
        data = ds.read()
    reference = _write(tmp_path / "pole.tif", data, crs="EPSG:4326", transform=Affine(0.01, 0, 10, 0, -0.01, 95))
    rc = main(_register(pair, tmp_path / "out", reference=reference))
    err = capsys.readouterr().err
    assert rc == 1 and "pole.tif' is georeferenced beyond the pole" in err and not (tmp_path / "out").exists()


@pytest.mark.parametrize("where", ["target", "report"])
def test_very_long_input_paths_are_named_not_crashed_on(where, tmp_path, pair, capsys):
    long = str(tmp_path / ("x" * 300)) + ("/" + "y" * 200) * 25
    args = (["map-points", long + ".json", "1", "2"] if where == "report"
            else _register(pair, tmp_path / "out", target=long + ".tif"))
    rc = main(args)
    err = capsys.readouterr().err
    assert rc == 1 and "does not exist" in err and "internal error" not in err


# hamta batch: (job list rows as "{target},{reference},output" templates, or None for the target as a pattern with
# --reference; extra arguments) -> (exit code, message pattern); each is refused before any work.
BATCH_CASES = {
    "zero-workers": (None, ["--workers", "0"], 2, "--workers must be at least 1"),
    "negative-workers": (None, ["--workers", "-2"], 2, "--workers must be at least 1"),
    "unreachable-tcp": (None, ["--scheduler", "tcp://127.0.0.1:1"], 1, "tcp://127.0.0.1:1 did not accept a connection"),
    "unreachable-tls": (None, ["--scheduler", "tls://127.0.0.1:1"], 1, "tls://127.0.0.1:1 needs TLS credentials"),
    "extra-fields": (["{target},{reference},out,surplus"], [], 1,
                     r"Row 1 \(line 2\) of the job list '{jobs}' has 4 fields, more than the 3 columns"),
    "output-escapes": (["{target},{reference},../../escape"], [], 1,
                       "Row 1 of the job list '{jobs}': the output '../../escape' is not a folder inside"),
    "output-absolute": (["{target},{reference},{outside}"], [], 1,
                        "Row 1 of the job list '{jobs}': the output '{outside}' is not a folder inside"),
    "same-output": (["{target},{reference},a", "{target},{reference},b/../a"], [], 1,
                    "Rows 1 and 2 of the job list '{jobs}' have the same output folder"),
}


@pytest.mark.parametrize("case", sorted(BATCH_CASES))
def test_bad_batches_are_refused_before_any_work(case, tmp_path, pair, capsys, monkeypatch):
    from hamta.core.batch import runner

    monkeypatch.setattr(runner, "CONNECT_TIMEOUT_S", 1)  # an unreachable scheduler's wait, 5 s by default
    rows, extra, code, pattern = BATCH_CASES[case]
    out, jobs, outside = tmp_path / "out", tmp_path / "jobs.csv", tmp_path / "outside"
    if rows is None:
        source = [str(pair["target"]), "--reference", str(pair["reference"])]
    else:
        jobs.write_text("target,reference,output\n" + "".join(
            row.format(target=pair["target"], reference=pair["reference"], outside=outside) + "\n" for row in rows))
        source = [str(jobs)]
    t0 = time.perf_counter()
    rc = main(["batch", *source, "--out", str(out), "--quiet", *extra])
    err = capsys.readouterr().err
    assert rc == code and "Traceback" not in err and "internal error" not in err, err
    escape = __import__("re").escape
    assert __import__("re").search(pattern.format(jobs=escape(str(jobs)), outside=escape(str(outside))), err), err
    assert not out.exists() and not outside.exists() and time.perf_counter() - t0 < 20
