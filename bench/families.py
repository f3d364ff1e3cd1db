"""The synthetic families of EVALUATION.md and the real development pairs, as benchmark cases.

Every case is generated deterministically from a named source image at a chosen size (the
reference's longest side in pixels) with a seed derived from its name. Sources: the Landsat
sample and the development images in ``../shared/data`` (real imagery), and the self-generated
farmland scene; a missing data folder falls back to the generated scene, with a note.
"""
from __future__ import annotations

import json
import math
import os
import zlib
from dataclasses import dataclass, field
from functools import lru_cache
from typing import List

import cv2
import numpy as np
from affine import Affine

from ..core.coords import apply_matrix, compose
from ..core.preprocess.sar import lee_filter
from . import collar, multimodal_set, trust
from .cases import Canvas, Case, read_canvas, reprojected_case, warped_case
from .nonrigid import Field, nonrigid_case
from .synthetic import make_landscape

FAMILIES = ("rotation", "scale", "affine", "overlap", "speckle", "multimodal", "georeferenced", "pairs", "crops",
            "should-fail", "collar") + tuple(multimodal_set.CATEGORIES) + ("large", "writing", "nonrigid", "batch",
                                                                          "basemap", "basemap-real", "basemap-dates",
                                                                          "speed", "years-apart", "basemap-requests",
                                                                          "scanned", "scanned-random",
                                                                          "scanned-random-tune")
# The real multimodal set (600 pairs), 'large' (a Sentinel-2-sized scene, ~1 GB of files), 'writing' (the
# output writer against gdalwarp, no registration cases of its own), 'nonrigid' (local distortion, for the
# local correction), 'batch' (throughput on a Dask cluster, no cases of its own) and 'basemap' (onto a local
# tile server, a study of its own: hamta.bench.goals.basemap; 'basemap-real' onto tiles of another date:
# hamta.bench.goals.basemap_real; 'basemap-dates' its held-out cases: hamta.bench.goals.basemap_dates),
# 'speed' (whole runs against each peer on
# its own ground: hamta.bench.goals.speed) and 'years-apart' (dates years apart, georeferencing moved:
# hamta.bench.goals.years_apart) and 'basemap-requests' (the requests a search sends on a layer with data
# everywhere: hamta.bench.goals.basemap_requests) and 'scanned' (sheets by their own printed grid:
# hamta.bench.goals.scanned) and 'scanned-random', 'scanned-random-tune' (sheets drawn at random, held-out and
# tuning seeds: hamta.bench.goals.scanned_random) run on request.
DEFAULT_FAMILIES = FAMILIES[:11]
GROUPS = {"multimodal-set": tuple(multimodal_set.CATEGORIES)}
SOURCE_FILES = {"landsat": "landsat/RGB.byte.tif", "multitemporal": "pairs/multitemporal_1.jpg",
                "sar": "pairs/sar-optical_1.jpg"}


@dataclass(frozen=True)
class CaseSpec:
    family: str
    name: str
    params: dict = field(default_factory=dict)

    @property
    def model(self) -> str:
        """The model a user would choose for this family's geometry."""
        return "projective" if self.family == "affine" and self.params.get("persp") else "affine"

    @property
    def seed(self) -> int:
        return zlib.crc32(f"{self.family}/{self.name}".encode())


def default_data_dir() -> str:
    """``$HAMTA_SHARED_DATA``, else ``shared/data`` beside the repository (or the installed package)."""
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    return os.environ.get("HAMTA_SHARED_DATA", os.path.join(os.path.dirname(repo), "shared", "data"))


# ----------------------------------------------------------------------------------------------
# Sources
# ----------------------------------------------------------------------------------------------

@lru_cache(maxsize=8)
def load_source(name: str, size: int, data_dir: str, upsample: bool = True) -> Canvas:
    """Source image ``name`` resized so that its longest side is ``size`` px (georeferencing kept
    or, for plain images, a nominal 10 m UTM 39N grid so that references are georeferenced).
    With ``upsample`` False a smaller image keeps its native size."""
    path = os.path.join(data_dir, SOURCE_FILES[name]) if name in SOURCE_FILES else None
    if path is None or not os.path.exists(path):
        return _landscape(size)
    canvas = read_canvas(path)
    if canvas.data.shape[0] == 3 and name != "landsat":
        canvas = Canvas(canvas.data.mean(axis=0, keepdims=True), canvas.valid, canvas.crs, canvas.transform,
                        canvas.dtype)
    return _resized(canvas, size if upsample else min(size, max(canvas.shape)))


