"""The random family of scanned sheets (:mod:`hamta.bench.random_sheets`): a seed gives the same bytes, the
truth lies on the printed ink, hints lie near the truth, 200 seeds draw every class of sheet, and each label
sits beside its own line. Scan px throughout (x = column, y = row, origin at the top-left pixel's corner)."""
import collections
import os

import numpy as np
import pytest

from hamta.bench.random_sheets import GEO_FORMATS, GRID_FORMATS, HERSHEY_FONTS, PROJECTIONS, draw_spec, render_random

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data")
SPECS = [draw_spec(seed) for seed in range(200)]


def _data_dir():
    """The development data where present, else None (the sheets' content is then a generated texture)."""
    return DATA if os.path.isdir(DATA) else None


def _ink_distance(sheet) -> np.ndarray:
    """How far each scan px's colour is from the grid's ink (RGB distance)."""
    import cv2

    rgb = cv2.imread(sheet.path, cv2.IMREAD_COLOR)[..., ::-1].astype(np.float32)
    return np.linalg.norm(rgb - np.asarray(sheet.spec.ink, np.float32), axis=2)


def _luma(rgb) -> float:
    return float(np.dot(rgb, [0.299, 0.587, 0.114]))


def _small(spec) -> bool:
    """Whether the sheet's face is at most about 1600 px on its long side (cheap to render)."""
    return max(spec.face_cells) * spec.step / spec.pixel_size * (1 if spec.kind == "grid" else 111e3) < 1600


def _seeds(accept, n):
    return [s.seed for s in SPECS if accept(s)][:n]


@pytest.fixture(scope="module")
def rendered(tmp_path_factory):
    folder = tmp_path_factory.mktemp("random_sheets")
    cache = {}

    def get(seed):
        if seed not in cache:
            cache[seed] = render_random(seed, str(folder), _data_dir())
        return cache[seed]

    return get


def _strong_lines(spec) -> bool:
    return (spec.style == "lines" and _luma(spec.paper) - _luma(spec.ink) > 110 and spec.line_px >= 1.0
            and spec.noise < 6 and _small(spec))


def test_the_same_seed_renders_the_same_bytes(tmp_path):
    seed = _seeds(lambda s: _small(s) and s.labelled, 1)[0]
    a = render_random(seed, str(tmp_path / "a"), _data_dir())
    b = render_random(seed, str(tmp_path / "b"), _data_dir())
    with open(a.path, "rb") as fa, open(b.path, "rb") as fb:
        assert fa.read() == fb.read()
    assert a.labels == b.labels and a.spec == b.spec
    assert draw_spec(seed) == a.spec


@pytest.mark.parametrize("seed", _seeds(_strong_lines, 3))
def test_the_truth_lies_on_the_printed_lines(rendered, seed):
    """Midway between crossings the scan's colour is nearer the ink's on the lines than half a step away, and
    across each line the ink's centre lies on the truth to a fraction of a px."""
    sheet = rendered(seed)
    distance, step = _ink_distance(sheet), sheet.spec.step
    nodes = sheet.nodes()
    across = np.linspace(-6, 6, 49)
    on, off, centres = [], [], []
    for dx, dy in ((0, 0.5), (0.5, 0)):
        mid = nodes + [dx * step, dy * step]
        at = sheet.to_scan(mid)
        ahead = sheet.to_scan(mid + np.array([dx, dy]) * step * 1e-3)  # along the line
        normal = (ahead - at)[:, ::-1] * [1, -1]
        normal /= np.hypot(*normal.T)[:, None]
        on.append(_sample(distance, at))
        off.append(_sample(distance, sheet.to_scan(nodes + 0.5 * step)))
        profiles = _sample(distance, (at[:, None, :] + across[None, :, None] * normal[:, None, :]).reshape(-1, 2))
        centres.append(_ink_centre(profiles.reshape(len(at), len(across)), across))
    on, off, centres = (np.concatenate(v) for v in (on, off, centres))
    assert np.isfinite(on).sum() > 20 and np.isfinite(centres).sum() > 20
    assert np.nanmedian(on) < np.nanmedian(off) - 25
    assert abs(np.nanmedian(centres)) < 0.2 and np.nanmedian(np.abs(centres)) < 0.5


