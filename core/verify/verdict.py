"""The verdict rule. :func:`judge` gives one result's verdict from its sites' correlation peaks,
offsets and zero-offset lifts (against the same template compared with wrong alignments: chance),
with the reasons it is not verified. :func:`corroborating`, :func:`corroborate` and :func:`result_rank`
carry it across results (``auto``): two results of different methods that are each 'suspect' and
whose models agree within the tolerance verify each other. Coordinates: sites, offsets and
tolerances are full-resolution reference pixels; :func:`model_distance` compares two models at
target pixels, in reference pixels.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from .field import model_error, site_coverage
from .params import Verification, VerifyParams
from .statistics import binomial_tail, chance_rate, mann_whitney_greater

VERDICT_RANK = {"verified": 2, "suspect": 1, "failed": 0}


def judge(sites, offsets, peaks, zero_z, margins, turned, extent, params: VerifyParams,
          elapsed: float = 0.0) -> Verification:
    """The verdict from per-site results: ``offsets`` (n, 1 + k, 2), ``peaks``, ``zero_z`` and ``margins``
    (n, 1 + k) of each site's template against the target at its own site (column 0) and at k other
    sites or turned (chance). ``margins`` is how far a surface's best value beyond the agreement radius
    exceeds its best value within it. ``turned`` is (offsets (n, 2), peaks (n,)) of the model turned by
    180 degrees about the overlap's centre (None or NaN where not compared). ``extent`` (m, 2) are
    points over the overlap where the error field is evaluated."""
    measured = np.isfinite(peaks[:, 0])
    n = int(measured.sum())
    null_valid = np.isfinite(peaks[:, 1:])
    null_peaks = peaks[:, 1:][null_valid]
    clear_level, floor = (np.quantile(null_peaks, [0.9, 0.5]) if len(null_peaks) >= 8 else (1.0, 1.0))
    distance = np.linalg.norm(np.nan_to_num(offsets, nan=1e9), axis=2)
    near = distance <= params.agree_px
    peak = np.nan_to_num(peaks, nan=-1.0)
    interior = np.isfinite(offsets[:, 0]).all(axis=1)
    # A site agrees when its peak (not the weakest half of chance peaks) is near zero offset.
    agree = near[:, 0] & (peak[:, 0] >= floor)
    contradict = ~near[:, 0] & (peak[:, 0] >= clear_level) & interior & decisive(margins, null_valid,
                                                                                   params.decisive_quantile)
    k, n_contra = int(agree.sum()), int(contradict.sum())
    chance, rate = agreement_chance(distance, peak, null_valid, n, floor, clear_level, params)
    # Weak sites rarely peak exactly, but at a right model their correlation at zero offset still
    # stands above the rest of their surface more often than at wrong alignments.
    z = zero_z[:, 0]
    z_null = zero_z[:, 1:][np.isfinite(zero_z[:, 1:])]
    z_level = float(np.quantile(z_null, 0.95)) if len(z_null) >= 8 else np.inf
    lifted = measured & (np.nan_to_num(z, nan=-np.inf) > z_level)
    z_hits = int(lifted.sum())
    z_chance = binomial_tail(z_hits, n, 0.05)
    z_mw = (mann_whitney_greater(z[measured], z_null)
            if n and len(z_null) >= 8 else 1.0)
    significant = chance <= params.max_chance or (z_chance <= params.max_z_chance and z_mw <= params.max_rank_chance)
    n_clear = k + n_contra
    k_turned, n_turned, turned_chance = turned_agreement(turned, floor, rate, params)
    coverage = site_coverage(sites[agree | lifted], sites[measured])
    usable = measured & (peak[:, 0] >= floor) & interior
    fit, shared = model_error(sites, offsets[:, 0], agree, usable, extent, params.agree_px)
    error, bound, scatter = (None, None, None) if fit is None else (fit.error, fit.bound, fit.scatter)
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
    if k_turned >= params.min_agree and turned_chance <= params.max_suspect_chance:
        reasons.append(f"the model turned by 180 degrees about the overlap's centre fits too ({k_turned} of {n_turned} "
                       "sites agree with it): the scene repeats, and the check cannot tell the two apart")
    if shared is not None and shared > params.tolerance_px:
        reasons.append(f"the sites agree on an error of {shared:.1f} px of the model")
    if coverage < params.min_coverage:
        reasons.append(f"the sites that support the model span only {100 * coverage:.0f} % of the overlap's extent")
    if bound is not None and bound > params.tolerance_px:
        reasons.append(f"estimated error {error:.1f} px (bound {bound:.1f} px) exceeds the tolerance of "
                       f"{params.tolerance_px:g} px")
    if not reasons:
        verdict = "verified"
    elif k >= 3 and min(chance, z_chance) < params.max_suspect_chance:
        verdict = "suspect"
    else:
        verdict = "failed"
    return Verification(verdict, tuple(reasons), params.tolerance_px, params.template_px, n, k, n_contra, n_clear,
                        float(rate), chance, coverage, error, bound, scatter, round(elapsed, 4), sites,
                        offsets[:, 0], peaks[:, 0], agree, contradict, z_hits, z_chance, z_mw,
                        turned_agree=k_turned, turned_chance=turned_chance)


def agreement_chance(distance, peak, null_valid, n: int, floor: float, clear_level: float, params: VerifyParams):
    """(probability, rate): how likely wrong alignments give as many sites near zero offset as these.

    Agreement is counted within 1, 2, 3 px and the agreement radius (peaks above the weakest half of
    chance peaks), and precisely (within 1 px, a clear peak): a model right to a pixel gathers its sites
    in a small disc that chance peaks rarely reach. Each count's chance rate comes from the mismatched
    sites, floored by what uniformly placed chance peaks give (half pass the floor; a tenth are clear);
    the probability is the smallest binomial tail times the number of counts (Bonferroni). ``rate`` is
    the chance rate at the agreement radius."""
    cells = (2 * params.search_px + 1) ** 2
    counts = [((distance <= r) & (peak >= floor), 0.5 * math.pi * r * r / cells)
              for r in [r for r in (1.0, 2.0, 3.0) if r < params.agree_px] + [params.agree_px]]
    counts.append(((distance <= 1.0) & (peak >= clear_level), 0.1 * math.pi / cells))
    rates = [chance_rate(hits[:, 1:], null_valid, uniform) for hits, uniform in counts]
    tails = [binomial_tail(int(hits[:, 0].sum()), n, rate) for (hits, _), rate in zip(counts, rates)]
    return min(1.0, min(tails) * len(tails)), rates[-2]


def turned_agreement(turned, floor: float, rate: float, params: VerifyParams):
    """(sites that agree with the model turned by 180 degrees, sites compared, the probability that wrong
    alignments agree that often): a right model's turned twin agrees by chance alone (on the multimodal
    set, never with probability below 0.4); a scene of repeated parcels or streets can fit both."""
    if turned is None:
        return 0, 0, 1.0
    offsets, peaks = turned
    compared = np.isfinite(peaks)
    near = np.linalg.norm(np.nan_to_num(offsets, nan=1e9), axis=1) <= params.agree_px
    k = int((near & compared & (np.nan_to_num(peaks, nan=-1.0) >= floor)).sum())
    n = int(compared.sum())
    return k, n, binomial_tail(k, n, rate)


def decisive(margins: np.ndarray, null_valid: np.ndarray, quantile: float) -> np.ndarray:
    """Sites (column 0 of ``margins``) whose best value beyond the agreement radius exceeds their best
    value within it by more than ``quantile`` of the chance comparisons that peak beyond it do: a clear
    peak elsewhere that the zero offset nearly matches is an ambiguous site (repeated structure, speckle,
    a surface without one peak), not evidence against the model."""
    chance = margins[:, 1:][null_valid & (np.nan_to_num(margins[:, 1:], nan=-1.0) > 0)]
    level = float(np.quantile(chance, quantile)) if len(chance) >= 8 else 0.0
    return np.nan_to_num(margins[:, 0], nan=-1.0) > level


def corroborating(result, earlier, tolerance_px: float):
    """(an earlier result of another method, their distance) when both have partial support from the
    independent check and their models agree within ``tolerance_px``; None otherwise."""
    if result.verification.verdict != "suspect":
        return None
    for other in earlier:
        if other.method == result.method or other.verification.verdict != "suspect":
            continue
        d = model_distance(result, other)
        if d is not None and d <= tolerance_px:
            return other, d
    return None


def model_distance(a, b, n: int = 20):
    """RMS distance (reference px) between two results' models over an ``n`` x ``n`` grid of target
    points that ``a`` maps inside the reference; None when none does."""
    t, r = a.target, a.reference
    gx, gy = np.meshgrid((np.arange(n) + 0.5) * t.width / n, (np.arange(n) + 0.5) * t.height / n)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    pa = a.model.apply(pts)
    inside = np.all(np.isfinite(pa), axis=1) & (pa[:, 0] >= 0) & (pa[:, 1] >= 0) & (pa[:, 0] <= r.width) & (
        pa[:, 1] <= r.height)
    if not inside.any():
        return None
    return float(np.sqrt(np.mean(np.sum((pa[inside] - b.model.apply(pts[inside])) ** 2, axis=1))))


def corroborate(result, other, distance: float):
    """``result`` verified by agreement with ``other``, an independent method's result."""
    summary = (f"verified by agreement of independent estimates: {result.method} and {other.method} agree within "
               f"{distance:.2f} px, each partly supported by the site check")
    v = dataclasses.replace(result.verification, verdict="verified", reasons=(),
                            corroboration={"method": other.method, "distance_px": distance, "summary": summary,
                                           "own_reasons": list(result.verification.reasons)})
    return dataclasses.replace(result, verification=v)