def _landscape(size: int) -> Canvas:
    data = make_landscape((size, size), seed=7).astype(np.float32)
    return Canvas(data, np.ones((size, size), bool), "EPSG:32639", Affine(10.0, 0, 552000.0, 0, -10.0, 3620000.0))


def _resized(canvas: Canvas, size: int) -> Canvas:
    h, w = canvas.shape
    f = size / max(h, w)
    nw, nh = int(round(w * f)), int(round(h * f))
    interp = cv2.INTER_CUBIC if f > 1 else cv2.INTER_AREA
    data = np.stack([cv2.resize(b, (nw, nh), interpolation=interp) for b in canvas.data])
    valid = cv2.resize(canvas.valid.astype(np.uint8), (nw, nh), interpolation=cv2.INTER_NEAREST) > 0
    valid = cv2.erode(valid.astype(np.uint8), np.ones((5, 5), np.uint8)) > 0  # no interpolation fringe
    crs = canvas.crs or "EPSG:32639"
    tr = canvas.transform or Affine(10.0, 0, 552000.0, 0, -10.0, 3620000.0)
    tr = compose(tr, Affine.scale(w / nw, h / nh))
    return Canvas(data.astype(np.float32), valid, crs, tr, canvas.dtype)


# ----------------------------------------------------------------------------------------------
# Geometry and radiometry
# ----------------------------------------------------------------------------------------------

def target_matrix(target_shape, canvas_centre, *, angle_deg=0.0, scale=1.0, shear=0.0, aniso=1.0, persp=(0.0, 0.0),
                  shift=(0.0, 0.0)) -> np.ndarray:
    """Target px -> canvas px: about the target centre, ``scale`` target px per canvas px, rotation
    (clockwise as displayed), shear, anisotropy and a perspective term in 1/target-size units."""
    h, w = target_shape
    a = math.radians(angle_deg)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    lin = rot @ np.array([[1.0, shear], [0.0, 1.0]]) @ np.diag([aniso, 1.0 / aniso]) / scale
    centre_t = np.array([[1.0, 0, -w / 2.0], [0, 1.0, -h / 2.0], [0, 0, 1.0]])
    proj = np.eye(3)
    proj[:2, :2] = lin
    proj[2, :2] = np.asarray(persp, float) / max(h, w)
    to_canvas = np.array([[1.0, 0, canvas_centre[0] + shift[0]], [0, 1.0, canvas_centre[1] + shift[1]], [0, 0, 1.0]])
    return to_canvas @ proj @ centre_t


def gamma(g):
    return lambda v, rng: 255.0 * np.clip(v / 255.0, 0, 1) ** g


def gain_offset(a, b):
    return lambda v, rng: a * v + b


def speckle(looks, grain: float = 0.0):
    """Multiplicative speckle with ``looks`` looks on intensity; returns amplitude.

    ``grain`` = 0 gives independent Gamma speckle (the usual simulation). ``grain`` > 0 gives
    SAR-like correlated speckle: each look is the intensity of a circular complex Gaussian field
    smoothed by a Gaussian point spread function of that sigma (px), normalised to mean 1. The
    real SAR development image has a lag-1 speckle autocorrelation of about 0.55, which sigma 0.9
    reproduces (intensity autocorrelation exp(-d^2 / (2 sigma^2)) at lag d)."""
    def apply(v, rng):
        if grain > 0:
            mult = np.zeros(v.shape, np.float64)
            for _ in range(looks):
                for plane in mult.reshape(-1, *v.shape[-2:]):
                    z = [cv2.GaussianBlur(rng.standard_normal(v.shape[-2:]), (0, 0), grain) for _ in range(2)]
                    look = z[0] ** 2 + z[1] ** 2
                    plane += look / look.mean()
            mult /= looks
        else:
            mult = rng.gamma(looks, 1.0 / looks, size=v.shape)
        return np.sqrt(np.maximum(v, 0.0) ** 2 * mult).astype(np.float32)
    return apply


