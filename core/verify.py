"""Independent verification: does the returned model really align the two rasters?

A registration is presented as a success only after this check, which never looks at the
correspondences the model was fitted on. At sites on a regular grid over the overlap (chosen by
position alone), a reference template is compared with the target resampled through the model,
at full resolution, by normalised cross-correlation of CFOG structural descriptors (gradient
orientations: modality-independent, blind to contrast inversion) over a small search range.

Where the model is right, sites with structure peak near zero offset; where it is wrong, peaks
scatter. Comparing each template with the target at *other* sites gives, for this very pair, what
wrong alignments yield: how high chance peaks get and how often one lands near zero. The verdict
asks for (1) more sites near zero than chance explains (a binomial tail at that rate), (2) few
sites with a clear peak elsewhere, (3) agreeing sites spread over the overlap, and (4) an error
field fitted to the agreeing sites' offsets (their mean, a similarity or an affine trend,
depending on how many there are) whose RMS over the overlap, plus two standard errors, is within
the accuracy asked for. Local scatter (parallax, change, modality) widens the bound; a systematic
error shows in the field.

Coordinates: sites, offsets and tolerances are full-resolution reference pixels (corner convention).

References
----------
Ye, Y., Bruzzone, L., Shan, J., Bovolo, F., & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11), 9059-9070 (CFOG).
Scheffler, D., Hollstein, A., Diedrich, H., Segl, K., & Hostert, P. (2017). AROSICS. Remote
Sensing 9(7), 676 (reliability of local shifts, checked after de-shifting).
"""
from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass, field, replace
from typing import Optional, Tuple

import cv2
import numpy as np
from rasterio.windows import Window
from shapely.geometry import Point, Polygon, box
from shapely.prepared import prep

from .coords import raster_outline
from .descriptors.cfog import cfog, peak_offset
from .estimation.models import local_jacobian
from .io.raster import RasterInfo, open_dataset, read_image
from .progress import Monitor

VERDICTS = ("verified", "suspect", "failed")
NULL_PARTNERS = 4  # other sites' target content each template is also compared with (wrong alignments)
NULL_TURNS = 3  # and, turned or mirrored (rot180, mirror x, mirror y), with the first three of those again


@dataclass(frozen=True)
class VerifyParams:
    """Settings of the verification (full-resolution reference pixels).

    Attributes
    ----------
    tolerance_px : float
        The accuracy asked for: a verified model's estimated error bound is within it.
    template_px, max_template_px : int
        Smallest and largest side of a site's reference template; between them, the side that fits
        about ``target_sites`` sites into the overlap (more pixels per site help weak pairs).
    target_sites, max_sites : int
        See above; at most ``max_sites`` sites, on a grid whose spacing is at least one template
        (sites do not overlap, so they are independent evidence).
    agree_px : float
        Largest offset of an agreeing site; the tolerance, within 2 and 6 px (real pairs scatter
        by a few px from parallax and change; the systematic error is bounded separately).
    min_agree : int
        Fewest agreeing sites for a verified result (the error field is fitted to them).
    max_chance : float
        Significance by peaks: the largest probability that so many agreeing sites arise from
        wrong alignments (binomial tail at this pair's chance rate).
    max_z_chance, max_rank_chance : float
        Significance by zero-offset lift, the alternative for weak modality pairs: the largest
        probability that so many sites lift their zero-offset correlation above 95 % of chance
        sites (binomial tail at 5 %), and the largest Mann-Whitney p-value of the sites' lifts
        against chance; both must hold.
    max_contradict : float
        Largest share of clear sites (peak above 90 % of chance peaks) whose peak is elsewhere;
        contradicting sites that share one error field bound the model's error instead (see
        :func:`shared_error`).
    min_coverage : float
        Smallest share of the measured sites' extent spanned by agreeing sites, in each axis.
    """

    tolerance_px: float = 3.0
    template_px: int = 40
    max_template_px: int = 96
    target_sites: int = 25
    max_sites: int = 36
    min_agree: int = 3
    max_chance: float = 1e-5
    max_z_chance: float = 1e-6
    max_rank_chance: float = 1e-3
    max_contradict: float = 0.4
    min_coverage: float = 0.4

    @property
    def agree_px(self) -> float:
        return min(max(self.tolerance_px, 2.0), 6.0)

    @property
    def search_px(self) -> int:
        return max(8, int(math.ceil(2 * self.agree_px)))


