"""The model's order chosen by the check (:mod:`hamta.core.order`): a second-order polynomial where the points bend
away from the linear model and the check bounds it more tightly, the linear model otherwise."""
import numpy as np
import pytest
import rasterio
from pyproj import Transformer
from rasterio.warp import Resampling, calculate_default_transform, reproject

from hamta.core import RegisterOptions, register
from hamta.core.order import f_tail
from hamta.core.verify import Verification, beats

from ..conftest import write_raster


@pytest.fixture(scope="module")
def mercator_pair(landsat, tmp_path_factory):
    """The Landsat scene (240 km, UTM 18N, far from its zone's meridian) without its georeferencing, and the same
    scene warped to Web Mercator as the reference; and the truth, target px -> reference px."""
    folder = tmp_path_factory.mktemp("mercator")
    with rasterio.open(landsat) as src:
        transform, width, height = calculate_default_transform(src.crs, "EPSG:3857", src.width, src.height,
                                                               *src.bounds)
        reference = str(folder / "reference.tif")
        with rasterio.open(reference, "w", driver="GTiff", width=width, height=height, count=3, dtype="uint8",
                           crs="EPSG:3857", transform=transform, nodata=0) as dst:
            for b in (1, 2, 3):
                reproject(rasterio.band(src, b), rasterio.band(dst, b), resampling=Resampling.cubic)
        target = write_raster(folder / "target.tif", src.read())
        to_mercator = Transformer.from_crs(src.crs, "EPSG:3857", always_xy=True)
        source_transform = src.transform

    def truth(xy):
        x, y = source_transform * (xy[:, 0], xy[:, 1])
        mx, my = to_mercator.transform(x, y)
        return np.column_stack(~transform * (np.asarray(mx), np.asarray(my)))

    return target, reference, truth


def true_rms(result, truth, size=(791, 718)):
    gx, gy = np.meshgrid(np.linspace(20, size[0] - 20, 20), np.linspace(20, size[1] - 20, 20))
    points = np.column_stack([gx.ravel(), gy.ravel()])
    return float(np.sqrt(np.mean(np.sum((result.model.apply(points) - truth(points)) ** 2, axis=1))))


def test_a_footprint_that_bends_across_projections_gets_the_second_order_model(mercator_pair):
    target, reference, truth = mercator_pair
    chosen = register(target, reference, "sift")
    linear = register(target, reference, "sift", options=RegisterOptions(model="affine"))
    assert chosen.options["model"] == "polynomial-2" and chosen.verified
    assert any(n.startswith("model polynomial-2 chosen by the check") for n in chosen.notes), chosen.notes
    assert chosen.verification.error_bound_px < linear.verification.error_bound_px
    # The affine model misses the projection's bend by about 1.2 px; the second order follows it.
    assert true_rms(linear, truth) > 0.8
    assert true_rms(chosen, truth) < 0.3


def test_a_model_the_user_chose_is_never_replaced(mercator_pair):
    target, reference, _ = mercator_pair
    result = register(target, reference, "sift", options=RegisterOptions(model="similarity"))
    assert result.options["model"] == "similarity"
    assert not any("polynomial-2" in n for n in result.notes)


def test_points_that_follow_the_linear_model_keep_it(demo_pair):
    result = register(demo_pair["target"], demo_pair["reference"], "sift")
    assert result.options["model"] == "affine" and result.verified
    assert not any("chosen by the check" in n for n in result.notes)


def verification(verdict, bound):
    return Verification(verdict, (), 3.0, 40, 20, 15, 0, 15, 0.01, 1e-9, 0.9, bound, bound, 0.1, 0.1,
                        np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0), np.zeros(0, bool), np.zeros(0, bool))


@pytest.mark.parametrize("linear, bent, kept", [
    (("verified", 1.6), ("verified", 0.4), True),
    (("verified", 0.4), ("verified", 0.5), False),
    (("suspect", 2.0), ("verified", 2.5), True),
    (("verified", 1.0), ("suspect", 0.2), False),
])
def test_the_check_keeps_the_model_it_bounds_better(linear, bent, kept):
    assert beats(verification(*bent), verification(*linear)) is kept


@pytest.mark.parametrize("f, d1, d2, tail", [(1.0, 6, 50, 0.435847688472), (10.0, 6, 48, 3.77313709234e-07),
                                             (0.5, 8, 100, 0.853642656038), (2.0, 4, 20, 0.133347650272),
                                             (0.0, 6, 10, 1.0)])
def test_the_f_tail_is_fishers(f, d1, d2, tail):
    assert f_tail(f, d1, d2) == pytest.approx(tail, rel=1e-9)  # scipy.special.fdtrc's values
