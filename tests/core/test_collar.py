"""Collars: a constant fill around the footprint, undeclared, is read as nodata and reported."""
import cv2
import numpy as np

from hamta.core.io.collar import find_collar
from hamta.core.io.raster import open_raster, read_image, resolve_bands


def _rotated_footprint(value=0, size=300, angle=25.0):
    rng = np.random.default_rng(2)
    img = cv2.GaussianBlur(rng.uniform(20, 230, (size, size)).astype(np.float32), (0, 0), 2)
    mask = np.zeros((size, size), np.uint8)
    box = cv2.boxPoints(((size / 2, size / 2), (0.7 * size, 0.6 * size), angle)).astype(np.int32)
    cv2.fillPoly(mask, [box], 1)
    return np.where(mask > 0, np.clip(img, 1, 254), value).astype(np.uint8), mask > 0


def test_a_border_connected_fill_is_found_and_an_inner_dark_patch_is_not():
    img, inside = _rotated_footprint()
    collar = find_collar(img[None], "uint8")
    assert collar.value == 0 and abs(collar.share - (1 - inside.mean())) < 0.01
    plain = np.full((100, 100), 90, np.uint8)
    plain[40:60, 40:60] = 0
    assert find_collar(plain[None], "uint8") is None


def test_a_map_s_white_background_reaching_the_border_is_not_a_collar():
    img = np.full((200, 200), 255, np.uint8)
    for k in range(0, 200, 40):  # building blocks between white streets
        img[k + 8:k + 32, :] = 200
    img[:, 95:105] = 255
    assert find_collar(img[None], "uint8") is None


def test_a_white_collar_is_found_too():
    img, _ = _rotated_footprint(value=255)
    assert find_collar(img[None], "uint8").value == 255


def test_collar_pixels_read_as_invalid_unless_nodata_is_declared(raster_writer):
    img, inside = _rotated_footprint()
    info = open_raster(raster_writer("collar.tif", img))
    assert info.collar == 0
    data, valid = read_image(info, resolve_bands(info, None))
    assert not valid[~inside].any() and valid[inside].mean() > 0.93
    declared = open_raster(raster_writer("declared.tif", img, nodata=0))
    assert declared.collar is None


def test_white_streets_of_a_web_map_reaching_the_border_are_not_a_collar(shared):
    """Six Optical-Map references of the multimodal set have white streets that reach the border in a few
    places; the rest of the map is then nearly the whole raster and convex, but the streets lie inside
    it, not around it. Read as a collar they took a third of each map (every near-white pixel)."""
    folder = shared / "data" / "multimodal" / "Optical-Map"
    for pair in (14, 23, 37, 45, 76, 77):
        assert open_raster(str(folder / f"pair{pair}_2.jpg")).collar is None


def test_the_collar_takes_the_ringing_beside_it_not_a_dark_area_that_reaches_it():
    img, inside = _rotated_footprint()
    img[inside & (np.arange(300)[:, None] > 200)] = 6  # a dark field (sea, shadow) from the collar inwards
    collar = find_collar(img[None], "uint8")
    dark = inside & (np.arange(300)[:, None] > 200)
    far = dark & (cv2.distanceTransform(inside.astype(np.uint8), cv2.DIST_L2, 3) > 12)
    assert collar is not None and far.sum() > 1000 and not collar.mask[far].any()