@dataclass(frozen=True, eq=False)
class Verification:
    """The verdict and its evidence.

    ``verdict`` is 'verified', 'suspect' (evidence of alignment, but not enough, or not within the
    tolerance) or 'failed' (nothing supports the model). Site arrays (reference px): ``sites_xy``,
    measured ``offset_xy`` (NaN where no interior peak), ``peak`` (NCC), ``agree``, ``contradict``.
    """

    verdict: str
    reasons: Tuple[str, ...]
    tolerance_px: float
    template_px: int
    n_sites: int
    n_agree: int
    n_contradict: int
    n_clear: int
    chance_rate: float
    chance: float
    coverage: float
    error_px: Optional[float]
    error_bound_px: Optional[float]
    scatter_px: Optional[float]
    time_s: float
    sites_xy: np.ndarray = field(repr=False)
    offset_xy: np.ndarray = field(repr=False)
    peak: np.ndarray = field(repr=False)
    agree: np.ndarray = field(repr=False)
    contradict: np.ndarray = field(repr=False)
    z_hits: int = 0
    z_chance: float = 1.0
    z_mw: float = 1.0
    corroboration: Optional[dict] = None

    @property
    def verified(self) -> bool:
        return self.verdict == "verified"

    def to_dict(self) -> dict:
        """The ``quality`` section of ``report.json`` (see docs/report.md)."""
        def num(v):
            return None if v is None or not np.isfinite(v) else float(v)

        return {"verdict": self.verdict, "reasons": list(self.reasons), "check": "cfog-sites",
                "tolerance_px": self.tolerance_px, "template_px": self.template_px, "n_sites": self.n_sites,
                "n_agree": self.n_agree, "n_contradict": self.n_contradict, "n_clear": self.n_clear,
                "chance_rate": self.chance_rate, "chance_probability": self.chance, "coverage": self.coverage,
                "estimated_error_px": num(self.error_px), "error_bound_px": num(self.error_bound_px),
                "local_scatter_px": num(self.scatter_px), "time_s": self.time_s, "z_hits": self.z_hits,
                "z_chance": self.z_chance, "z_mw": self.z_mw, "corroboration": self.corroboration,
                "sites": [{"reference_px": [float(x), float(y)],
                           "offset_px": None if not np.isfinite(o).all() else [float(o[0]), float(o[1])],
                           "peak": num(p), "agree": bool(a), "contradict": bool(c)}
                          for (x, y), o, p, a, c in zip(self.sites_xy, self.offset_xy, self.peak, self.agree,
                                                        self.contradict)]}


