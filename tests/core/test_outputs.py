"""Every output format: content, conventions, GDAL's agreement with the model, atomic writing."""
import dataclasses
import json
import shutil
import sqlite3
import struct
import subprocess

import numpy as np
import pytest
import rasterio

from hamta.core import OutputError, OutputOptions, RegisterOptions, register
from hamta.core.coords import pixel_to_map
from hamta.core.io.raster import open_raster
from hamta.core.methods import get_method, registry
from hamta.core.options import MODEL_CHOICES, RESAMPLING_CHOICES
from hamta.core.outputs import OutputPaths, write_outputs
from hamta.core.outputs.model_vrt import write_model_vrt
from hamta.core.outputs.points import HEADER, qgs_double, read_points
from hamta.core.outputs.report import read_report


@pytest.fixture(scope="module")
def results(small_pair):
    """The small pair registered with each model; SIFT matches once (these tests are about the outputs), every
    model is fitted and checked by the pipeline."""
    sift = get_method("sift")
    found = []

    def match_once(*args, **kwargs):
        if not found:
            found.append(sift.match(*args, **kwargs))
        return found[0]

    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(registry._REGISTRY, "sift", dataclasses.replace(sift, match=match_once))
        return {m: register(small_pair["target"], small_pair["reference"], "sift", options=RegisterOptions(model=m))
                for m in MODEL_CHOICES}


def test_qgs_double_formats_like_qgis():
    assert qgs_double(500000.0) == "500000"
    assert qgs_double(0.1) == "0.10000000000000001"
    assert qgs_double(-0.0) == "0"
    assert qgs_double(-12.5) == "-12.5"


def test_points_file_layout_and_round_trip(tmp_path, results):
    res = results["affine"]
    path = tmp_path / "g.points"
    write_outputs(res, OutputPaths(points=str(path)))
    lines = path.read_text().split("\n")
    assert lines[0].startswith("#CRS: PROJCRS[\"WGS 84 / UTM zone 39N\"") and "\n" not in lines[0]
    assert lines[1] == HEADER and lines[-1] == ""
    assert all(len(row.split(",")) == 8 for row in lines[2:-1])
    crs, rows = read_points(str(path))
    assert "UTM zone 39N" in crs and len(rows) == len(res.gcps)
    for g, (mx, my, sx, sy, enabled) in zip(res.gcps, rows):
        assert (mx, my) == pytest.approx(g.map_xy, abs=1e-9)
        assert (sx, sy) == pytest.approx((g.target_px[0], -g.target_px[1]), abs=1e-9)  # QGIS: sourceY = -row
        assert enabled == g.enabled


def test_points_use_target_map_coordinates_when_the_target_is_georeferenced(tmp_path, landsat):
    from hamta.bench.cases import reprojected_case

    case = reprojected_case(str(tmp_path), landsat, dst_crs="EPSG:32617", shift_px=(10.0, 5.0))
    res = register(case.target, case.reference, "sift")
    write_outputs(res, OutputPaths(points=str(tmp_path / "p.points")))
    _, rows = read_points(str(tmp_path / "p.points"))
    t = res.target.transform
    g = res.gcps[0]
    assert rows[0][2:4] == pytest.approx(tuple(pixel_to_map(t, [g.target_px])[0]), abs=1e-6)


def test_gcp_geopackage_is_a_valid_point_layer(tmp_path, results):
    res = results["affine"]
    path = tmp_path / "g.gpkg"
    write_outputs(res, OutputPaths(gpkg=str(path)))
    con = sqlite3.connect(path)
    assert con.execute("PRAGMA application_id").fetchone()[0] == 0x47504B47
    assert con.execute("SELECT srs_id FROM gpkg_geometry_columns WHERE table_name='gcps'").fetchone()[0] == 32639
    rows = con.execute("SELECT geom, enabled, residual_px, map_x, map_y FROM gcps ORDER BY fid").fetchall()
    assert len(rows) == len(res.gcps)
    blob, enabled, residual, mx, my = rows[0]
    assert blob[:2] == b"GP" and struct.unpack("<dd", blob[-16:]) == pytest.approx((mx, my))
    assert enabled == 1 and residual == pytest.approx(res.gcps[0].residual_px)
    if shutil.which("ogrinfo"):
        info = subprocess.run(["ogrinfo", "-so", str(path), "gcps"], capture_output=True, text=True).stdout
        assert f"Feature Count: {len(res.gcps)}" in info and "UTM zone 39N" in info