def beats(v, w, ties: bool = False) -> bool:
    """Whether verification ``v`` beats ``w``: a better verdict, or the same verdict with a smaller error bound
    (or an equal one, with ``ties``)."""
    if VERDICT_RANK[v.verdict] != VERDICT_RANK[w.verdict]:
        return VERDICT_RANK[v.verdict] > VERDICT_RANK[w.verdict]
    return error_bound(v) <= error_bound(w) if ties else error_bound(v) < error_bound(w)


def error_bound(v) -> float:
    """The check's bound on a model's error (reference px) from its :class:`Verification`; infinite where it
    gave none."""
    return float("inf") if v.error_bound_px is None else v.error_bound_px


def result_rank(result):
    """Sort key of results, best last: the verdict, then the stronger evidence (the agreement least likely by
    chance, :meth:`VerifyParams.shortfall`: a count of agreeing sites favours a model that merely lies over
    more of them; on held-out Landsat dates a wrong model agreeing at 4 of 12 sites, with probability 8e-3,
    was returned over a right one agreeing at 3 of 7 with 2e-4), then agreeing sites, then the smaller error
    bound."""
    v = result.verification
    evidence = -VerifyParams(tolerance_px=v.tolerance_px).shortfall(v)
    return VERDICT_RANK[v.verdict], evidence, v.n_agree, -(v.error_bound_px if v.error_bound_px is not None else 1e9)
