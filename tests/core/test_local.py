"""Local (non-rigid) correction: it follows a smooth displacement field the global model cannot, keeps
outliers out, and shows its grid as shift vectors."""
import sqlite3

import numpy as np
import pytest

from hamta.bench.families import CaseSpec, build_case
from hamta.core import OutputOptions, RegisterOptions, register
from hamta.core.local import LocalParams, consistent, smooth
from hamta.core.outputs import OutputPaths, write_outputs


@pytest.fixture(scope="module")
def case(tmp_path_factory, shared):
    spec = CaseSpec("nonrigid", "landsat_smooth_3px", {"source": "landsat", "amplitude": 3.0, "patches": 0})
    return build_case(spec, str(tmp_path_factory.mktemp("nonrigid")), 800, str(shared / "data"))


def _rmse(case, result):
    return float(np.sqrt(np.mean(case.errors(result.model) ** 2)))


def test_local_correction_follows_a_smooth_field(case, tmp_path):
    glob = register(case.target, case.reference, method="sift")
    local = register(case.target, case.reference, method="sift", options=RegisterOptions(local=True))
    assert local.model.kind == "tps" and local.verified
    assert _rmse(case, local) < 0.5 * _rmse(case, glob) and _rmse(case, local) < 0.4
    summary = local.to_report()["local"]
    assert summary["n_kept"] >= 0.9 * summary["n_windows"] >= 40
    assert summary["window_px"] == 64 and summary["spacing_px"] >= 32
    write_outputs(local, OutputPaths(gpkg=str(tmp_path / "g.gpkg")), output=OutputOptions())
    with sqlite3.connect(tmp_path / "g.gpkg") as con:
        layers = sorted(r[0] for r in con.execute("SELECT table_name FROM gpkg_contents WHERE data_type='features'"))
        n = con.execute('SELECT count(*) FROM "gcps_local_shifts"').fetchone()[0]
    assert layers == ["gcps", "gcps_local_shifts"] and n == summary["n_windows"]


def test_outliers_disagree_with_their_neighbours_and_smoothing_keeps_a_gradient():
    rng = np.random.default_rng(0)
    gx, gy = np.meshgrid(np.arange(20) * 50.0, np.arange(20) * 50.0)
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    field = np.column_stack([0.002 * xy[:, 0], -0.001 * xy[:, 1] + 1.0])  # a smooth gradient
    noisy = field + rng.normal(0, 0.05, field.shape)
    bad = rng.choice(len(xy), 12, replace=False)
    noisy[bad] += rng.uniform(3, 6, (12, 2))
    kept = consistent(xy, noisy, np.ones(len(xy), bool), LocalParams())
    assert not kept[bad].any() and kept.sum() >= len(xy) - 20
    smoothed = smooth(xy[kept], noisy[kept], 8)
    assert np.abs(smoothed - field[kept]).mean() < 0.5 * np.abs(noisy[kept] - field[kept]).mean()


@pytest.mark.parametrize("bad", [dict(window_px=8), dict(spacing_px=-1.0), dict(neighbours=1)])
def test_bad_local_settings_are_refused(bad):
    with pytest.raises(ValueError):
        LocalParams(**bad)


def test_on_a_shift_the_local_correction_is_never_worse_than_the_global_model(landsat, tmp_path):
    import rasterio
    from affine import Affine

    with rasterio.open(landsat) as ds:
        profile, data = ds.profile, ds.read()
        profile.update(transform=ds.transform * Affine.translation(-6.4, 3.7))
    target = str(tmp_path / "moved.tif")
    with rasterio.open(target, "w", **profile) as out:
        out.write(data)
    whole = register(target, landsat, method="shift")
    local = register(target, landsat, method="shift", options=RegisterOptions(local=True))
    assert whole.verified and local.verified
    assert local.verification.error_bound_px <= whole.verification.error_bound_px
    if local.local is None:
        assert any(n.startswith("local correction not kept") for n in local.notes)
        assert local.model.matrix.tolist() == whole.model.matrix.tolist()