def test_vrt_carries_the_enabled_gcps_without_resampling(tmp_path, results):
    res = results["affine"]
    path = tmp_path / "g.vrt"
    write_outputs(res, OutputPaths(vrt=str(path)))
    with rasterio.open(path) as ds, rasterio.open(res.target.path) as src:
        gcps, crs = ds.gcps
        assert len(gcps) == len(res.enabled_gcps()) and crs.to_epsg() == 32639
        assert np.array_equal(ds.read(), src.read())
        g = res.enabled_gcps()[0]
        assert (gcps[0].col, gcps[0].row, gcps[0].x, gcps[0].y) == pytest.approx(g.target_px + g.map_xy)


@pytest.mark.skipif(shutil.which("gdaltransform") is None, reason="needs GDAL's gdaltransform")
@pytest.mark.parametrize("model", MODEL_CHOICES)
def test_gdal_transformer_reproduces_the_model(tmp_path, results, model):
    """The VRT we warp from, read by GDAL's own transformer, maps target pixels where the model does."""
    res = results[model]
    vrt = str(tmp_path / "model.vrt")
    options = write_model_vrt(vrt, res)
    flags = {"GCP_TPS": ["-tps"], "GCP_POLYNOMIAL": ["-order", str(options.get("MAX_GCP_ORDER"))]}
    pts = np.random.default_rng(0).random((300, 2)) * [res.target.width, res.target.height]
    out = subprocess.run(["gdaltransform", *flags.get(options.get("SRC_METHOD"), []), vrt], capture_output=True,
                         text=True, input="\n".join(f"{x:.10f} {y:.10f}" for x, y in pts), check=True).stdout
    gdal_map = np.array([[float(v) for v in line.split()[:2]] for line in out.strip().splitlines()])
    err = np.linalg.norm(gdal_map - res.reference_to_map(res.model.apply(pts)), axis=1) / 10.0  # reference px
    assert err.max() < (0.01 if model == "projective" else 1e-6)


@pytest.mark.parametrize("model, warper", [("affine", "gdal"), ("tps", "gdal"), ("tps", "spline"),
                                           ("tps", "spline in small lattice chunks")])
def test_warped_raster_agrees_with_the_model(tmp_path, results, raster_writer, monkeypatch, model, warper):
    """Warp a raster whose values are its own pixel-centre coordinates: every output pixel then holds
    the target position sampled, which the model must map onto that output pixel. Exact for a
    geotransform; with GCP transformers GDAL's warper itself adds a few hundredths of a pixel
    (measured against its own transformer with GDAL 3.6 and 3.10). A spline is warped by
    :mod:`hamta.core.outputs.spline_warp` (the model's exact inverse), unless forced through GDAL; its
    lattice is inverted in chunks that need not hold whole lattice rows, each solved until all its nodes
    map within Newton's tolerance (a chunk of a few nodes stops sooner than one of thousands)."""
    from hamta.core.estimation.inverse import TOLERANCE_PX
    from hamta.core.outputs import spline_warp

    if warper == "gdal":
        monkeypatch.setattr(spline_warp, "KERNELS", {})
    if "chunks" in warper:
        monkeypatch.setattr(spline_warp, "LATTICE_CHUNK", 37)
    res = results[model]
    t = res.target
    cols, rows = np.meshgrid(np.arange(t.width) + 0.5, np.arange(t.height) + 0.5)
    ramp = raster_writer("ramp.tif", np.stack([cols, rows]).astype("float64"))
    res = dataclasses.replace(res, target=open_raster(ramp))
    out = tmp_path / "warped.tif"
    write_outputs(res, OutputPaths(raster=str(out)), output=OutputOptions(resampling="bilinear", resolution=8.0))
    with rasterio.open(out) as ds:
        data, tr = ds.read(), ds.transform
        assert ds.crs.to_epsg() == 32639
    valid = np.isfinite(data).all(axis=0)
    valid[[0, -1], :] = valid[:, [0, -1]] = False
    r, c = np.nonzero(valid)
    keep = (data[0][r, c] > 2) & (data[0][r, c] < t.width - 2) & (data[1][r, c] > 2) & (data[1][r, c] < t.height - 2)
    pick = np.random.default_rng(0).choice(np.flatnonzero(keep), 20000, replace=False)
    r, c = r[pick], c[pick]
    sampled = np.column_stack([data[0][r, c], data[1][r, c]])
    centres = res.reference_to_map(res.model.apply(sampled))
    x, y = tr.c + (c + 0.5) * tr.a, tr.f + (r + 0.5) * tr.e
    err = np.hypot(centres[:, 0] - x, centres[:, 1] - y) / 10.0  # reference pixels
    bound = {"gdal": 0.05 if model == "tps" else 1e-3, "spline": 1e-3}.get(warper, TOLERANCE_PX + 1e-3)
    assert np.percentile(err, 99) < bound