def despeckled(canvas: Canvas) -> Canvas:
    """The real SAR image's own (about 1-look) speckle removed by a 7 x 7 Lee filter on intensity
    (equivalent number of looks about 0.9 -> 6 in its homogeneous areas), so that the speckle
    added to each side is nearly independent, not a shared pattern that makes matching easy."""
    data = np.sqrt(np.stack([lee_filter(b * b, looks=1.0, window=7) for b in canvas.data]))
    return Canvas(data.astype(np.float32), canvas.valid, canvas.crs, canvas.transform, canvas.dtype)


def nonlinear(kind: str, looks=None):
    """Multimodal proxy: a non-linear intensity mapping (some invert contrast), then optional speckle."""
    maps = {
        "invert": lambda u: 1.0 - u,
        "sqrt-invert": lambda u: 1.0 - np.sqrt(u),
        "fold": lambda u: np.abs(u - 0.5) * 2.0,  # non-monotonic: dark and bright become alike
        "sigmoid-invert": lambda u: 1.0 / (1.0 + np.exp(12.0 * (u - 0.5))),
    }

    def apply(v, rng):
        u = np.clip(v / 255.0, 0, 1)
        out = 255.0 * maps[kind](u)
        return speckle(looks)(out, rng) if looks else out
    return apply


# ----------------------------------------------------------------------------------------------
# Families
# ----------------------------------------------------------------------------------------------

def family_specs(family: str, quick: bool = False) -> List[CaseSpec]:
    """The cases of ``family`` (a short subset with ``quick``)."""
    return _SPECS[family](quick)


def _rotation(quick):
    angles = (10, 90) if quick else (0, 10, 30, 45, 90, 135, 180)
    radios = ("none",) if quick else ("none", "gamma")
    sources = ("landsat",) if quick else ("landsat", "multitemporal")
    return [CaseSpec("rotation", f"{src}_rot{a}_{r}", {"source": src, "angle": a, "radiometry": r})
            for src in sources for a in angles for r in radios]


def _scale(quick):
    scales = (0.7, 1.4) if quick else (0.5, 0.7, 1.0, 1.4, 2.0)
    sources = ("landsat",) if quick else ("landsat", "landscape")
    return [CaseSpec("scale", f"{src}_scale{s}", {"source": src, "scale": s}) for src in sources for s in scales]


def _affine(quick):
    combos = [(0.05, 0.0), (0.10, 0.0), (0.15, 0.0), (0.05, 0.15), (0.10, 0.25), (0.15, 0.35)]
    combos = combos[2:3] if quick else combos
    return [CaseSpec("affine", f"{'landsat' if i % 2 == 0 else 'landscape'}_shear{sh}_persp{p}",
                     {"source": "landsat" if i % 2 == 0 else "landscape", "shear": sh, "persp": p})
            for i, (sh, p) in enumerate(combos)]


def _overlap(quick):
    fractions = (0.6,) if quick else (1.0, 0.9, 0.75, 0.6, 0.5)
    sources = ("landsat",) if quick else ("landsat", "multitemporal")
    return [CaseSpec("overlap", f"{src}_overlap{f}", {"source": src, "fraction": f})
            for src in sources for f in fractions]


SAR_GRAIN = 0.9  # px; see speckle()


def _speckle(quick):
    """Speckled pairs, independent speckle on each side. Landsat with independent Gamma speckle
    (the usual simulation); the real SAR image of the SAR-optical development pair, its own speckle
    averaged out, with SAR-like correlated speckle (``SAR_GRAIN``). Rotations up to 180 degrees and
    scales 0.6-1.6 make the hard cases where a detector's speckle handling matters."""
    geoms = ((30, 1.25),) if quick else ((10, 0.8), (30, 1.25), (75, 0.6), (120, 1.6), (180, 1.0), (160, 0.7))
    looks = (1,) if quick else (1, 4)
    sources = ("sar",) if quick else ("landsat", "sar")
    return [CaseSpec("speckle", f"{src}_L{L}_rot{a}_scale{s}",
                     {"source": src, "looks": L, "angle": a, "scale": s, "grain": SAR_GRAIN if src == "sar" else 0.0})
            for src in sources for L in looks for a, s in geoms]


def _multimodal(quick):
    kinds = ("invert",) if quick else ("invert", "sqrt-invert", "fold", "sigmoid-invert")
    sources = ("landsat",) if quick else ("landsat", "multitemporal")
    return [CaseSpec("multimodal", f"{src}_{k}", {"source": src, "mapping": k}) for src in sources for k in kinds]


