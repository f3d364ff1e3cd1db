import numpy as np
import pytest
from affine import Affine
from rasterio.windows import Window

from hamta.core.errors import InputError
from hamta.core.io.raster import budget_shape, open_raster, read_image, resolve_bands

GEO = dict(crs="EPSG:32633", transform=Affine(10, 0, 500000, 0, -10, 4000000))


@pytest.mark.parametrize("dtype", ["uint8", "uint16", "int16", "float32"])
def test_read_full_resolution_is_exact(raster_writer, dtype):
    data = (np.arange(60 * 80).reshape(60, 80) % 200).astype(dtype)
    info = open_raster(raster_writer(f"a_{dtype}.tif", data, **GEO))
    img, valid = read_image(info, (1,))
    assert img.dtype == np.float32 and valid.all()
    assert np.array_equal(img, data.astype(np.float32))


def test_complex_data_is_read_as_amplitude_also_when_decimated(raster_writer):
    rng = np.random.default_rng(0)
    data = (rng.normal(size=(64, 64)) + 1j * rng.normal(size=(64, 64))).astype(np.complex64)
    info = open_raster(raster_writer("c.tif", data))
    full, _ = read_image(info, (1,))
    assert np.allclose(full, np.abs(data), atol=1e-6)
    small, _ = read_image(info, (1,), out_shape=(16, 16))
    expected = np.abs(data).reshape(16, 4, 16, 4).mean(axis=(1, 3))
    assert np.allclose(small, expected, atol=1e-5)


def test_decimated_read_is_a_block_average_with_corner_alignment(raster_writer):
    data = np.random.default_rng(1).integers(0, 255, (120, 90)).astype("uint8")
    info = open_raster(raster_writer("d.tif", data))
    img, _ = read_image(info, (1,), window=Window(30, 60, 60, 60), out_shape=(20, 20))
    expected = data[60:120, 30:90].reshape(20, 3, 20, 3).mean(axis=(1, 3))
    assert np.allclose(img, expected, atol=0.51)  # GDAL rounds the average to the band type


def test_nodata_and_nan_are_invalid(raster_writer):
    data = np.ones((20, 20), "float32")
    data[:5] = -9999
    data[10, 10] = np.nan
    info = open_raster(raster_writer("n.tif", data, nodata=-9999))
    img, valid = read_image(info, (1,))
    assert not valid[:5].any() and not valid[10, 10] and valid[6:10].all()
    assert (img[~valid] == 0).all()


def test_window_outside_the_raster_reads_as_invalid(raster_writer):
    info = open_raster(raster_writer("w.tif", np.full((10, 10), 7, "uint8")))
    img, valid = read_image(info, (1,), window=Window(-5, -5, 10, 10))
    assert valid[5:, 5:].all() and not valid[:5].any() and not valid[:, :5].any()
    assert (img[5:, 5:] == 7).all()


def test_rgb_becomes_luminance_and_bands_can_be_chosen(raster_writer):
    rgb = np.stack([np.full((8, 8), v, "uint8") for v in (100, 50, 200)])
    info = open_raster(raster_writer("rgb.tif", rgb, photometric="RGB"))
    assert resolve_bands(info, None) == (1, 2, 3)
    img, _ = read_image(info, resolve_bands(info, None))
    assert np.allclose(img, 0.299 * 100 + 0.587 * 50 + 0.114 * 200, atol=1e-3)
    assert resolve_bands(info, 2) == (2,)
    with pytest.raises(InputError, match="Band 4 does not exist in .*rgb.tif"):
        resolve_bands(info, 4)


def test_georeferencing_is_detected(raster_writer):
    geo = open_raster(raster_writer("g.tif", np.zeros((4, 4), "uint8"), **GEO))
    plain = open_raster(raster_writer("p.tif", np.zeros((4, 4), "uint8")))
    assert geo.georeferenced and geo.crs.to_epsg() == 32633 and geo.pixel_size == 10
    assert not plain.georeferenced and plain.crs is None


