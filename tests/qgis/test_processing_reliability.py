"""The bad-input matrix through Processing: each case ends in a QgsProcessingException naming the file or
parameter (never a raw traceback), inputs stay byte-identical and nothing partial is written."""
import hashlib
import os
import re
import shutil
import sqlite3

import numpy as np
import pytest
from qgis.core import QgsProcessingException, QgsVectorLayer


def _run(alg, params):
    import processing

    return processing.run(f"hamta:{alg}", params)


def _digest(*paths):
    out = []
    for p in paths:
        with open(p, "rb") as f:
            out.append(hashlib.sha256(f.read()).hexdigest())
    return out


@pytest.fixture
def pair(small_pair, tmp_path):
    folder = tmp_path / "inputs"
    folder.mkdir()
    return {k: str(shutil.copy(small_pair[k], folder / os.path.basename(small_pair[k])))
            for k in ("target", "reference")}


def _truncated(pair, tmp_path):
    data = open(pair["target"], "rb").read()
    path = tmp_path / "truncated.tif"
    path.write_bytes(data[: len(data) * 6 // 10])
    return str(path)


def _constant(pair, tmp_path):
    from tests.conftest import write_raster

    return write_raster(tmp_path / "flat.tif", np.full((80, 80), 5, np.uint8))


# case -> (target maker, extra parameters, message pattern)
CASES = {
    "truncated target": (_truncated, {}, r"truncated\.tif"),
    "constant target": (_constant, {}, r"flat\.tif' is constant"),
    "NaN parameter": (None, {"P_RATIO": float("nan")}, r"ratio|P_RATIO"),
    "too few GCPs asked": (None, {"MAX_GCPS": 1}, r"max_gcps|MAX_GCPS|Maximum"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_input_is_a_clear_processing_error(case, provider, pair, tmp_path):
    make, extra, pattern = CASES[case]
    target = make(pair, tmp_path) if make else pair["target"]
    before = _digest(pair["target"], pair["reference"])
    out = tmp_path / "out"
    params = dict(TARGET=target, REFERENCE=pair["reference"], OUTPUT=str(out / "o.tif"),
                  REPORT=str(out / "r.json"), **extra)
    with pytest.raises(QgsProcessingException) as info:
        _run("registersift", params)
    message = str(info.value)
    assert re.search(pattern, message) and "Traceback" not in message, message
    assert _digest(pair["target"], pair["reference"]) == before
    assert not out.exists() or not [f for f in os.listdir(out) if not f.startswith(".")]


def test_an_output_over_the_target_is_refused(provider, pair):
    before = _digest(pair["target"])
    with pytest.raises(QgsProcessingException, match="one of the input files"):
        _run("registersift", dict(TARGET=pair["target"], REFERENCE=pair["reference"], OUTPUT=pair["target"]))
    assert _digest(pair["target"]) == before


@pytest.mark.parametrize("error, says", [
    (RuntimeError("boom"), r"unexpected error \(RuntimeError: boom\)"),
    (ValueError("math domain error"), r"unexpected error \(ValueError: math domain error\)"),  # a bug, not the user's
    ("usage", r"Invalid parameter: step must be a positive number"),
])
def test_an_unexpected_error_is_wrapped_and_a_usage_error_named_as_one(provider, pair, tmp_path, monkeypatch, error,
                                                                       says):
    import hamta.processing.register_algorithm as alg
    from hamta.core.errors import UsageError

    def broken(*args, **kwargs):
        raise UsageError("step must be a positive number") if error == "usage" else error

    monkeypatch.setattr(alg, "run", broken)
    with pytest.raises(QgsProcessingException, match=says):
        _run("registersift", dict(TARGET=pair["target"], REFERENCE=pair["reference"], OUTPUT=str(tmp_path / "o.tif")))


def test_a_bug_in_a_method_names_the_method(provider, pair, tmp_path, monkeypatch):
    import hamta.processing.register_algorithm as alg
    from hamta.core.errors import MethodCrashed

    def broken(*args, **kwargs):
        cause = ValueError("operands could not be broadcast")
        raise MethodCrashed("sift", cause) from cause

    monkeypatch.setattr(alg, "run", broken)
    with pytest.raises(QgsProcessingException, match=r"unexpected error \(ValueError in method 'sift': operands could"):
        _run("registersift", dict(TARGET=pair["target"], REFERENCE=pair["reference"], OUTPUT=str(tmp_path / "o.tif")))


def _layers(path):
    with sqlite3.connect(path) as con:
        return sorted(r[0] for r in con.execute("SELECT table_name FROM gpkg_contents WHERE data_type = 'features'"))


@pytest.mark.parametrize("form", ["ogr-uri", "layername"])
def test_the_gcp_layer_joins_an_existing_geopackage(form, provider, pair, tmp_path):
    """A layer added to the user's GeoPackage: the other layers are kept, the GCP layer is named as asked."""
    gpkg = tmp_path / "project.gpkg"
    first = _run("registersift", dict(TARGET=pair["target"], REFERENCE=pair["reference"],
                                      OUTPUT=str(tmp_path / "a.tif"), GCP_LAYER=str(gpkg)))
    assert _layers(first["GCP_LAYER"]) == ["gcps"]
    destination = (f"ogr:dbname='{gpkg}' table=\"second\" (geom)" if form == "ogr-uri"
                   else f"{gpkg}|layername=second")
    res = _run("registersift", dict(TARGET=pair["target"], REFERENCE=pair["reference"],
                                    OUTPUT=str(tmp_path / "b.tif"), GCP_LAYER=destination))
    assert _layers(str(gpkg)) == ["gcps", "second"]
    layer = QgsVectorLayer(res["GCP_LAYER"], "second", "ogr")
    assert layer.isValid() and layer.featureCount() >= 20
    del layer