def _georeferenced(quick):
    combos = [("landsat", "EPSG:4326", (35, -22)), ("landsat", "EPSG:3857", (-28, 40)),
              ("landsat", "EPSG:32617", (60, 15)), ("landscape", "EPSG:32640", (-45, -30)),
              ("landscape", "EPSG:4326", (25, 50)), ("landscape", "EPSG:3857", (-70, 10))]
    combos = combos[:1] if quick else combos
    return [CaseSpec("georeferenced", f"{src}_{crs.replace(':', '')}", {"source": src, "crs": crs, "shift": sh})
            for src, crs, sh in combos]


def _pairs(quick):
    return [CaseSpec("pairs", "multitemporal", {"pair": "multitemporal"}),
            CaseSpec("pairs", "sar_optical", {"pair": "sar_optical"})]


def _crops(quick):
    return [CaseSpec("crops", name, {"source": "landsat", "kind": name}) for name in trust.crop_names(quick)]


def _should_fail(quick):
    sources = ("landsat",) if quick else ("landsat", "multitemporal", "sar")
    return [CaseSpec("should-fail", f"{src}_{kind}", {"source": src, "kind": kind})
            for src in sources for kind in trust.should_fail_names(quick)]


def _collar(quick):
    return [CaseSpec("collar", name, {"case": name}) for name in collar.names(quick)]


def _multimodal_set(family):
    return lambda quick: [CaseSpec(family, str(i), {"pair": i}) for i in multimodal_set.pair_ids(quick)]


def _nonrigid(quick):
    sources = ("landsat",) if quick else ("landsat", "multitemporal", "landscape")
    kinds = (("smooth", 0),) if quick else (("smooth", 0), ("patches", 2))
    amplitudes = (3.0,) if quick else (2.0, 4.0)
    return [CaseSpec("nonrigid", f"{src}_{kind}_{a:g}px", {"source": src, "amplitude": a, "patches": n})
            for src in sources for kind, n in kinds for a in amplitudes]


def _large(quick):
    return [CaseSpec("large", "s2_10980px", {"source": "landscape", "size": 10980, "shift": (37, -21)})]


_SPECS = {"crops": _crops, "should-fail": _should_fail, "collar": _collar,
          **{f: _multimodal_set(f) for f in multimodal_set.CATEGORIES},
          "rotation": _rotation, "scale": _scale, "affine": _affine, "overlap": _overlap, "speckle": _speckle,
          "multimodal": _multimodal, "georeferenced": _georeferenced, "pairs": _pairs, "large": _large,
          "writing": lambda quick: [], "nonrigid": _nonrigid, "batch": lambda quick: [], "basemap": lambda quick: [],
          "basemap-real": lambda quick: [], "basemap-dates": lambda quick: [], "speed": lambda quick: [],
          "years-apart": lambda quick: [],
          "basemap-requests": lambda quick: [], "scanned": lambda quick: [],
          "scanned-random": lambda quick: [], "scanned-random-tune": lambda quick: []}


# ----------------------------------------------------------------------------------------------
# Building cases
# ----------------------------------------------------------------------------------------------