def test_gcp_georeferencing_gives_an_affine_prior(tmp_path):
    import rasterio
    from rasterio.control import GroundControlPoint as G

    gcps = [G(0, 0, 500000, 4000000), G(0, 40, 500400, 4000000), G(30, 0, 500000, 3999700), G(30, 40, 500400, 3999700)]
    path = str(tmp_path / "gcp.tif")
    with rasterio.open(path, "w", driver="GTiff", width=40, height=30, count=1, dtype="uint8", gcps=gcps,
                       crs="EPSG:32633") as dst:
        dst.write(np.zeros((1, 30, 40), "uint8"))
    info = open_raster(path)
    assert info.georef_source == "gcps" and info.crs.to_epsg() == 32633
    assert np.allclose(info.transform.to_gdal(), (500000, 10, 0, 4000000, 0, -10))


def test_missing_and_unreadable_files_name_the_file(tmp_path):
    with pytest.raises(InputError, match="target raster '.*nope.tif' does not exist"):
        open_raster(str(tmp_path / "nope.tif"), "target")
    junk = tmp_path / "junk.tif"
    junk.write_text("not an image")
    with pytest.raises(InputError, match="reference raster '.*junk.tif' is not a raster GDAL can read"):
        open_raster(str(junk), "reference")
    with pytest.raises(InputError, match="is a folder"):
        open_raster(str(tmp_path), "target")


def test_budget_shape_bounds_the_pixel_count():
    (rows, cols), factor = budget_shape(10980, 10980, 4_000_000)
    assert rows * cols <= 4_000_000 * 1.001 and factor > 5
    assert budget_shape(100, 50, 4_000_000) == ((50, 100), 1.0)


def test_nodata_beside_an_alpha_band_reads_without_a_warning(raster_writer):
    import warnings

    data = np.random.default_rng(0).integers(1, 255, (4, 64, 64)).astype("uint8")
    path = raster_writer("rgba.tif", data, nodata=0, crs="EPSG:32632", transform=Affine(1, 0, 10, 0, -1, 0),
                         photometric="RGB", alpha="YES")
    info = open_raster(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", PendingDeprecationWarning)
        image, valid = read_image(info, (1, 2, 3), window=Window(-5, -5, 80, 80))
    assert image.shape == (80, 80) and valid.sum() == 64 * 64


def test_a_raster_without_a_mask_reads_as_if_its_every_pixel_were_masked_valid(raster_writer, tmp_path):
    """Inside the raster an all-valid mask is not read (GDAL would cache its blocks): the pixels and the
    validity (NaN invalid, parts outside the raster invalid) are those of the same raster with an explicit
    all-valid mask, read window by window and decimated."""
    import rasterio

    data = np.random.default_rng(2).normal(size=(2, 90, 120)).astype("float32")
    data[:, 20:30, 40:55] = np.nan
    plain = raster_writer("plain.tif", data)
    masked = str(tmp_path / "masked.tif")
    with rasterio.open(plain) as src:
        profile = src.profile
    with rasterio.Env(GDAL_TIFF_INTERNAL_MASK=True), rasterio.open(masked, "w", **profile) as dst:
        dst.write(data)
        dst.write_mask(np.full((90, 120), 255, np.uint8))
    a, b = open_raster(plain), open_raster(masked)
    with rasterio.open(plain) as p, rasterio.open(masked) as m:
        assert p.mask_flag_enums[0] != m.mask_flag_enums[0]
    for window, shape in [(None, None), (None, (30, 40)), (Window(10, 5, 50, 40), None), (Window(-8, 70, 40, 40), None),
                          (Window(100, -10, 30, 30), (10, 10))]:
        for bands in [(1,), (2,)]:
            (ia, va), (ib, vb) = read_image(a, bands, window, shape), read_image(b, bands, window, shape)
            assert np.array_equal(ia, ib) and np.array_equal(va, vb) and not va.all() and va.any()