def _ink_centre(profiles, across) -> np.ndarray:
    """Where the ink lies across each profile of distances to the ink's colour (px from its middle; NaN where
    a profile leaves the scan or shows no line)."""
    ends = np.concatenate([profiles[:, :6], profiles[:, -6:]], axis=1)
    weight = np.clip(np.median(ends, axis=1)[:, None] - profiles, 0, None)
    weight[:, np.abs(across) > 4] = 0
    total = weight.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(total > 0, (weight * across).sum(axis=1) / total, np.nan)


def _sample(image, xy) -> np.ndarray:
    """The image's value at each point (scan px), interpolated between pixel centres (NaN off the image)."""
    import cv2

    flat = np.asarray(xy, np.float32).reshape(-1, 1, 2) - 0.5
    ok = np.all(np.isfinite(flat), axis=2)
    flat[~ok] = -10
    out = cv2.remap(image, flat[..., 0], flat[..., 1], cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT,
                    borderValue=np.nan)[:, 0].astype(float)
    out[~ok[:, 0]] = np.nan
    return out


def test_hints_lie_near_the_truth_on_crossings(rendered):
    seed = _seeds(_strong_lines, 1)[0]
    sheet = rendered(seed)
    rows = sheet.hints(6, seed=11, noise_px=3.0)
    assert rows.shape == (6, 4)
    assert np.all(np.hypot(*(rows[:, :2] - sheet.to_scan(rows[:, 2:])).T) <= 3.0 + 1e-9)
    steps = rows[:, 2:] / sheet.spec.step
    assert np.allclose(steps, np.round(steps), atol=1e-6)
    assert len({tuple(r) for r in rows[:, 2:]}) == 6
    h, w = sheet.shape
    assert np.all((rows[:, 0] > 20) & (rows[:, 0] < w - 20) & (rows[:, 1] > 20) & (rows[:, 1] < h - 20))
    assert np.array_equal(rows, sheet.hints(6, seed=11, noise_px=3.0))


def _classes(spec) -> list:
    """Every class a spec belongs to, as (family, class)."""
    crs = spec.sheet_crs
    if crs.startswith("EPSG:326") or crs.startswith("EPSG:327"):
        crs = "utm north" if crs.startswith("EPSG:326") else "utm south"
    out = [("kind", spec.kind), ("sheet_crs", crs), ("style", spec.style), ("neatline", spec.neatline),
           ("label step", f"{round(spec.label_step / spec.step)}x"), ("file", "png" if spec.jpeg == 0 else "jpeg"),
           ("scanner margin", "wide" if spec.scanner_margin > 20 else "tight"), ("labelled", spec.labelled),
           ("turn", _turn_class(spec.angle_deg)), ("fold", spec.fold is not None),
           ("corner", spec.corner is not None)]
    if spec.kind == "graticule":
        out.append(("projection", spec.projection.split()[0][6:]))
    if spec.labelled:
        edges = spec.label_edges
        pair = "opposite" if set(edges) in ({"top", "bottom"}, {"left", "right"}) else "adjacent"
        which = f"{len(edges)} {pair}" if len(edges) == 2 else f"{len(edges)}"
        out += [("format", spec.label_format), ("abbreviated", spec.label_abbrev),
                ("placement", spec.label_placement), ("edges", which),
                ("font", "hershey" if spec.label_font in HERSHEY_FONTS else "truetype"),
                ("dark band", spec.label_dark_band), ("boxed", spec.label_boxed)]
        if {"left", "right"} & set(edges):
            out.append(("side labels turned", spec.label_turn))
    return out


def _turn_class(angle) -> str:
    if abs(angle) <= 3:
        return "within 3 deg"
    if min(abs(abs(angle) - 90), abs(abs(angle) - 180)) <= 2:
        return "near 90/180/270"
    return "any"