def build_case(spec: CaseSpec, folder: str, size: int, data_dir: str) -> Case:
    """Write the case's rasters into ``folder`` and return it."""
    p = spec.params
    rng = np.random.default_rng(spec.seed)
    name = f"{spec.family}_{spec.name}"
    if spec.family == "pairs":
        return _pair_case(p["pair"], data_dir)
    if spec.family in multimodal_set.CATEGORIES:
        return multimodal_set.build(spec.family, p["pair"], data_dir)
    if spec.family == "collar":
        return collar.build(folder, p["case"], data_dir)
    if spec.family == "large":
        return _large_case(folder, name, p["size"], p["shift"])
    if spec.family == "nonrigid":
        return nonrigid_case(folder, name, load_source(p["source"], size, data_dir), rng, p["amplitude"],
                             p["patches"])
    # Speckle lives at the sensor's resolution cell: an upsampled SAR image would carry it too fine.
    canvas = load_source(p["source"], size, data_dir, upsample=not (spec.family == "speckle" and p["source"] == "sar"))
    ch, cw = canvas.shape
    centre = (cw / 2.0, ch / 2.0)
    info = {"family": spec.family, **p}
    if spec.family == "georeferenced":
        return reprojected_case(folder, None, dst_crs=p["crs"], shift_px=p["shift"], name=name, canvas=canvas)
    if spec.family == "should-fail":
        return trust.build_should_fail(folder, name, p["kind"], canvas, spec.seed)
    if spec.family == "crops":
        return trust.build_crop(folder, name, p["kind"], canvas, spec.seed)
    if spec.family == "overlap":
        return _overlap_case(folder, name, canvas, p["fraction"], rng, info)
    shift = tuple(rng.uniform(-20, 20, 2))
    shape, kw, radio, dtype = (ch, cw), {}, None, None
    if spec.family == "rotation":
        kw = {"angle_deg": p["angle"]}
        radio = gamma(0.6) if p["radiometry"] == "gamma" else None
    elif spec.family == "scale":
        kw = {"angle_deg": float(rng.uniform(0, 30)), "scale": p["scale"]}
        shape = (int(round(ch * p["scale"])), int(round(cw * p["scale"])))
    elif spec.family == "affine":
        kw = {"angle_deg": float(rng.uniform(0, 20)), "scale": float(rng.uniform(0.85, 1.15)), "shear": p["shear"],
              "aniso": float(rng.uniform(0.9, 1.1)), "persp": tuple(rng.choice([-1, 1], 2) * p["persp"])}
        radio = gain_offset(float(rng.uniform(0.7, 1.3)), float(rng.uniform(-20, 20)))
    elif spec.family == "speckle":
        kw = {"angle_deg": p["angle"], "scale": p["scale"]}
        shape = (int(round(ch * p["scale"])), int(round(cw * p["scale"])))
        radio, dtype = speckle(p["looks"], p.get("grain", 0.0)), "float32"
    elif spec.family == "multimodal":
        kw = {"angle_deg": float(rng.uniform(0, 30)), "scale": float(rng.uniform(0.7, 1.4))}
        shape = (int(round(ch * kw["scale"])), int(round(cw * kw["scale"])))
        radio, dtype = nonlinear(p["mapping"], looks=1), "float32"
    info.update({k: v for k, v in kw.items()})
    g = target_matrix(shape, centre, shift=shift, **kw)
    ref_radio = speckle(p["looks"], p.get("grain", 0.0)) if spec.family == "speckle" else None
    if spec.family == "speckle" and p["source"] == "sar":
        canvas = despeckled(canvas)
    return warped_case(folder, name, canvas, g, shape, reference_radiometry=ref_radio, target_radiometry=radio,
                       dtype=dtype, seed=spec.seed, info=info)


def _overlap_case(folder, name, canvas, fraction, rng, info):
    """Reference and target are shifted crops of a larger canvas overlapping by ``fraction``."""
    ch, cw = canvas.shape
    rh, rw = int(0.6 * ch), int(0.6 * cw)
    c0, r0 = int(0.2 * cw), int(0.2 * ch)
    k = 1.0 - math.sqrt(fraction)
    dx, dy = rng.choice([-1, 1], 2) * np.array([k * rw, k * rh])
    angle = float(rng.uniform(0, 10))
    centre = (c0 + rw / 2.0 + dx, r0 + rh / 2.0 + dy)
    g = target_matrix((rh, rw), centre, angle_deg=angle)
    return warped_case(folder, name, canvas, g, (rh, rw), ref_window=(c0, r0, rw, rh), seed=int(rng.integers(1 << 30)),
                       info=dict(info, angle_deg=angle, shift=[float(dx), float(dy)]))