@pytest.mark.parametrize("fill", ["nodata", "alpha"])
def test_spline_warp_matches_gdal_on_values_nodata_and_alpha(tmp_path, results, raster_writer, monkeypatch, fill):
    """The spline path and GDAL's GCP_TPS warp of the same uint16 target agree: same nodata
    or alpha convention, the same covered pixels (the spline path also drops the ring of pixels whose
    kernel touches a nodata hole), the same values up to GDAL's own spline inverse."""
    from hamta.core.outputs import spline_warp

    res = results["tps"]
    t = res.target
    yy, xx = np.mgrid[0:t.height, 0:t.width]
    data = (2000 + 900 * np.sin(xx / 7.0) * np.cos(yy / 11.0) + 3 * xx).astype("uint16")
    if fill == "nodata":
        data[100:160, 200:280] = 0
    ramp = raster_writer("u16.tif", data, **({"nodata": 0} if fill == "nodata" else {}))
    res = dataclasses.replace(res, target=open_raster(ramp))
    assert spline_warp.spline_applies(res, "uint16", "bilinear")
    outs = {}
    for how in ("opencv", "gdal"):
        if how == "gdal":
            monkeypatch.setattr(spline_warp, "KERNELS", {})
        write_outputs(res, OutputPaths(raster=str(tmp_path / f"{how}.tif")))
        with rasterio.open(tmp_path / f"{how}.tif") as ds:
            outs[how] = (ds.read(), ds.nodata, ds.count, ds.transform)
    (a, nodata_a, count_a, tr_a), (b, nodata_b, count_b, tr_b) = outs["opencv"], outs["gdal"]
    assert (nodata_a, count_a, tr_a) == (nodata_b, count_b, tr_b) and a.shape == b.shape
    if fill == "alpha":
        assert count_a == 2 and set(np.unique(a[1])) == set(np.unique(b[1])) == {0, 65535}  # as GDAL: the type's max
        va, vb = a[1] > 0, b[1] > 0
    else:
        assert nodata_a == 0 and count_a == 1
        va, vb = a[0] != 0, b[0] != 0
    assert not (va & ~vb).any()
    assert (vb & ~va).sum() < 0.01 * vb.sum()
    diff = np.abs(a[0].astype(float) - b[0].astype(float))[va]
    assert np.median(diff) <= 2 and np.percentile(diff, 99) < 40  # values span 1100..3800


@pytest.mark.parametrize("model", ["affine", "tps"])
def test_the_warped_raster_is_the_same_in_strips_and_tiles_on_any_number_of_threads(tmp_path, results, monkeypatch,
                                                                                      model):
    """Strips (256 rows) warped ahead of the one being written, the spline's tiles (64 px) on threads: the
    same raster on one thread as on three."""
    from hamta.core import parallel
    from hamta.core.outputs import spline_warp, warp

    monkeypatch.setattr(warp, "STRIP_BYTES", 1)
    monkeypatch.setattr(spline_warp, "TILE_PX", 64)
    rasters = []
    for threads in (1, 3):
        monkeypatch.setattr(parallel, "THREADS", threads)
        path = tmp_path / f"{threads}.tif"
        write_outputs(results[model], OutputPaths(raster=str(path)))
        with rasterio.open(path) as ds:
            rasters.append(ds.read())
    assert rasters[0].shape[1] > 256 and np.array_equal(rasters[0], rasters[1])


def test_a_model_that_blows_the_grid_up_writes_no_raster(tmp_path, results):
    """A projective model whose horizon nearly reaches the target's edge maps it onto a grid far
    larger than its scale at the centre allows: refused, nothing written."""
    from hamta.core.estimation.models import LinearModel

    res = results["affine"]
    m = res.model.matrix @ np.array([[1.0, 0, 0], [0, 1.0, 0], [-0.95 / res.target.width, 0, 1.0]])
    res = dataclasses.replace(res, model=LinearModel("projective", m))
    with pytest.raises(OutputError, match="implausible"):
        write_outputs(res, OutputPaths(raster=str(tmp_path / "out" / "r.tif")))
    assert not (tmp_path / "out" / "r.tif").exists()