def verify(model, target: RasterInfo, target_bands, reference: RasterInfo, reference_bands,
           params: VerifyParams = VerifyParams(), monitor: Optional[Monitor] = None) -> Verification:
    """Check ``model`` (target px -> reference px, any model type) against the pixels of both rasters.

    Parameters
    ----------
    model
        The registration's final model.
    target, reference : RasterInfo
        The rasters, read through windows at full resolution.
    target_bands, reference_bands : tuple of int
        The bands (or RGB triple) that were matched.
    """
    t0 = time.perf_counter()
    monitor = monitor or Monitor()
    outline = footprint(model, target)
    overlap = _overlap(outline, reference)
    side = template_side(overlap, params)
    sites = site_grid(outline, overlap, reference, side, params)
    tmpls, patches = [], []
    with open_dataset(target) as tds, open_dataset(reference) as rds:
        for i, p in enumerate(sites):
            pair = _read_site(model, p, target, target_bands, tds, reference, reference_bands, rds, side,
                              params.search_px)
            tmpls.append(None if pair is None else pair[0])
            patches.append(None if pair is None else pair[1])
            if i % 8 == 0:
                monitor.report(0.5 * i / max(len(sites), 1), "verifying")
    n = len(sites)
    columns = 1 + NULL_PARTNERS + NULL_TURNS
    offsets = np.full((n, columns, 2), np.nan)
    peaks = np.full((n, columns), np.nan)
    zero_z = np.full((n, columns), np.nan)
    shape = (side + 2 * params.search_px,) * 2
    stacks = tmpls
    tmpls = [None if t is None else _TemplateSpectrum(t, shape) for t in stacks]
    patches = [None if p is None else _SearchSpectrum(p, side) for p in patches]
    usable = [i for i in range(n) if tmpls[i] is not None and patches[i] is not None]
    for rank, i in enumerate(usable):
        m = len(usable)
        step = max(m // (NULL_PARTNERS + 1), 1)
        others = [usable[(rank + k * step) % m] for k in range(1, NULL_PARTNERS + 1)]
        pairs = [(i, tmpls[i])] + [(j, tmpls[i]) for j in others]
        pairs += [(j, _TemplateSpectrum(t, shape)) for j, t in zip(others, _turned(stacks[i]))]
        for c, (j, template) in enumerate(pairs):
            if c > 0 and j == i:
                continue
            surface = patches[j].ncc(template, params.search_px)
            zero_z[i, c] = _zero_score(surface, params.search_px)
            offset, peak = peak_offset(surface, params.search_px)
            peaks[i, c] = peak
            if offset is not None:
                offsets[i, c] = offset
        if rank % 8 == 0:
            monitor.report(0.5 + 0.5 * rank / max(len(usable), 1), "verifying")
    monitor.report(1.0, "verifying")
    extent = overlap_grid(overlap)
    return judge(sites, offsets, peaks, zero_z, extent, replace(params, template_px=side), time.perf_counter() - t0)


def _turned(stack: np.ndarray):
    """The CFOG template turned by 180 degrees and mirrored in x and in y, its orientation channels
    following (orientations are modulo 180 degrees, so a half turn keeps them; a mirror reverses them)."""
    reverse = np.r_[0, np.arange(len(stack) - 1, 0, -1)]
    return (stack[:, ::-1, ::-1], stack[reverse][:, :, ::-1], stack[reverse][:, ::-1, :])


class _TemplateSpectrum:
    """A (C, t, t) descriptor template, zero-mean over all channels, as the spectrum of its
    zero-padded ``shape`` canvas, with its norm."""

    def __init__(self, template: np.ndarray, shape):
        t = template - template.mean()
        self.norm = float(np.sqrt((t ** 2).sum()))
        self.spectrum = np.conj(np.fft.rfft2(t, shape, axes=(1, 2)))
        self.size = template.size


class _SearchSpectrum:
    """A (C, t + 2s, t + 2s) descriptor search area as spectra, with its window sums for NCC."""

    def __init__(self, search: np.ndarray, side: int):
        self.spectrum = np.fft.rfft2(search, axes=(1, 2))
        self.shape = search.shape[1:]
        w = (side, side)
        self.s1 = cv2.boxFilter(search.sum(axis=0), -1, w, normalize=False, anchor=(0, 0),
                                borderType=cv2.BORDER_CONSTANT)
        self.s2 = cv2.boxFilter((search ** 2).sum(axis=0), -1, w, normalize=False, anchor=(0, 0),
                                borderType=cv2.BORDER_CONSTANT)

    def ncc(self, template: "_TemplateSpectrum", s: int) -> np.ndarray:
        """(2s + 1, 2s + 1) normalised cross-correlation surface (as :func:`ncc_surface`)."""
        num = np.fft.irfft2((self.spectrum * template.spectrum).sum(axis=0), self.shape)[:2 * s + 1, :2 * s + 1]
        s1, s2 = self.s1[:2 * s + 1, :2 * s + 1], self.s2[:2 * s + 1, :2 * s + 1]
        var = np.maximum(s2 - s1 ** 2 / template.size, 0.0)
        return num / np.maximum(np.sqrt(var) * template.norm, 1e-9)


def _zero_score(surface: np.ndarray, s: int) -> float:
    """How far the correlation at zero offset stands above the surface's values 4 px or more away
    (in their standard deviations)."""
    yy, xx = np.mgrid[-s:s + 1, -s:s + 1]
    ring = surface[np.maximum(np.abs(xx), np.abs(yy)) >= 4]
    return float((surface[s, s] - ring.mean()) / max(float(ring.std()), 1e-6))


def judge(sites, offsets, peaks, zero_z, extent, params: VerifyParams, elapsed: float = 0.0) -> Verification:
    """The verdict from per-site results: ``offsets`` (n, 1 + k, 2) and ``peaks`` (n, 1 + k) of each
    site's template against the target at its own site (column 0) and at k other sites (chance).
    ``extent`` (m, 2) are points over the overlap where the error field is evaluated."""
    measured = np.isfinite(peaks[:, 0])
    n = int(measured.sum())
    null_valid = np.isfinite(peaks[:, 1:])
    null_peaks = peaks[:, 1:][null_valid]
    clear_level, floor = (np.quantile(null_peaks, [0.9, 0.5]) if len(null_peaks) >= 8 else (1.0, 1.0))
    near = np.linalg.norm(np.nan_to_num(offsets, nan=1e9), axis=2) <= params.agree_px
    peak = np.nan_to_num(peaks, nan=-1.0)
    # A site agrees when its peak (not the weakest half of chance peaks) is near zero offset; it
    # contradicts when a clear peak (above 90 % of chance peaks) lies elsewhere.
    agree_all = near & (peak >= floor)
    agree, contradict = agree_all[:, 0], ~near[:, 0] & (peak[:, 0] >= clear_level) & measured
    # Chance rates from the mismatched sites, floored by what uniformly placed chance peaks give:
    # half pass the floor and land in the agreement disc so often; a tenth are clear, and so few
    # of those land within 1 px (precise agreement: strong evidence from few sites).
    cells = (2 * params.search_px + 1) ** 2
    rate = _rate(agree_all[:, 1:], null_valid, 0.5 * math.pi * params.agree_px ** 2 / cells)
    precise_all = (np.linalg.norm(np.nan_to_num(offsets, nan=1e9), axis=2) <= 1.0) & (peak >= clear_level)
    precise_rate = _rate(precise_all[:, 1:], null_valid, 0.1 * math.pi / cells)
    k, n_contra = int(agree.sum()), int(contradict.sum())
    n_precise = int(precise_all[:, 0].sum())
    chance = min(_tail(k, n, rate), _tail(n_precise, n, precise_rate))
    # Weak sites rarely peak exactly, but at a right model their correlation at zero offset still
    # stands above the rest of their surface more often than at wrong alignments.
    z = zero_z[:, 0]
    z_null = zero_z[:, 1:][np.isfinite(zero_z[:, 1:])]
    z_level = float(np.quantile(z_null, 0.95)) if len(z_null) >= 8 else np.inf
    lifted = measured & (np.nan_to_num(z, nan=-np.inf) > z_level)
    z_hits = int(lifted.sum())
    z_chance = _tail(z_hits, n, 0.05)
    z_mw = (mann_whitney_greater(z[measured], z_null)
            if n and len(z_null) >= 8 else 1.0)
    significant = chance <= params.max_chance or (z_chance <= params.max_z_chance and z_mw <= params.max_rank_chance)
    n_clear = k + n_contra
    coverage = _coverage(sites[agree | lifted], sites[measured])
    error, bound, scatter = error_field(sites[agree], offsets[agree, 0], extent)
    clear = measured & (peak[:, 0] >= clear_level) & np.isfinite(offsets[:, 0]).all(axis=1)
    shared = shared_error(sites[clear], offsets[clear, 0], extent, params.agree_px)
    reasons = []
    if n == 0:
        reasons.append("no site of the overlap could be compared (too small an overlap, masked pixels, or no "
                       "structure)")
    if k < params.min_agree:
        reasons.append(f"only {k} of {n} sites agree with the model (at least {params.min_agree} are needed)")
    if not significant:
        reasons.append(f"wrong alignments would give this much agreement with probability {min(chance, z_chance):.1e}")
    if n_clear and n_contra > params.max_contradict * n_clear:
        reasons.append(f"{n_contra} of {n_clear} clear sites contradict the model")
    if shared is not None and shared > params.tolerance_px:
        reasons.append(f"the clear sites agree on an error of {shared:.1f} px of the model")
    if coverage < params.min_coverage:
        reasons.append(f"the sites that support the model span only {100 * coverage:.0f} % of the overlap's extent")
    if bound is not None and bound > params.tolerance_px:
        reasons.append(f"estimated error {error:.1f} px (bound {bound:.1f} px) exceeds the tolerance of "
                       f"{params.tolerance_px:g} px")
    if not reasons:
        verdict = "verified"
    elif k >= 3 and min(chance, z_chance) < 1e-3:
        verdict = "suspect"
    else:
        verdict = "failed"
    return Verification(verdict, tuple(reasons), params.tolerance_px, params.template_px, n, k, n_contra, n_clear,
                        float(rate), chance, coverage, error, bound, scatter, round(elapsed, 4), sites,
                        offsets[:, 0], peaks[:, 0], agree, contradict, z_hits, z_chance, z_mw)


def shared_error(sites: np.ndarray, offsets: np.ndarray, extent: np.ndarray, radius: float):
    """RMS over ``extent`` of the affine error field that most clear sites share (within ``radius``
    of their offsets), when more sites share it than share no error at all; None otherwise.

    Contradicting sites scattered at random are local differences (parallax, change); contradicting
    sites that agree with one another are the model's own error (a turn or scale it missed)."""
    n = len(sites)
    if n < 4 or len(extent) == 0:
        return None
    support0 = int((np.linalg.norm(offsets, axis=1) <= radius).sum())
    centre = extent.mean(axis=0)
    scale = max(float(np.abs(extent - centre).max()), 1.0)
    a = np.column_stack([np.ones(n), (sites - centre) / scale])
    e = np.column_stack([np.ones(len(extent)), (extent - centre) / scale])
    triples = np.array(list(itertools.combinations(range(n), 3)))
    blocks = a[triples]
    ok = np.abs(np.linalg.det(blocks)) > 1e-6
    if not ok.any():
        return None
    coef = np.linalg.solve(blocks[ok], offsets[triples[ok]])  # (K, 3, 2) affine error fields
    support = (np.linalg.norm(offsets[None] - np.einsum("nj,kjc->knc", a, coef), axis=2) <= radius).sum(axis=1)
    k = int(np.argmax(support))
    if support[k] <= max(support0, 3):  # three sites fit any field: a shared one needs a fourth
        return None
    best_field = coef[k]
    inliers = np.linalg.norm(offsets - a @ best_field, axis=1) <= radius
    coef = np.linalg.lstsq(a[inliers], offsets[inliers], rcond=None)[0]
    return float(np.sqrt(np.mean(np.sum((e @ coef) ** 2, axis=1))))


def _rate(hits: np.ndarray, valid: np.ndarray, floor: float) -> float:
    return max((int((hits & valid).sum()) + 1) / (int(valid.sum()) + 2), floor)


def _tail(k: int, n: int, rate: float) -> float:
    """Probability of ``k`` or more hits among ``n`` sites at chance ``rate`` (1 without sites): the
    binomial upper tail, summed exactly (``n`` is a few dozen sites; scipy.stats would cost half a
    second of import per run)."""
    if not n or not k:
        return 1.0
    if rate <= 0.0:
        return 0.0
    if rate >= 1.0:
        return 1.0
    log_p, log_q = math.log(rate), math.log1p(-rate)
    terms = [math.lgamma(n + 1) - math.lgamma(i + 1) - math.lgamma(n - i + 1) + i * log_p + (n - i) * log_q
             for i in range(k, n + 1)]
    top = max(terms)
    return float(min(1.0, math.exp(top) * sum(math.exp(t - top) for t in terms)))


def mann_whitney_greater(x: np.ndarray, y: np.ndarray) -> float:
    """One-sided p-value that ``x`` tends to exceed ``y`` (Mann-Whitney U, normal approximation with
    tie and continuity corrections: scipy.stats.mannwhitneyu's 'asymptotic' method)."""
    n1, n2 = len(x), len(y)
    both = np.concatenate([x, y])
    _, inverse, counts = np.unique(both, return_inverse=True, return_counts=True)
    ranks = (np.cumsum(counts) - (counts - 1) / 2.0)[inverse.ravel()]  # ties share their mean rank
    u = ranks[:n1].sum() - n1 * (n1 + 1) / 2.0
    n = n1 + n2
    ties = float((counts ** 3 - counts).sum())
    sigma = math.sqrt(n1 * n2 / 12.0 * ((n + 1) - ties / (n * (n - 1))))
    if sigma == 0:
        return 1.0
    z = (u - n1 * n2 / 2.0 - 0.5) / sigma
    return 0.5 * math.erfc(z / math.sqrt(2.0))


def error_field(sites: np.ndarray, offsets: np.ndarray, extent: np.ndarray):
    """(error, bound, scatter) in px from agreeing sites' offsets: the RMS over ``extent`` of an
    error field fitted to them (the mean offset with fewer than 4 sites, a similarity with 4 to 7,
    an affine from 8, and from 12 a quadratic field when the Bayesian information criterion prefers
    it: a projective or polynomial model's error curves, and an affine field fitted where the sites
    are would understate it toward the overlap's edges), the same plus two standard errors of the
    fit, and the residual scatter; all None without sites."""
    k = len(sites)
    if k == 0 or len(extent) == 0:
        return None, None, None
    centre = extent.mean(axis=0)
    scale = max(float(np.abs(extent - centre).max()), 1.0)
    order = 0 if k < 4 else (1 if k < 8 else 2)
    fits = [_field_fit(sites, offsets, extent, centre, scale, order)]
    if k >= 12:
        fits.append(_field_fit(sites, offsets, extent, centre, scale, 3))
    error, bound, scatter, _ = min(fits, key=lambda f: f[3])
    return error, bound, scatter


def _field_design(xy: np.ndarray, centre, scale: float, order: int) -> np.ndarray:
    """Rows (all x, then all y) of an error field's design: 0 a shift, 1 a similarity, 2 an affine,
    3 a quadratic field."""
    u = (xy - centre) / scale
    one, zero = np.ones(len(xy)), np.zeros(len(xy))
    cols = [(one, zero), (zero, one)]
    if order == 1:
        cols += [(u[:, 0], u[:, 1]), (-u[:, 1], u[:, 0])]
    elif order >= 2:
        terms = [u[:, 0], u[:, 1]] + ([u[:, 0] ** 2, u[:, 0] * u[:, 1], u[:, 1] ** 2] if order == 3 else [])
        cols += [(t, zero) for t in terms] + [(zero, t) for t in terms]
    return np.stack([np.concatenate(c) for c in cols], axis=1)


def _field_fit(sites, offsets, extent, centre, scale: float, order: int):
    """(error, bound, scatter, BIC) of one error field fitted to the sites' offsets."""
    a = _field_design(sites, centre, scale, order)
    b = np.concatenate([offsets[:, 0], offsets[:, 1]])
    coef, *_ = np.linalg.lstsq(a, b, rcond=None)
    resid = b - a @ coef
    rss = float(resid @ resid)
    dof = max(len(b) - a.shape[1], 1)
    sigma = max(math.sqrt(rss / dof), 0.1)
    e = _field_design(extent, centre, scale, order)
    field_xy = (e @ coef).reshape(2, -1).T
    error = float(np.sqrt(np.mean(np.sum(field_xy ** 2, axis=1))))
    cov = sigma ** 2 * np.linalg.pinv(a.T @ a)
    var = np.einsum("ij,jk,ik->i", e, cov, e).reshape(2, -1).sum(axis=0)  # per point, x + y
    se = float(np.sqrt(np.mean(var)))
    bic = len(b) * math.log(max(rss, 1e-6 * len(b)) / len(b)) + a.shape[1] * math.log(len(b))
    return error, error + 2.0 * se, float(np.sqrt(np.mean(resid ** 2) * 2)), bic


def _coverage(agreeing: np.ndarray, measured: np.ndarray) -> float:
    """The smaller of the two axes' spans of ``agreeing`` sites, as shares of ``measured`` sites' spans."""
    if len(agreeing) < 2 or len(measured) < 2:
        return 0.0
    span = np.ptp(measured, axis=0)
    spans = np.where(span > 0, np.ptp(agreeing, axis=0) / np.maximum(span, 1e-9), 1.0)
    return float(np.min(spans))


def footprint(model, target: RasterInfo) -> np.ndarray:
    """The target's outline in reference px (64 points), as ``model`` maps it."""
    return model.apply(raster_outline(target.width, target.height, 17))


def _overlap(outline: np.ndarray, reference: RasterInfo):
    if not np.isfinite(outline).all():
        return None
    poly = Polygon(outline)
    poly = poly if poly.is_valid else poly.buffer(0)
    overlap = poly.intersection(box(0, 0, reference.width, reference.height))
    return None if overlap.is_empty or overlap.area <= 0 else overlap


def overlap_grid(overlap, n: int = 20) -> np.ndarray:
    """Points of a regular ``n x n`` grid over the overlap's bounding box that fall inside it."""
    if overlap is None:
        return np.zeros((0, 2))
    x0, y0, x1, y1 = overlap.bounds
    gx, gy = np.meshgrid(x0 + (np.arange(n) + 0.5) * (x1 - x0) / n, y0 + (np.arange(n) + 0.5) * (y1 - y0) / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    inside = prep(overlap)
    return pts[np.array([inside.contains(Point(x, y)) for x, y in pts], bool)]


def template_side(overlap, params: VerifyParams) -> int:
    """Template side for about ``params.target_sites`` sites over the overlap (even, within limits)."""
    area = 0.0 if overlap is None else float(overlap.area)
    side = math.sqrt(area / params.target_sites) if area > 0 else params.template_px
    return int(2 * round(min(max(side, params.template_px), params.max_template_px) / 2))


def site_grid(outline: np.ndarray, overlap, reference: RasterInfo, side: int, params: VerifyParams) -> np.ndarray:
    """Site centres (K, 2) in reference px: a regular grid, spacing at least one template, over the
    overlap; templates lie inside the reference and the target neighbourhoods they are compared
    with inside the target."""
    if overlap is None:
        return np.zeros((0, 2))
    lo = np.maximum(outline.min(axis=0), 0) + side / 2.0 + 1
    hi = np.minimum(outline.max(axis=0), [reference.width, reference.height]) - side / 2.0 - 1
    if np.any(hi < lo):
        return np.zeros((0, 2))
    step = max(math.sqrt(float(overlap.area) / params.max_sites), float(side))
    nx, ny = int((hi[0] - lo[0]) // step) + 1, int((hi[1] - lo[1]) // step) + 1
    xs = (lo[0] + hi[0]) / 2 + (np.arange(nx) - (nx - 1) / 2) * step
    ys = (lo[1] + hi[1]) / 2 + (np.arange(ny) - (ny - 1) / 2) * step
    gx, gy = np.meshgrid(xs, ys)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    margin = side / 2.0 + params.search_px + 2
    poly = outline.astype(np.float32)
    inside = np.array([cv2.pointPolygonTest(poly, (float(x), float(y)), True) >= margin for x, y in pts], bool)
    return pts[inside] if len(pts) else pts


def _inverse_at(model, p: np.ndarray, target: RasterInfo) -> Optional[Tuple[np.ndarray, np.ndarray]]:
    """(q, J^-1): the target px q that ``model`` maps onto reference px ``p`` (Newton's method), and
    the inverse of the model's Jacobian there, for a local affine inverse around ``p``."""
    if getattr(model, "matrix", None) is not None:
        q = model.inverse().apply(p[None])[0]
        return q, np.linalg.inv(local_jacobian(model, q[None])[0])
    c = np.array([target.width / 2.0, target.height / 2.0])
    j = local_jacobian(model, c[None])[0]
    q = c + np.linalg.solve(j, p - model.apply(c[None])[0])
    for _ in range(8):
        j = local_jacobian(model, q[None])[0]
        step = np.linalg.solve(j, p - model.apply(q[None])[0])
        q = q + step
        if np.abs(step).max() < 1e-4:
            break
    if not np.isfinite(q).all() or np.abs(model.apply(q[None])[0] - p).max() > 0.05:
        return None
    return q, np.linalg.inv(j)


def _read_site(model, p, target, target_bands, tds, reference, reference_bands, rds, side: int, search: int):
    """CFOG stacks of the reference template at ``p`` and of the target resampled through the model
    onto the template's search area; None when the site cannot be compared (outside an image,
    masked pixels, no structure)."""
    t, s = side, search
    x0, y0 = int(math.floor(p[0])) - t // 2, int(math.floor(p[1])) - t // 2
    if x0 < 0 or y0 < 0 or x0 + t > reference.width or y0 + t > reference.height:
        return None
    tmpl, ok = read_image(reference, reference_bands, Window(x0, y0, t, t), dataset=rds)
    if ok.mean() < 0.95 or tmpl[ok].std() < 1e-6:
        return None
    inverse = _inverse_at(model, np.asarray(p, float), target)
    if inverse is None:
        return None
    q, jinv = inverse
    size = t + 2 * s
    gx, gy = np.meshgrid(np.arange(size) + x0 - s + 0.5, np.arange(size) + y0 - s + 0.5)
    src = q + (np.column_stack([gx.ravel(), gy.ravel()]) - p) @ jinv.T
    c0, r0 = np.floor(src.min(axis=0)).astype(int) - 2
    c1, r1 = np.ceil(src.max(axis=0)).astype(int) + 2
    if c1 <= 0 or r1 <= 0 or c0 >= target.width or r0 >= target.height or (c1 - c0) * (r1 - r0) > 16 * size * size:
        return None
    # The window may reach past the target (a turned square's bounding box); what is sampled must not.
    patch, pok = read_image(target, target_bands, Window(c0, r0, c1 - c0, r1 - r0), dataset=tds)
    if pok.mean() < 0.5:
        return None
    patch = np.where(pok, patch, np.float32(patch[pok].mean())).astype(np.float32)
    mx = (src[:, 0] - c0 - 0.5).reshape(size, size).astype(np.float32)
    my = (src[:, 1] - r0 - 0.5).reshape(size, size).astype(np.float32)
    warped = cv2.remap(patch, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    wok = cv2.remap(pok.astype(np.uint8), mx, my, cv2.INTER_NEAREST, borderValue=0) > 0
    if wok.mean() < 0.95:
        return None
    return cfog(tmpl, valid=ok), cfog(warped, valid=wok)
