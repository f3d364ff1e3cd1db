"""The chance side of the verdict: the rate at which wrong alignments give a hit (agreement, a
precise peak), the binomial tail of so many hits among the sites at that rate, and the one-sided
Mann-Whitney test of the sites' zero-offset lifts against chance; computed here, exactly or as
scipy.stats does, because importing scipy.stats costs half a second per run. Coordinates: none;
counts, rates and probabilities only.
"""
from __future__ import annotations

import math

import numpy as np


def chance_rate(hits: np.ndarray, valid: np.ndarray, floor: float) -> float:
    """The share of ``valid`` chance comparisons that are ``hits`` (one added to each side, so never
    0 or 1), at least ``floor``."""
    return max((int((hits & valid).sum()) + 1) / (int(valid.sum()) + 2), floor)


def binomial_tail(k: int, n: int, rate: float) -> float:
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