def test_report_schema(tmp_path, results):
    res = results["affine"]
    written = write_outputs(res, OutputPaths(report=str(tmp_path / "report.json")))
    rep = read_report(written["report"])
    assert rep["method"] == "sift" and rep["model"]["type"] == "affine"
    m = np.array(rep["model"]["target_px_to_reference_px"])
    assert m.shape == (3, 3) and np.allclose(m, res.model.matrix)
    g = rep["gcps"][0]
    assert set(g) >= {"target_px", "reference_px", "map", "residual_px", "enabled"}
    assert len(rep["reference"]["transform"]) == 6 and "UTM zone 39N" in rep["reference"]["crs"]
    assert set(rep["stats"]) >= {"n_matches", "n_inliers", "rmse_px", "rms_loo_px"}
    assert rep["timings_s"]["total"] > 0 and {"read", "match", "estimate"} <= set(rep["timings_s"])
    assert rep["versions"]["hamta"] and rep["versions"]["gdal"]
    json.dumps(rep, allow_nan=False)


def test_outputs_appear_whole_or_not_at_all(tmp_path, results, monkeypatch):
    import hamta.core.outputs as outputs

    def broken(path, result, *args, **kwargs):
        with open(path, "w") as f:
            f.write("partial")
        raise RuntimeError("a writer failed")

    monkeypatch.setattr(outputs, "write_gcp_layer", broken)
    with pytest.raises(RuntimeError):
        write_outputs(results["affine"], OutputPaths.in_folder(str(tmp_path / "out")))
    assert list((tmp_path / "out").iterdir()) == []  # no output, no staging folder, no manifest


def test_unwritable_output_folder_is_a_clear_error(tmp_path, results):
    blocker = tmp_path / "file.txt"
    blocker.write_text("x")
    with pytest.raises(OutputError, match="Cannot create the output folder '.*file.txt/out'"):
        write_outputs(results["affine"], OutputPaths.in_folder(str(blocker / "out")))


def _ramp_result(results, raster_writer, dtype="float64"):
    res = results["affine"]
    t = res.target
    cols, rows = np.meshgrid(np.arange(t.width) + 0.5, np.arange(t.height) + 0.5)
    ramp = raster_writer(f"ramp-{dtype}.tif", np.stack([cols, rows]).astype(dtype))
    return dataclasses.replace(res, target=open_raster(ramp))


def test_every_format_holds_the_same_pixels(tmp_path, results, raster_writer):
    res = _ramp_result(results, raster_writer)
    arrays = {}
    for fmt, name in (("gtiff", "a.tif"), ("cog", "b.tif"), ("auto", "c.vrt")):
        small_blocks = ("BLOCKSIZE=128",) if fmt == "cog" else ()  # overviews of a small raster
        write_outputs(res, OutputPaths(raster=str(tmp_path / name)),
                      output=OutputOptions(format=fmt, creation_options=small_blocks))
        with rasterio.open(tmp_path / name) as ds:
            arrays[fmt] = ds.read()
            assert ds.driver == ("VRT" if name.endswith(".vrt") else "GTiff") and ds.crs.to_epsg() == 32639
            if fmt == "cog":
                assert ds.overviews(1) and ds.tags(ns="IMAGE_STRUCTURE").get("LAYOUT") == "COG"
            if fmt == "gtiff":
                assert ds.profile["tiled"] and ds.compression.name == "deflate"
    assert "<SourceDataset relativeToVRT=\"0\">" in (tmp_path / "c.vrt").read_text()
    # The same warp for the COG; a VRT is warped block by block by GDAL, which does not widen the bilinear
    # kernel where an output pixel is larger than a target pixel (the GeoTIFF, like gdalwarp, does): a few
    # hundredths of a pixel typically, up to 0.3 px where the kernel meets the edge (GDAL 3.6 and 3.10).
    for fmt, typical, worst in (("cog", 1e-9, 1e-9), ("auto", 0.05, 0.5)):
        both = np.isfinite(arrays[fmt]) & np.isfinite(arrays["gtiff"])
        diff = np.abs(arrays[fmt] - arrays["gtiff"])[both]
        assert both.mean() > 0.5 and np.median(diff) <= typical and diff.max() < worst, fmt


