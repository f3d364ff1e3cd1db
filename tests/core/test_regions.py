"""Regions as control points (issue 56, a scanned map onto a reference): the regions found, their constellation
matched under any turn and scale, and a map drawn from real water registered onto that water as a layer."""
import numpy as np
import pytest

from hamta.core.detectors.regions import find_regions
from hamta.core.matching.constellation import match_constellation


def _blobs(size=600, seed=0):
    """A grey image of 25 dark irregular blobs apart, at random places on a bright ground, and their centres
    (corner convention)."""
    import cv2

    rng = np.random.default_rng(seed)
    img = np.full((size, size), 200, np.uint8)
    centres = np.zeros((0, 2))
    while len(centres) < 25:
        c = rng.uniform(50, size - 50, 2)
        if not len(centres) or np.hypot(*(centres - c).T).min() > 75:
            centres = np.vstack([centres, c])
    for c in centres:
        angles = np.linspace(0, 2 * np.pi, 12, endpoint=False)
        radius = rng.uniform(6, 22) * rng.uniform(0.6, 1.4, 12)
        outline = c + np.column_stack([np.cos(angles), np.sin(angles)]) * radius[:, None] - 0.5
        cv2.fillPoly(img, [np.round(outline * 16).astype(np.int32)], 60, shift=4)
    return img.astype(np.float32), centres


def _turned(img, angle_deg, scale):
    import cv2

    h, w = img.shape
    m = cv2.getRotationMatrix2D((w / 2 - 0.5, h / 2 - 0.5), angle_deg, scale)
    out = cv2.warpAffine(img, m, (w, h), flags=cv2.INTER_LINEAR, borderValue=200)
    corner = m.copy()  # the same map in corner coordinates
    corner[:, 2] += 0.5 - m[:, :2] @ [0.5, 0.5]
    return out, corner


def test_regions_are_found_once_each_with_their_centroid_and_side():
    img, centres = _blobs()
    found = find_regions(img, np.ones(img.shape, bool))
    dark = found.subset(found.dark & (found.area > 50))
    offset = np.hypot(*(dark.xy[:, None] - centres[None]).transpose(2, 0, 1))
    per_blob = np.bincount(np.argmin(offset, axis=1), minlength=25)
    assert per_blob.min() >= 1 and per_blob.max() <= 2  # a spiky outline blurred can be cut twice
    assert np.median(np.min(offset, axis=1)) < 4.0
    assert not dark.blocky.any()


def test_a_grid_cell_is_blocky():
    img = np.full((600, 600), 220, np.float32)
    img[:, 100::100] = img[100::100, :] = 40
    found = find_regions(img, np.ones(img.shape, bool))
    cells = found.subset(~found.dark & (found.area > 5000))
    assert len(cells) and cells.blocky.all()


@pytest.mark.parametrize("angle, scale", [(0.0, 1.0), (37.0, 0.6), (-120.0, 1.5)])
def test_the_constellation_is_found_at_any_turn_and_scale(angle, scale):
    img, _ = _blobs(seed=1)
    other, matrix = _turned(img, angle, scale)
    t = find_regions(img, np.ones(img.shape, bool))
    r = find_regions(other, np.ones(other.shape, bool))
    found = match_constellation(t.subset(~t.blocky), r)
    assert found is not None and len(found.target) >= 8
    probe = np.array([[200.0, 200.0], [400.0, 300.0], [300.0, 450.0]])
    got = probe @ found.matrix[:, :2].T + found.matrix[:, 2]
    want = probe @ matrix[:, :2].T + matrix[:, 2]
    assert np.abs(got - want).max() < 1.5


def test_unrelated_blobs_bring_few_regions_together():
    a, _ = _blobs(seed=2)
    b, _ = _blobs(seed=3)
    t, r = find_regions(a, np.ones(a.shape, bool)), find_regions(b, np.ones(b.shape, bool))
    found = match_constellation(t.subset(~t.blocky), r)
    assert found is None or len(found.target) < 8


@pytest.fixture(scope="module")
def water_map(shared, tmp_path_factory):
    from hamta.bench.water_map import draw

    folder = tmp_path_factory.mktemp("water_map")
    return draw(str(shared / "data"), "20160816", str(folder / "map.jpg"), 6.0, 25.0), folder


@pytest.mark.parametrize("layer", ["water", "water-mirrored"])
def test_a_map_is_placed_on_its_water_layer_and_refused_on_the_layer_mirrored(shared, water_map, layer):
    from hamta.bench.water_map import AREA, write_reference
    from hamta.core.errors import HamtaError
    from hamta.core.pipeline import register

    sheet, folder = water_map
    reference = write_reference(str(shared / "data"), "20160816", str(folder / f"{layer}.tif"), layer)
    try:
        result = register(sheet.path, reference, method="regions")
    except HamtaError:
        assert layer == "water-mirrored"
        return
    if layer == "water-mirrored":
        assert not result.verified
        return
    assert result.verified
    canvas = np.array([[0.2, 0.2], [0.8, 0.3], [0.5, 0.8]]) * np.array(AREA[2:]) * sheet.zoom
    full = np.vstack([sheet.matrix, [0, 0, 1]])
    scan = (canvas - full[:2, 2]) @ np.linalg.inv(full[:2, :2]).T
    assert np.abs(result.model.apply(scan) - sheet.to_reference(scan)).max() < 1.0