def test_two_hundred_seeds_draw_every_class():
    counts = collections.Counter(c for spec in SPECS for c in _classes(spec))
    expected = {"kind": ("graticule", "grid"), "style": ("lines", "crosses", "ticks", "none"),
                "sheet_crs": ("EPSG:4326", "EPSG:4269", "utm north", "utm south", "EPSG:2154", "EPSG:27700",
                              "EPSG:3857", "EPSG:2263", "EPSG:27291"),
                "projection": PROJECTIONS, "format": GEO_FORMATS + GRID_FORMATS, "abbreviated": (True, False),
                "placement": ("outside", "inside", "between"), "edges": ("1", "2 opposite", "2 adjacent", "4"),
                "font": ("truetype", "hershey"), "dark band": (True, False), "boxed": (True, False),
                "labelled": (True, False), "neatline": ("lines", "rectangle"), "label step": ("1x", "2x", "5x"),
                "file": ("png", "jpeg"), "scanner margin": ("wide", "tight"),
                "turn": ("within 3 deg", "near 90/180/270", "any"), "fold": (True, False),
                "corner": (True, False), "side labels turned": (0, 90, -90)}
    for family in expected:
        print(family, {c: n for (f, c), n in sorted(counts.items(), key=str) if f == family})
    missing = [(f, c) for f, classes in expected.items() for c in classes if counts[(f, c)] == 0]
    assert not missing
    assert 0.35 < counts[("kind", "graticule")] / len(SPECS) < 0.7
    assert 0.04 < counts[("style", "none")] / len(SPECS) < 0.14


def test_specs_are_plain_values_within_their_ranges():
    import json
    from dataclasses import asdict

    for spec in SPECS:
        assert 3 <= min(spec.face_cells) and max(spec.face_cells) < 12
        assert 7 <= spec.glyph_px <= 45 and 0.6 <= spec.line_px <= 3.5
        assert round(spec.label_step / spec.step) in (1, 2, 5, 10)
        assert json.loads(json.dumps(asdict(spec)))["seed"] == spec.seed


def _labelled(spec) -> bool:
    return spec.labelled and _small(spec) and len(spec.label_edges) >= 2


LABELLED = sorted({*_seeds(lambda s: _labelled(s) and s.kind == "graticule", 1),
                   *_seeds(lambda s: _labelled(s) and s.kind == "grid" and abs(s.angle_deg) > 3, 1),
                   *_seeds(lambda s: _labelled(s) and s.label_placement == "between", 1),
                   *_seeds(lambda s: _labelled(s) and s.label_placement == "inside", 1),
                   *_seeds(lambda s: _labelled(s) and s.label_turn and {"left", "right"} & set(s.label_edges), 1)})


@pytest.mark.parametrize("seed", LABELLED)
def test_each_label_sits_beside_its_own_line(rendered, seed):
    """The line a label names passes within one label width of the label's centre on the scan, no other line
    of its axis passes closer, and a full label prints its line's degrees or its value."""
    import re

    sheet = rendered(seed)
    assert sheet.labels
    step = sheet.spec.step
    nodes = sheet.nodes()
    lo, hi = nodes.min(axis=0) - 3 * step, nodes.max(axis=0) + 3 * step
    for label in sheet.labels:
        axis, xy = label["axis"], np.asarray(label["xy"])
        distance = {}
        for k in range(-2, 3):
            t = np.linspace(lo[1 - axis], hi[1 - axis], 800)
            pts = np.empty((len(t), 2))
            pts[:, axis], pts[:, 1 - axis] = label["value"] + k * step, t
            distance[k] = _to_polyline(xy, sheet.to_scan(pts))
        assert distance[0] <= max(label["size"]), label
        assert distance[0] == min(distance.values()), label
        if label["full"] and sheet.spec.kind == "graticule":
            assert int(re.findall(r"\d+", label["text"])[0]) == round(abs(label["value"]) * 3600) // 3600, label
        elif sheet.spec.label_format == "full":
            assert label["text"] == str(round(label["value"])), label


def _to_polyline(p, line) -> float:
    line = line[np.all(np.isfinite(line), axis=1)]
    a, b = line[:-1], line[1:]
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-12), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * d - p).T)))