def test_output_crs_keeps_every_pixel_where_the_model_puts_it(tmp_path, results, raster_writer):
    from rasterio.warp import transform as reproject_points

    res = _ramp_result(results, raster_writer)
    out = tmp_path / "geo.tif"
    write_outputs(res, OutputPaths(raster=str(out)), output=OutputOptions(crs="EPSG:4326"))
    with rasterio.open(out) as ds:
        data, tr = ds.read(), ds.transform
        assert ds.crs.to_epsg() == 4326
    r, c = np.array(data.shape[1:]) // 2
    target_px = data[:, r, c]
    lon, lat = tr * (c + 0.5, r + 0.5)
    x, y = reproject_points("EPSG:4326", "EPSG:32639", [lon], [lat])
    expected = pixel_to_map(res.reference.transform, res.model.apply(target_px[None]))[0]
    assert np.hypot(x[0] - expected[0], y[0] - expected[1]) < 0.05 * abs(res.reference.transform.a)


def test_valid_zeros_stay_valid_and_fill_is_chosen(tmp_path, results, raster_writer):
    res = _ramp_result(results, raster_writer, "uint8")  # columns and rows mod 256: many valid zeros
    out = tmp_path / "alpha.tif"
    write_outputs(res, OutputPaths(raster=str(out)))
    with rasterio.open(out) as ds:
        assert ds.count == 3 and ds.nodata is None and ds.colorinterp[-1].name == "alpha"
        data = ds.read()
    inside = data[2] == 255
    assert inside.mean() > 0.5 and (data[0][inside] == 0).sum() > 100  # valid zeros are kept as data
    write_outputs(res, OutputPaths(raster=str(tmp_path / "nd.tif")),
                  output=OutputOptions(fill="nodata", nodata=7, creation_options=("COMPRESS=LZW",)))
    with rasterio.open(tmp_path / "nd.tif") as ds:
        assert ds.count == 2 and ds.nodata == 7 and ds.compression.name == "lzw"


@pytest.mark.parametrize("bad", [dict(format="png"), dict(fill="mask"), dict(crs="EPSG:999999"),
                                 dict(creation_options=("COMPRESS",))])
def test_bad_output_options_are_refused(bad):
    with pytest.raises(ValueError):
        OutputOptions(**bad)


@pytest.mark.parametrize("resampling", RESAMPLING_CHOICES)
def test_every_resampling_choice_warps(tmp_path, results, resampling):
    out = tmp_path / f"{resampling}.tif"
    write_outputs(results["affine"], OutputPaths(raster=str(out)),
                  output=OutputOptions(resampling=resampling, resolution=20.0))
    with rasterio.open(out) as ds:
        data = ds.read(1)
    assert data.std() > 1


def test_positions_between_lattice_nodes_are_bilinear_and_a_node_without_inverse_blanks_its_cells():
    """A strip's lattice (nodes every ``step`` output px) interpolated for tiles that do not start on a
    node: a linear field is reproduced exactly; a node without an inverse (NaN) empties only the cells
    around it."""
    from hamta.core.outputs.spline_warp import interpolate

    step, rows, cols = 7, 6, 9
    ny, nx = np.mgrid[0:rows, 0:cols] * float(step)
    lattice = np.stack([3.0 + 0.5 * nx - 0.25 * ny, -2.0 + 0.125 * nx + 1.5 * ny], axis=-1)
    c0, t0, w, h = 5, 3, 40, 29  # pixels c0 .. c0 + w, t0 .. t0 + h of the strip
    xs, ys = interpolate(lattice, step, c0, t0, w, h)
    px, py = np.meshgrid(c0 + np.arange(w, dtype=float), t0 + np.arange(h, dtype=float))
    assert xs.shape == (h, w) and np.allclose(xs, 3.0 + 0.5 * px - 0.25 * py, atol=1e-12)
    assert np.allclose(ys, -2.0 + 0.125 * px + 1.5 * py, atol=1e-12)
    lattice[2, 3] = np.nan
    xs, ys = interpolate(lattice, step, c0, t0, w, h)
    near = (px >= 2 * step) & (px < 4 * step) & (py >= step) & (py < 3 * step)  # the four cells it is a corner of
    assert np.isnan(xs[near]).all() and np.isfinite(xs[~near]).all() and np.array_equal(np.isnan(xs), np.isnan(ys))