def _large_case(folder: str, name: str, size: int, shift) -> Case:
    """A Sentinel-2-sized pair: a ``size`` x ``size`` uint16 reference (10 m, UTM 39N) and an 8000 x 8000
    uint16 target inside it whose geotransform is off by ``shift`` target pixels and whose content
    is displaced by a smooth terrain-like field of up to 3 px (hills of 150-300 px): the memory- and
    time-bound case, for the global model and the local correction."""
    import rasterio
    from rasterio.windows import Window

    os.makedirs(folder, exist_ok=True)
    reference, target = os.path.join(folder, f"{name}_reference.tif"), os.path.join(folder, f"{name}_target.tif")
    tsize = min(8000, size - size // 8)
    off = (size - tsize) // 2
    field = Field((size, size), np.random.default_rng(11), 3.0, 0, hills=max(6, 6 * size * size // 1_000_000))
    truth = lambda p: np.asarray(p, float) + off + field(np.asarray(p, float) + off)  # noqa: E731
    gx, gy = np.meshgrid(np.linspace(50, tsize - 50, 25), np.linspace(50, tsize - 50, 25))
    case = Case(name, target, reference, truth, np.column_stack([gx.ravel(), gy.ravel()]),
                info={"family": "large", "size": size, "target_size": tsize, "georeferencing_error_px": list(shift),
                      "field_amplitude_px": 3.0})
    if os.path.exists(target) and os.path.exists(reference):
        return case
    base = make_landscape((size // 4, size // 4), seed=3).astype(np.float32)
    grey = 0.299 * base[0] + 0.587 * base[1] + 0.114 * base[2]
    rng = np.random.default_rng(5)
    full = np.clip(cv2.resize(grey, (size, size), interpolation=cv2.INTER_CUBIC) * 40
                   + rng.normal(0, 80, (size, size)).astype(np.float32), 1, 65535).astype(np.float32)
    tr = Affine(10.0, 0, 500000.0, 0, -10.0, 4000000.0)
    prof = dict(driver="GTiff", width=size, height=size, count=1, dtype="uint16", crs="EPSG:32639", transform=tr,
                tiled=True, blockxsize=512, blockysize=512, compress="deflate")
    with rasterio.open(reference, "w", **prof) as ref:
        for r0 in range(0, size, 1024):
            ref.write(full[r0:r0 + 1024].astype("uint16"), 1, window=Window(0, r0, size, min(1024, size - r0)))
    tgt_prof = dict(prof, width=tsize, height=tsize,
                    transform=compose(tr, Affine.translation(off + shift[0], off + shift[1])))
    with rasterio.open(target, "w", **tgt_prof) as tgt:
        for r0 in range(0, tsize, 512):
            rows = min(512, tsize - r0)
            d = field.dense(off, off + r0, tsize, rows)
            xx, yy = np.meshgrid(np.arange(tsize, dtype=np.float32) + off, np.arange(rows, dtype=np.float32) + off + r0)
            strip = cv2.remap(full, xx + d[..., 0], yy + d[..., 1], cv2.INTER_CUBIC, borderMode=cv2.BORDER_REFLECT)
            tgt.write(np.clip(strip, 1, 65535).astype("uint16"), 1, window=Window(0, r0, tsize, rows))
    return case


def _pair_case(pair_id: str, data_dir: str) -> Case:
    folder = os.path.join(data_dir, "pairs")
    with open(os.path.join(folder, "ground_truth.json")) as f:
        pair = next(p for p in json.load(f)["pairs"] if p["id"] == pair_id)
    pts = np.asarray(pair["points"], float)
    h = np.asarray(pair["H_a_to_b"], float)
    return Case(f"pairs_{pair_id}", os.path.join(folder, pair["a"]), os.path.join(folder, pair["b"]),
                lambda p: apply_matrix(h, p), pts[:, :2], pts[:, 2:], float(pair.get("success_tol_px", 3.0)),
                info={"family": "pairs", "modality": pair.get("modality"), "confidence_px": pair.get("confidence_px")})


def available(family: str, data_dir: str) -> bool:
    """Whether a family can run (the real pairs need the data folder)."""
    if family in ("pairs", "collar"):
        return os.path.exists(os.path.join(data_dir, "pairs", "ground_truth.json"))
    if family in multimodal_set.CATEGORIES:
        return multimodal_set.available(data_dir, family)
    if family == "basemap":  # tiles cut from the Landsat sample, no fallback
        return os.path.exists(os.path.join(data_dir, SOURCE_FILES["landsat"]))
    if family == "basemap-real":  # real images of several dates
        from .goals.basemap_real import available as real_available

        return real_available(data_dir)
    if family == "basemap-dates":  # the held-out dates, windows and files of the same images
        from .goals.basemap_dates import available as dates_available

        return dates_available(data_dir)
    if family == "years-apart":
        from .goals.years_apart import available as years_available

        return years_available(data_dir)
    if family == "basemap-requests":
        from .goals.basemap_requests import available as requests_available

        return requests_available(data_dir)
    if family == "scanned":
        from .goals.scanned import available as scanned_available

        return scanned_available(data_dir)
    return True


