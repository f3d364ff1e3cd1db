"""The Processing algorithm: parameters, outputs as layers, errors and cancellation."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest
from qgis.core import QgsProcessingException, QgsProcessingFeedback, QgsRasterLayer, QgsVectorLayer

from hamta.core.mapping import map_points_from_report
from hamta.core.outputs.report import read_report
from hamta.processing.mapping import register_settings


def _run(params, feedback=None):
    import processing

    return processing.run("hamta:registersift", params, feedback=feedback or QgsProcessingFeedback())


def test_provider_lists_the_algorithm_with_its_parameters(provider):
    alg = provider.algorithm("registersift")
    assert alg is not None and alg.displayName() == "Register raster (SIFT baseline)"
    names = [p.name() for p in alg.parameterDefinitions()]
    for name in ("TARGET", "REFERENCE", "MODEL", "RESAMPLING", "OUTPUT", "GCP_LAYER", "GCP_POINTS", "REPORT",
                 "P_RATIO", "P_N_FEATURES"):
        assert name in names
    assert "Lowe" in alg.shortHelpString()


def test_rilbp_algorithm_runs(provider, small_pair, tmp_path):
    import processing

    alg = provider.algorithm("registerrilbp")
    assert alg.displayName() == "Register satellite image (RILBP, rotation-invariant)"
    assert "P_PATCH_SMOOTHING" in [p.name() for p in alg.parameterDefinitions()]
    res = processing.run("hamta:registerrilbp", dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"],
                                                     OUTPUT=str(tmp_path / "o.tif"), REPORT=str(tmp_path / "r.json")))
    report = json.loads(open(res["REPORT"]).read())
    assert report["method"] == "rilbp" and res["N_GCPS"] >= 20


def test_sar_algorithm_registers_a_speckled_pair(provider, shared, tmp_path):
    import processing
    from hamta.bench.families import CaseSpec, build_case

    spec = CaseSpec("speckle", "sar_L4_rot30", {"source": "sar", "looks": 4, "angle": 30, "scale": 1.0, "grain": 0.9})
    case = build_case(spec, str(tmp_path), 400, str(shared / "data"))
    alg = provider.algorithm("registerndsift")
    units = next(p for p in alg.parameterDefinitions() if p.name() == "P_UNITS")
    assert units.options() == ["amplitude", "intensity", "db"]
    res = processing.run("hamta:registerndsift", dict(TARGET=case.target, REFERENCE=case.reference, P_UNITS=0,
                                                      OUTPUT=str(tmp_path / "o.tif"), REPORT=str(tmp_path / "r.json")))
    report = read_report(res["REPORT"])
    assert report["method"] == "ndsift-pc" and report["params"]["units"] == "amplitude"
    assert report["stats"]["refined"]
    check = map_points_from_report(res["REPORT"], case.check_points)
    mapped = np.array([p["reference_px"] for p in check])
    assert np.sqrt(np.mean(np.sum((mapped - case.truth(case.check_points)) ** 2, axis=1))) < 1.0


def test_sar_optical_algorithm_registers_an_inverted_speckled_image(provider, shared, tmp_path):
    import processing
    from hamta.bench.families import CaseSpec, build_case

    spec = CaseSpec("multimodal", "landsat_sigmoid-invert", {"source": "landsat", "mapping": "sigmoid-invert"})
    case = build_case(spec, str(tmp_path), 512, str(shared / "data"))
    alg = provider.algorithm("registersaroptical")
    coarse = next(p for p in alg.parameterDefinitions() if p.name() == "P_COARSE")
    assert coarse.options() == ["search", "lines"]
    params = dict(TARGET=case.target, REFERENCE=case.reference, OUTPUT=str(tmp_path / "o.tif"),
                  REPORT=str(tmp_path / "r.json"))
    res = processing.run("hamta:registersaroptical", params)
    report = read_report(res["REPORT"])
    assert report["method"] == "cfog" and res["N_GCPS"] >= 50
    check = map_points_from_report(res["REPORT"], case.check_points)
    mapped = np.array([p["reference_px"] for p in check])
    assert np.sqrt(np.mean(np.sum((mapped - case.truth(case.check_points)) ** 2, axis=1))) < 1.0


def test_sar_optical_dialog_shows_the_few_tuned_parameters_and_hides_the_rest(provider):
    from qgis.core import QgsProcessingParameterDefinition as Definition

    alg = provider.algorithm("registersaroptical")
    method = [p for p in alg.parameterDefinitions() if p.name().startswith("P_")]
    basic = {p.name() for p in method if not p.flags() & Definition.FlagAdvanced}
    assert basic == {"P_UNITS", "P_MAX_ROTATION_DEG", "P_MAX_SCALE"}
    assert len(method) <= 14 and "P_GGS_ALPHA" not in {p.name() for p in method}


def test_enum_labels_follow_the_core_choices(provider):
    from hamta.core.options import MODEL, RESAMPLING

    alg = provider.algorithm("registersaroptical")
    defs = {p.name(): p for p in alg.parameterDefinitions()}
    assert defs["MODEL"].options() == [MODEL.labels[v] for v in MODEL.values]
    assert defs["MODEL"].options()[defs["MODEL"].defaultValue()] == MODEL.labels["auto"]
    assert defs["RESAMPLING"].options()[defs["RESAMPLING"].defaultValue()] == RESAMPLING.labels["bilinear"]
    ndsift = {p.name(): p for p in provider.algorithm("registerndsift").parameterDefinitions()}
    assert ndsift["MODEL"].defaultValue() == MODEL.index("auto")  # the method's similarity, or the check's choice


def test_every_method_algorithm_is_listed(provider):
    ids = {a.name() for a in provider.algorithms()}
    assert {"registerauto", "registersift", "registerrilbp", "registersibrif", "registerndsift", "registersaroptical",
            "registercrossmodal"} <= ids
    sibrif = provider.algorithm("registersibrif")
    enum = next(p for p in sibrif.parameterDefinitions() if p.name() == "P_MAGNITUDE")
    assert enum.options() == ["l1", "l2"]


def test_parameter_mapping_is_pure():
    options, paths, output = register_settings({"MODEL": 5, "RESAMPLING": 2, "PIXEL_GRID": 1, "REFINE": 2,
                                                "TARGET_BAND": 0, "REFERENCE_BAND": 2, "SEED": 3,
                                                "OUTPUT": "/x/o.tif", "GCP_POINTS": ""})
    assert options.model == "tps" and options.refine == "off" and options.seed == 3
    assert options.target_band is None and options.reference_band == 2
    assert output.resampling == "cubic" and output.pixel_grid == "reference"
    assert paths.raster == "/x/o.tif" and paths.points is None
    options, _, output = register_settings({"TOLERANCE": 0, "RANSAC_THRESHOLD": 0.0, "RESOLUTION": 0})
    assert options.tolerance_px == 3.0 and options.ransac_threshold_px is None and output.resolution is None


def test_processing_run_writes_outputs_that_load_as_layers(provider, small_pair, tmp_path):
    out = {"OUTPUT": str(tmp_path / "reg.tif"), "GCP_LAYER": str(tmp_path / "gcps.gpkg"),
           "GCP_POINTS": str(tmp_path / "gcps.points"), "REPORT": str(tmp_path / "report.json")}
    res = _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], MODEL=1, **out))
    for key, path in out.items():
        assert res[key] == path and os.path.isfile(path)
    raster = QgsRasterLayer(res["OUTPUT"], "reg")
    assert raster.isValid() and raster.crs().authid() == "EPSG:32639"
    layer = QgsVectorLayer(res["GCP_LAYER"], "gcps", "ogr")
    assert layer.isValid() and layer.crs().authid() == "EPSG:32639" and layer.featureCount() >= 50
    assert res["N_GCPS"] >= 50 and 0 < res["RMSE_PX"] < 1.0
    report = json.loads(open(res["REPORT"]).read())
    assert report["model"]["type"] == "affine"
    renderer = layer.renderer()  # the default style stored in the GeoPackage: by residual, rejected apart
    assert renderer.type() == "RuleRenderer"
    rules = renderer.rootRule().children()
    assert [r.filterExpression() for r in rules][-1] == 'NOT "enabled"' and len(rules) == 5
    counts = {r.label(): _drawn_by(layer, r.filterExpression()) for r in rules}
    assert counts["rejected match (not used for the fit)"] > 0 and sum(counts.values()) == layer.featureCount()
    del raster, layer, renderer, rules


def _drawn_by(layer, expression: str) -> int:
    """Features a rule draws: evaluated by QGIS's expression engine as the renderer does (a provider's SQL
    filter may read a Boolean field differently)."""
    from qgis.core import QgsExpression, QgsExpressionContext

    rule, context, n = QgsExpression(expression), QgsExpressionContext(), 0
    for feature in layer.getFeatures():
        context.setFeature(feature)
        n += bool(rule.evaluate(context))
    return n


def test_method_parameters_reach_the_core(provider, small_pair, tmp_path):
    res = _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], P_RATIO=0.6, P_CROSS_CHECK=0,
                    OUTPUT=str(tmp_path / "r.tif"), REPORT=str(tmp_path / "r.json")))
    params = json.loads(open(res["REPORT"]).read())["params"]
    assert params["ratio"] == pytest.approx(0.6) and params["cross_check"] == "none"


def test_bad_input_raises_a_processing_exception(provider, small_pair, tmp_path, raster_writer):
    import numpy as np

    flat = raster_writer("flat.tif", np.full((64, 64), 3, "uint8"))
    with pytest.raises(QgsProcessingException, match="flat.tif' is constant"):
        _run(dict(TARGET=flat, REFERENCE=small_pair["reference"], OUTPUT=str(tmp_path / "o.tif")))
    assert not (tmp_path / "o.tif").exists()


def test_cancel_stops_cleanly_and_writes_nothing(provider, small_pair, tmp_path):
    feedback = QgsProcessingFeedback()
    feedback.progressChanged.connect(lambda p: feedback.cancel() if p > 20 else None)
    with pytest.raises(QgsProcessingException, match="canceled"):
        _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], OUTPUT=str(tmp_path / "o.tif"),
                  GCP_LAYER=str(tmp_path / "g.gpkg")), feedback)
    assert list(tmp_path.iterdir()) == []


def test_points_file_round_trips_through_the_qgis_reader(provider, small_pair, tmp_path):
    from hamta.core.outputs.points import read_points

    path = str(tmp_path / "g.points")
    _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], OUTPUT=str(tmp_path / "o.tif"),
              GCP_POINTS=path))
    reader = os.path.join(os.path.dirname(__file__), "qgis_points_reader.py")
    proc = subprocess.run(["/usr/bin/python3", reader, path], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    loaded = json.loads(proc.stdout.strip().splitlines()[-1])
    assert loaded["crs_valid"] and loaded["crs_authid"] == "EPSG:32639"
    _, ours = read_points(path)
    assert len(loaded["points"]) == len(ours)
    for (mx, my, sx, sy, en), (qmx, qmy, qsx, qsy, qen) in zip(ours, loaded["points"]):
        assert (qmx, qmy, qsx, qsy) == pytest.approx((mx, my, sx, sy), abs=1e-6) and qen == en


def test_automatic_algorithm_registers_and_reports_its_verdict(provider, small_pair, tmp_path):
    import processing

    alg = provider.algorithm("registerauto")
    assert alg is not None and alg.displayName() == "Register raster (automatic)"
    assert not [p for p in alg.parameterDefinitions() if p.name().startswith("P_")]
    res = processing.run("hamta:registerauto", dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"],
                                                    OUTPUT=str(tmp_path / "o.tif"), REPORT=str(tmp_path / "r.json")))
    assert res["VERDICT"] == "verified" and res["METHOD"] == "sift" and os.path.isfile(res["OUTPUT"])
    report = json.loads(open(res["REPORT"]).read())
    assert report["quality"]["verdict"] == "verified" and report["auto"]["attempts"][0]["accepted"]


def test_unverified_result_fails_clearly_unless_kept(provider, small_pair, tmp_path):
    import processing

    params = dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], TOLERANCE=0.01,
                  OUTPUT=str(tmp_path / "o.tif"), REPORT=str(tmp_path / "r.json"))
    from qgis.core import QgsProcessingFeedback

    class Feedback(QgsProcessingFeedback):
        def __init__(self):
            super().__init__()
            self.lines = []

        def pushInfo(self, text):  # noqa: N802 (QGIS's name)
            self.lines.append(text)

    feedback = Feedback()
    with pytest.raises(QgsProcessingException, match="not verified"):
        processing.run("hamta:registersift", params, feedback=feedback)
    assert not (tmp_path / "o.tif").exists()
    tips = [line for line in feedback.lines if line.startswith("May help: ")]
    assert any("'Local (non-rigid) correction' = on" in t for t in tips), feedback.lines
    assert any("'Transformation' = Polynomial 2" in t for t in tips), tips
    res = processing.run("hamta:registersift", dict(params, KEEP_UNVERIFIED=True))
    assert res["VERDICT"] in ("suspect", "failed") and os.path.isfile(res["OUTPUT"])


def test_output_control_vrt_crs_html_and_creation_options(provider, small_pair, tmp_path):
    res = _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], OUTPUT=str(tmp_path / "out.vrt"),
                    OUTPUT_CRS="EPSG:4326", OUTPUT_HTML=str(tmp_path / "report.html")))
    raster = QgsRasterLayer(res["OUTPUT"], "reg")
    assert raster.isValid() and raster.crs().authid() == "EPSG:4326"
    assert raster.dataProvider().name() == "gdal" and pathlib.Path(res["OUTPUT"]).read_text().startswith("<VRTDataset")
    assert "data:image/jpeg;base64," in pathlib.Path(res["OUTPUT_HTML"]).read_text()
    del raster
    with pytest.raises(QgsProcessingException, match="COG driver says: driver COG does not support creation option "
                                                      "BLOCKXSIZE"):  # the GeoTIFF's option, not the COG's
        _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], OUTPUT=str(tmp_path / "c.tif"),
                  FORMAT=2, CREATION_OPTIONS="COMPRESS=LZW BLOCKXSIZE=512 BLOCKYSIZE=512", FILL=2, NODATA=255))
    res = _run(dict(TARGET=small_pair["target"], REFERENCE=small_pair["reference"], OUTPUT=str(tmp_path / "c.tif"),
                    FORMAT=2, CREATION_OPTIONS="COMPRESS=LZW BLOCKSIZE=256", FILL=2, NODATA=255))
    import rasterio

    with rasterio.open(res["OUTPUT"]) as ds:
        assert ds.compression.name == "lzw" and ds.nodata == 255 and ds.overviews(1)
        assert ds.block_shapes[0] == (256, 256)


def test_a_reference_without_georeferencing_needs_the_pixel_mode_box(provider, small_pair, tmp_path):
    import cv2
    import rasterio

    with rasterio.open(small_pair["reference"]) as ds:
        plain = str(tmp_path / "plain.png")
        cv2.imwrite(plain, ds.read().transpose(1, 2, 0)[:, :, ::-1])
    params = {"TARGET": small_pair["target"], "REFERENCE": plain, "OUTPUT": str(tmp_path / "o.tif"),
              "GCP_LAYER": str(tmp_path / "g.gpkg")}
    with pytest.raises(QgsProcessingException, match=r"plain\.png' has no georeferencing.*\(set 'Pixel-to-pixel"):
        _run(params)
    assert not (tmp_path / "o.tif").exists()
    feedback = QgsProcessingFeedback()
    warnings = []
    feedback.pushWarning = warnings.append
    result = _run(dict(params, PIXEL_MODE=True), feedback)
    assert result["VERDICT"] == "verified" and any("pixel-to-pixel" in w for w in warnings)
    assert QgsRasterLayer(result["OUTPUT"], "o").crs().isValid() is False


def _processing_value(spec, value):
    if spec.choice is not None:
        return spec.choice.index(value)
    if spec.kind == "extent":  # QGIS writes xmin,xmax,ymin,ymax [CRS]
        xmin, ymin, xmax, ymax, crs = value.split(",")
        return f"{xmin},{xmax},{ymin},{ymax} [{crs}]"
    return value[0] if isinstance(value, tuple) else value


@pytest.mark.parametrize("name", ["registerauto", "registersift", "batchregister"])
def test_every_option_is_reachable_from_processing_with_the_same_default(provider, name):
    from dataclasses import replace

    from qgis.core import QgsProcessingContext

    from hamta.core.options import OutputOptions, RegisterOptions, processing_key, resolve_options
    from hamta.processing.options import option_values
    from tests.conftest import option_samples

    alg = provider.algorithm(name).create()
    method = alg.method() if hasattr(alg, "method") else None
    defaults = replace(resolve_options(RegisterOptions(), method), model=None) if method else RegisterOptions()
    context = QgsProcessingContext()
    options, _, output = register_settings(option_values(alg, {}, context))
    assert options == defaults and output == OutputOptions()
    for f, spec, value in option_samples():
        key = processing_key(f, spec)
        assert alg.parameterDefinition(key) is not None, f"{name} lacks {key}"
        values = option_values(alg, {key: _processing_value(spec, value)}, context)
        options, _, output = register_settings(values)
        assert getattr(options if hasattr(options, f.name) else output, f.name) == value, key


def test_a_method_module_added_shows_as_an_algorithm_with_its_parameters(provider, new_method_module, small_pair,
                                                                         tmp_path):
    import processing
    from hamta.processing.batch_algorithm import batch_methods

    provider.refreshAlgorithms()
    try:
        alg = provider.algorithm("registertestmethod")
        assert alg is not None and alg.displayName() == "Test method" and "SIFT under another name" in \
            alg.shortHelpString()
        names = [p.name() for p in alg.parameterDefinitions()]
        assert {"P_RATIO", "P_N_FEATURES", "TOLERANCE", "MODEL"} <= set(names)
        assert new_method_module in batch_methods()
        res = processing.run("hamta:registertestmethod", dict(
            TARGET=small_pair["target"], REFERENCE=small_pair["reference"], P_RATIO=0.75,
            OUTPUT=str(tmp_path / "o.tif"), REPORT=str(tmp_path / "r.json")))
        assert res["METHOD"] == new_method_module and res["VERDICT"] == "verified"
    finally:
        import hamta.core.methods.registry as registry

        registry._REGISTRY.pop(new_method_module, None)
        provider.refreshAlgorithms()


def test_the_search_area_s_help_gives_the_order_qgis_accepts(provider):
    """qgis_process refuses 'xmin,ymin,xmax,ymax' for an extent parameter; its help shows QGIS's own form."""
    extent = provider.algorithm("registerauto").parameterDefinition("EXTENT")
    assert "xmin,xmax,ymin,ymax [EPSG:code]" in extent.help() and "xmin,ymin,xmax,ymax" not in extent.help()


