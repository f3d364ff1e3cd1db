"""CRS edge cases (issue 25): rasters across the antimeridian, a local engineering CRS, a reference with a
geotransform but no CRS. No internal error, and the result placed where it belongs."""
import numpy as np
import pytest
import rasterio
from pyproj import Transformer
from rasterio.crs import CRS
from rasterio.transform import Affine
from rasterio.warp import Resampling, calculate_default_transform, reproject

from hamta.cli.main import main
from hamta.core import register


@pytest.fixture(scope="module")
def antimeridian(tmp_path_factory, landsat):
    """The Landsat sample as a geographic reference spanning longitude 179.3 to 180.9 (and the same place
    written as -180.7 to -179.1), and a target correctly georeferenced in UTM zone 1 south."""
    folder = tmp_path_factory.mktemp("antimeridian")
    with rasterio.open(landsat) as src:
        data = src.read()
    h, w = data.shape[1:]
    refs = {}
    for name, x0 in (("east", 179.3), ("west", 179.3 - 360.0)):
        refs[name] = str(folder / f"ref_{name}.tif")
        with rasterio.open(refs[name], "w", driver="GTiff", width=w, height=h, count=3, dtype="uint8",
                           crs="EPSG:4326", transform=Affine(1.6 / w, 0, x0, 0, -1.6 / w, -16.0), nodata=0) as dst:
            dst.write(data)
    with rasterio.open(refs["east"]) as ref:
        tr, tw, th = calculate_default_transform(ref.crs, "EPSG:32701", ref.width, ref.height, *ref.bounds)
        out = np.zeros((3, th, tw), np.uint8)
        reproject(ref.read(), out, src_transform=ref.transform, src_crs=ref.crs, dst_transform=tr,
                  dst_crs="EPSG:32701", resampling=Resampling.bilinear, src_nodata=0, dst_nodata=0)
    target = str(folder / "target_utm1s.tif")
    with rasterio.open(target, "w", driver="GTiff", width=tw, height=th, count=3, dtype="uint8", crs="EPSG:32701",
                       transform=tr, nodata=0) as dst:
        dst.write(out)
    return refs, target, tr


@pytest.mark.parametrize("side", ["east", "west"])
def test_a_reference_across_the_antimeridian_registers_a_utm_target_in_place(antimeridian, side):
    refs, target, target_transform = antimeridian
    result = register(target, refs[side])
    assert result.verified and result.plan.mode == "georeferenced"
    px = np.array([[150.0, 150.0], [400.0, 350.0], [600.0, 550.0]])
    mp = np.column_stack(target_transform * px.T)
    lon, lat = Transformer.from_crs("EPSG:32701", "EPSG:4326", always_xy=True).transform(mp[:, 0], mp[:, 1])
    lon = np.where(lon < 0, lon + 360.0, lon) if side == "east" else np.where(lon > 0, lon - 360.0, lon)
    with rasterio.open(refs[side]) as ref:
        want = np.column_stack(~ref.transform * (lon, lat))
    assert np.abs(result.model.apply(px) - want).max() < 0.3


def test_a_target_in_a_local_engineering_crs_is_searched_without_its_georeferencing(tmp_path, landsat, capsys):
    with rasterio.open(landsat) as src:
        profile, data = src.profile, src.read()
    profile.update(crs=CRS.from_wkt('LOCAL_CS["Site grid",LOCAL_DATUM["Local",0],UNIT["metre",1],'
                                    'AXIS["Easting",EAST],AXIS["Northing",NORTH]]'))
    target = tmp_path / "local.tif"
    with rasterio.open(target, "w", **profile) as dst:
        dst.write(data)
    args = ["register", "--reference", landsat, "--target", str(target), "--method", "sift", "--quiet"]
    assert main(args + ["--out", str(tmp_path / "a")]) == 0
    assert main(args + ["--out", str(tmp_path / "b"), "--target-georef", "use"]) == 1
    assert "cannot be transformed to the reference's" in capsys.readouterr().err


def test_a_reference_without_a_crs_places_the_output_by_its_geotransform(tmp_path, small_pair, capsys):
    with rasterio.open(small_pair["reference"]) as src:
        profile, data = src.profile, src.read()
    profile.pop("crs")
    reference = tmp_path / "no_crs.tif"
    with rasterio.open(reference, "w", **profile) as dst:
        dst.write(data)
    common = ["register", "--target", small_pair["target"], "--method", "sift", "--quiet"]
    assert main(common + ["--reference", small_pair["reference"], "--out", str(tmp_path / "with")]) == 0
    assert main(common + ["--reference", str(reference), "--out", str(tmp_path / "without")]) == 0
    assert "has a geotransform but no CRS" in capsys.readouterr().out
    with rasterio.open(tmp_path / "with" / "registered.tif") as a, rasterio.open(tmp_path / "without" /
                                                                                  "registered.tif") as b:
        assert b.crs is None and b.transform == a.transform and not b.transform.is_identity
