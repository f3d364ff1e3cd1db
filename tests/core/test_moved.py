"""Output grid 'target': the target's pixels unchanged under the georeferencing the model gives."""
from types import SimpleNamespace

import numpy as np
import pytest
import rasterio
from affine import Affine

from hamta.core import OutputOptions, RegisterOptions, run
from hamta.core.errors import OutputError
from hamta.core.estimation.models import LinearModel
from hamta.core.outputs import OutputPaths
from hamta.core.outputs.moved import moved_transform


def _result(matrix):
    reference = SimpleNamespace(path="ref.tif", crs=rasterio.crs.CRS.from_epsg(32617),
                                transform=Affine(30.0, 0, 500000.0, 0, -30.0, 4000000.0))
    return SimpleNamespace(target=SimpleNamespace(width=400, height=300, path="t.tif"), reference=reference,
                           pixel_mode=False, model=LinearModel("affine", np.asarray(matrix, float)))


def test_a_shift_and_scale_becomes_the_geotransform():
    transform = moved_transform(_result([[0.5, 0, 12.25], [0, 0.5, -3.5], [0, 0, 1]]))
    assert transform.almost_equals(Affine(15.0, 0, 500367.5, 0, -15.0, 4000105.0), precision=1e-9)


def test_a_turned_model_is_refused_naming_the_way_out():
    a = np.radians(0.5)
    with pytest.raises(OutputError, match="turns or bends .* 'linear'"):
        moved_transform(_result([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]]))


def test_a_moved_georeferencing_is_corrected_without_touching_a_pixel(landsat, tmp_path):
    with rasterio.open(landsat) as ds:
        profile, data, true = ds.profile, ds.read(), ds.transform
    profile.update(transform=true * Affine.translation(7.3, -4.6))
    target = str(tmp_path / "moved.tif")
    with rasterio.open(target, "w", **profile) as out:
        out.write(data)
    result, written = run(target, landsat, OutputPaths(raster=str(tmp_path / "out.tif")),
                          options=RegisterOptions(model="linear"), output=OutputOptions(pixel_grid="target"))
    assert result.verified
    with rasterio.open(written["raster"]) as out:
        assert np.array_equal(out.read(), data) and out.crs == profile["crs"]
        corner = np.subtract(~true * (out.transform.c, out.transform.f), (0, 0))
        assert np.hypot(*corner) < 0.2 and abs(out.transform.a / true.a - 1) < 1e-3


def test_the_grid_target_takes_no_output_crs():
    from hamta.core.outputs.warp import check_output_options

    with pytest.raises(ValueError, match="no output CRS"):
        check_output_options(OutputOptions(pixel_grid="target", crs="EPSG:4326"), None, "out.tif")
