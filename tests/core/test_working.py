"""Overlap planning, working resolution and the maps from working pixels back to the files."""
import numpy as np
import pytest
import rasterio
from affine import Affine
from rasterio.crs import CRS

import hamta.core.io.working as working
from hamta.bench.cases import reprojected_case, similarity_case
from hamta.core import RegisterOptions, register
from hamta.core.errors import ReferenceNotGeoreferenced
from hamta.core.io.raster import open_raster, resolve_bands
from hamta.core.io.working import prepare_working_images
from hamta.core.outputs import OutputPaths, write_outputs
from hamta.core.outputs.points import read_points


def _prepare(case, **kw):
    t, r = open_raster(case.target), open_raster(case.reference)
    return prepare_working_images(t, r, target_bands=resolve_bands(t, None), reference_bands=resolve_bands(r, None),
                                  **kw)


def test_prior_resamples_the_target_onto_the_reference_grid(tmp_path, landsat):
    case = reprojected_case(str(tmp_path), landsat, dst_crs="EPSG:4326", shift_px=(0.0, 0.0))
    tgt, ref, plan = _prepare(case, max_pixels=4_000_000)
    assert plan.mode == "georeferenced" and tgt.shape == ref.shape
    pts = np.array([[200.5, 150.5], [500.25, 400.75]])  # working px
    # With exact georeferencing the same working pixel shows the same ground in both images.
    assert np.allclose(case.truth(tgt.to_source.forward(pts)), ref.to_source.forward(pts), atol=1e-6)
    assert np.allclose(tgt.to_source.inverse(tgt.to_source.forward(pts)), pts, atol=1e-6)


def test_pixel_budget_bounds_the_working_images(tmp_path, landsat):
    case = similarity_case(str(tmp_path), landsat, angle_deg=5, scale=1.0)
    tgt, ref, plan = _prepare(case, max_pixels=50_000)
    assert plan.mode == "search"
    assert tgt.data.size <= 50_000 * 1.01 and ref.data.size <= 50_000 * 1.01
    assert tgt.source_px_per_working_px > 3


def test_overlap_window_limits_what_is_read(tmp_path, landsat):
    with rasterio.open(landsat) as ds:
        data, prof = ds.read(window=rasterio.windows.Window(300, 250, 200, 200)), ds.profile
        tr = rasterio.windows.transform(rasterio.windows.Window(300, 250, 200, 200), ds.transform)
    crop = str(tmp_path / "crop.tif")
    with rasterio.open(crop, "w", driver="GTiff", width=200, height=200, count=3, dtype="uint8", crs=prof["crs"],
                       transform=tr) as dst:
        dst.write(data)
    t, r = open_raster(crop), open_raster(landsat)
    _, ref, plan = prepare_working_images(t, r, target_bands=(1, 2, 3), reference_bands=(1, 2, 3),
                                          max_pixels=4_000_000)
    w = plan.reference_window
    assert w.width < 500 and w.col_off > 150 and w.row_off > 100  # not the whole 791 x 718 reference
    assert ref.shape == (int(w.height), int(w.width))


def test_pixel_mode_without_reference_georeferencing(tmp_path, landsat):
    with rasterio.open(landsat) as ds:
        data = ds.read()
    plain_ref = str(tmp_path / "plain_ref.tif")
    with rasterio.open(plain_ref, "w", driver="GTiff", width=data.shape[2], height=data.shape[1], count=3,
                       dtype="uint8", photometric="RGB") as dst:
        dst.write(data)
    case = similarity_case(str(tmp_path), plain_ref, angle_deg=-8.0, scale=0.9, shift_px=(4.0, -6.0))
    with pytest.raises(ReferenceNotGeoreferenced, match="has no georeferencing"):
        register(case.target, case.reference, options=RegisterOptions(model="affine"))
    res = register(case.target, case.reference, options=RegisterOptions(model="affine", pixel_mode=True))
    assert res.plan.mode == "pixel" and res.pixel_mode
    assert np.sqrt(np.mean(case.errors(res.model) ** 2)) < 0.5
    g = res.gcps[0]
    assert g.map_xy == pytest.approx(g.reference_px)  # map coordinates are reference pixels
    written = write_outputs(res, OutputPaths.in_folder(str(tmp_path / "out")))
    with rasterio.open(written["raster"]) as ds:
        assert (ds.width, ds.height) == (data.shape[2], data.shape[1]) and ds.crs is None
        assert ds.transform == Affine.identity()
    crs, rows = read_points(written["points"])
    assert crs == "" and rows[0][1] == pytest.approx(-g.reference_px[1])  # QGIS shows plain images at y = -row


@pytest.mark.parametrize("to_src", [Affine(1, 0, 37.3, 0, 1, 55.7), Affine(1.0005, 0, 3.3, 0, 1.0002, 5.7),
                                    Affine(0.7, 0, -20.3, 0, 0.8, 1.0)])
def test_same_crs_resampling_matches_gdal(to_src):
    """Between two north-up grids of one CRS the working target is resampled one axis at a time; it gives what
    GDAL's bilinear warp with NaN nodata and its nearest-neighbour mask give, at every valid pixel and in the
    mask, also where the destination reaches past the source."""
    rng = np.random.default_rng(0)
    y, x = np.mgrid[0:300, 0:400]
    img = (100 + 20 * np.sin(x / 7.0) * np.cos(y / 5.0) + rng.normal(0, 2, (300, 400))).astype(np.float32)
    valid = np.ones(img.shape, bool)
    valid[:40] = False
    valid[100:120, 200:260] = False
    src = Affine(10, 0, 1000, 0, -10, 5000)
    dst = src * to_src
    crs = CRS.from_epsg(32633)
    fast = working._resample_onto(img, valid, src, crs, dst, crs, (280, 390))
    gdal = working._gdal_resample(img, valid, src, crs, dst, crs, (280, 390))
    assert np.array_equal(fast[1], gdal[1]) and gdal[1].sum() > 50_000
    assert np.abs(fast[0] - gdal[0])[gdal[1]].max() < 1e-3


def test_downsampling_between_grids_stays_with_gdal():
    """GDAL widens its bilinear kernel where the source is finer than the destination; a plain bilinear does
    not, so there the resampling is GDAL's own."""
    img = np.random.default_rng(1).normal(0, 1, (200, 200)).astype(np.float32)
    valid = np.ones(img.shape, bool)
    src, crs = Affine(10, 0, 0, 0, -10, 2000), CRS.from_epsg(32633)
    dst = src * Affine.scale(2.0)
    both = [f(img, valid, src, crs, dst, crs, (100, 100)) for f in (working._resample_onto, working._gdal_resample)]
    assert np.array_equal(both[0][0], both[1][0]) and np.array_equal(both[0][1], both[1][1])
