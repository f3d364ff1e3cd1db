"""Reading many windows (the refinement's and the check's sites) and what a run keeps of its files."""
import os
import time

import cv2
import numpy as np
import pytest
from affine import Affine
from rasterio.windows import Window

from hamta.core.io import scope
from hamta.core.io.raster import open_raster, read_image, resolve_bands
from hamta.core.io.windows import WindowReader, read_whole
from hamta.core.parallel import threaded


def _windows(info, n=150, seed=0):
    """Windows of every kind: inside, across an edge or a corner, wholly outside."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        w, h = (int(v) for v in rng.integers(3, 90, 2))
        c, r = int(rng.integers(-60, info.width + 10)), int(rng.integers(-60, info.height + 10))
        out.append(Window(c, r, w, h))
    return out


def _collared(size=240):
    """An RGB scene turned inside a zero collar, no nodata declared (read as a collar)."""
    rng = np.random.default_rng(4)
    img = cv2.GaussianBlur(rng.uniform(20, 230, (size, size, 3)).astype(np.float32), (0, 0), 2)
    mask = np.zeros((size, size), np.uint8)
    box = cv2.boxPoints(((size / 2, size / 2), (0.7 * size, 0.6 * size), 25.0)).astype(np.int32)
    cv2.fillPoly(mask, [box], 1)
    return np.where(mask[..., None] > 0, np.clip(img, 1, 254), 0).astype(np.uint8).transpose(2, 0, 1)


@pytest.mark.parametrize("kind", ["rgb-collar", "grey-nodata", "float-nan"])
def test_held_windows_are_the_windows_gdal_reads(raster_writer, kind):
    """A small raster is read once and its windows cut from memory: the same pixels and validity as
    reading each window through GDAL, collar, nodata, NaN and the parts outside included."""
    rng = np.random.default_rng(1)
    if kind == "rgb-collar":
        path = raster_writer("rgb.tif", _collared())
    elif kind == "grey-nodata":
        data = rng.integers(0, 200, (150, 170)).astype("uint16")
        data[40:60, 30:90] = 7
        path = raster_writer("g.tif", data, nodata=7)
    else:
        data = rng.normal(size=(130, 110)).astype("float32")
        data[10:30, 50:70] = np.nan
        path = raster_writer("f.tif", data)
    info = open_raster(path)
    assert (info.collar is not None) == (kind == "rgb-collar")
    bands = resolve_bands(info, None)
    with WindowReader(info, bands) as held, WindowReader(info, bands, hold_pixels=0) as direct:
        for window in _windows(info):
            a, b = held.read(window), direct.read(window)
            assert np.array_equal(a[1], b[1]), window
            # RGB luminance is a weighted sum through BLAS, whose kernels order it by the array's shape (an
            # AVX-512 kernel and an older one differ in the last float32 place): the same pixels agree to
            # within a few units of float32 rounding at 255 (3e-5 each), not bit for bit.
            np.testing.assert_allclose(a[0], b[0], rtol=0, atol=1e-4, err_msg=str(window))


def test_a_run_describes_each_file_once_and_reads_it_through_one_dataset(raster_writer, monkeypatch):
    data = np.random.default_rng(2).integers(0, 255, (80, 90)).astype("uint8")
    path = raster_writer("a.tif", data, crs="EPSG:32633", transform=Affine(10, 0, 500000, 0, -10, 4000000))
    opened = []
    real = scope.rasterio.open
    monkeypatch.setattr(scope.rasterio, "open", lambda p, *a, **k: opened.append(p) or real(p, *a, **k))
    with scope.run_scope() as files:
        first = open_raster(path, "target")
        assert open_raster(path, "reference") is first
        for _ in range(3):
            image, valid = read_image(first, (1,), window=Window(5, 5, 20, 20))
        assert np.array_equal(image, data[5:25, 5:25].astype(np.float32))
        assert threaded(lambda _: scope.current(), range(2)) == [files, files]  # threads share the run's files
        with scope.run_scope() as inner:
            assert inner is files
        scope.release_datasets()
        read_image(first, (1,), window=Window(0, 0, 4, 4))  # opened again after a release
    assert opened == [path, path]
    assert scope.current() is None and open_raster(path) is not first  # nothing kept outside a run


def test_a_run_reads_a_small_raster_whole_once_for_all_its_window_readers(raster_writer, monkeypatch):
    """The refinement and the check (of every attempt) cut their windows from one whole read per run; the
    held arrays cannot be changed by a reader, and nothing is held after the run."""
    import hamta.core.io.windows as windows

    data = np.random.default_rng(3).integers(0, 255, (3, 70, 90)).astype("uint8")
    path = raster_writer("rgb.tif", data)
    reads = []
    real = windows.read_image
    monkeypatch.setattr(windows, "read_image", lambda *a, **k: reads.append(a[0].path) or real(*a, **k))
    with scope.run_scope():
        info = open_raster(path)
        bands = resolve_bands(info, None)
        first = []
        for _ in range(3):
            with WindowReader(info, bands) as reader:
                first.append(reader.read(Window(-5, 10, 30, 20)))
                assert not reader._held[0].flags.writeable
        with WindowReader(info, (1,)) as one_band:  # other bands: another read
            one_band.read(Window(0, 0, 8, 8))
    assert reads == [path, path]
    assert all(np.array_equal(a, b) for got in first[1:] for a, b in zip(got, first[0]))
    with WindowReader(open_raster(path), bands):
        pass
    assert reads == [path, path, path]


@pytest.mark.parametrize("kind", ["grey", "rgb-collar"])
def test_the_report_s_whole_read_is_the_window_readers_one(raster_writer, monkeypatch, kind):
    """A run that held a small raster for its windows gives the report's preview the same read, collar masked
    as :func:`read_image` masks it; outside a run, the raster is read."""
    import hamta.core.io.windows as windows

    data = _collared() if kind == "rgb-collar" else np.random.default_rng(4).integers(0, 255, (60, 80)).astype("uint8")
    path = raster_writer("x.tif", data)
    reads = []
    real = windows.read_image
    monkeypatch.setattr(windows, "read_image", lambda *a, **k: reads.append(a[0].path) or real(*a, **k))
    info = open_raster(path)
    assert (info.collar_fill is not None) == (kind == "rgb-collar")
    bands = resolve_bands(info, None)
    expected = read_image(info, bands)
    with scope.run_scope():
        with WindowReader(open_raster(path), bands):
            pass
        got = read_whole(open_raster(path), bands)
    assert reads == [path]
    assert all(np.array_equal(a, b) and a.dtype == b.dtype for a, b in zip(got, expected))
    assert all(np.array_equal(a, b) for a, b in zip(read_whole(info, bands), expected))
    assert reads == [path, path]


def test_a_file_changed_during_a_run_is_described_again(raster_writer):
    path = raster_writer("b.tif", np.full((40, 40), 5, np.uint8))
    with scope.run_scope():
        before = open_raster(path)
        time.sleep(0.01)
        raster_writer("b.tif", np.full((50, 60), 5, np.uint8))
        os.utime(path)
        after = open_raster(path)
    assert (before.width, after.width) == (40, 60)


def test_threads_give_results_and_errors_in_the_order_of_the_items():
    def work(i):
        time.sleep(0.02 * (4 - i))  # later items finish first
        if i in (1, 3):
            raise ValueError(f"item {i}")
        return i * i

    assert threaded(lambda i: i * i, range(6)) == [0, 1, 4, 9, 16, 25]
    with pytest.raises(ValueError, match="item 1"):
        threaded(work, range(4))