def test_the_batch_resolves_its_reference_layer_once(provider, small_pair, xyz_source, landsat, tmp_path, monkeypatch):
    from urllib.parse import quote

    from qgis.core import QgsProcessingContext

    import hamta.core.reference as reference_module
    from hamta.core.reference import RasterReference, ServiceReference

    parse, calls = reference_module.parse_service, []
    monkeypatch.setattr(reference_module, "parse_service", lambda text: calls.append(text) or parse(text))
    alg, context = provider.algorithm("batchregister").create(), QgsProcessingContext()
    targets = [small_pair["target"], small_pair["reference"]]
    jobs = alg._jobs({"TARGETS": targets, "REFERENCE": small_pair["reference"]}, context, str(tmp_path / "a"))
    assert [j.reference for j in jobs] == [RasterReference(small_pair["reference"])] * 2 and calls == []
    layer = QgsRasterLayer(xyz_source, "basemap", "wms")
    jobs = alg._jobs({"TARGETS": targets, "REFERENCE": layer}, context, str(tmp_path / "b"))
    assert len(calls) == 1 and all(isinstance(j.reference, ServiceReference) for j in jobs)
    assert jobs[0].reference is jobs[1].reference
    source = landsat[0]
    uri = (f"?crs=EPSG:32618&extent=0,0,1,1&width=1&height=1&formula=%22s@1%22&s:uri={quote(source)}"
           "&s:provider=gdal")
    with pytest.raises(QgsProcessingException, match="cannot be read by every pair of a batch"):
        alg._jobs({"TARGETS": targets, "REFERENCE": QgsRasterLayer(uri, "calculated", "virtualraster")}, context,
                  str(tmp_path / "c"))
