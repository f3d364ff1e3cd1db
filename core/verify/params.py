"""The verification's settings and its result: :class:`VerifyParams` (tolerances, template sizes,
significance levels), :class:`Verification` (the verdict, its reasons and the per-site evidence,
with its ``report.json`` form) and the verdicts' names. Coordinates: everything is in
full-resolution reference pixels (corner convention).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional, Tuple

import numpy as np

VERDICTS = ("verified", "suspect", "failed")


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
        Largest share of clear sites that contradict the model: their clear peak (above 90 % of chance
        peaks) lies elsewhere, decisively (see ``decisive_quantile``). Contradicting sites that share one
        error field bound the model's error instead (see :func:`hamta.core.verify.field.model_error`).
    decisive_quantile : float
        A peak elsewhere contradicts only when it exceeds the site's best correlation near zero offset by
        more than this quantile of what chance comparisons peaking elsewhere give: on right models of
        cross-modal pairs, most clear peaks elsewhere beat the zero offset by a hair (a median 0.017 in
        correlation on the multimodal set, against 0.083 at models 8 px off) and said nothing.
    min_coverage : float
        Smallest share of the measured sites' extent spanned by agreeing sites, in each axis.
    max_suspect_chance : float
        A result that does not verify is 'suspect' rather than 'failed' when at least 3 sites agree
        and wrong alignments would give its agreement (by peaks or by zero-offset lift, whichever is
        less likely) with a probability below this: partial support, which ``auto`` may corroborate
        with another method's result (see :func:`hamta.core.verify.verdict.corroborate`). 1e-2 was chosen on the
        odd-numbered half of the real multimodal pairs (``tools/calibrate_check.py``; 1e-3 before): right answers
        flagged there 6 -> 4 of 300, on the held-out half 10 -> 9, no wrong answer verified on either half, on the
        calibration study's models or on the should-fail cases. The verified levels above were not refitted: they
        also guard searches that check many wrong places, which that evidence holds few of.
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
    decisive_quantile: float = 0.9
    min_coverage: float = 0.4
    max_suspect_chance: float = 1e-2

    def second_look(self) -> "VerifyParams":
        """The settings of the second look: half of each chance level, so that two looks together keep
        within 1.5 times the first look's risk of verifying a wrong model."""
        return replace(self, max_chance=self.max_chance / 2, max_z_chance=self.max_z_chance / 2,
                       max_rank_chance=self.max_rank_chance / 2)

    def tried(self, n: int) -> "VerifyParams":
        """The chance levels for one of ``n`` candidates a search tries: each divided by ``n`` (Bonferroni),
        so that the search as a whole keeps one check's risk of verifying a wrong model."""
        return replace(self, max_chance=self.max_chance / n, max_z_chance=self.max_z_chance / n,
                       max_rank_chance=self.max_rank_chance / n)

    def significant(self, v: "Verification") -> bool:
        """Whether ``v``'s agreement is as unlikely from wrong alignments as these levels ask (the second look's
        verdicts against these levels' second look)."""
        return self.shortfall(v) <= 1.0

    def shortfall(self, v: "Verification") -> float:
        """How many times more likely by chance ``v``'s agreement is than these levels allow, by the nearer of
        the two measures (at most 1 exactly where it is :meth:`significant`; NaN counts as infinitely likely): the
        strength of its evidence, comparable across results whatever their number of sites."""
        p = self.second_look() if v.look == "structure" else self

        def ratio(x, level):
            r = x / level
            return r if r == r else math.inf

        return min(ratio(v.chance, p.max_chance), max(ratio(v.z_chance, p.max_z_chance),
                                                       ratio(v.z_mw, p.max_rank_chance)))

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
    ``look`` says where the sites were: 'grid' (a regular grid) or 'structure' (the second look's sites,
    placed where both images show structure). ``turned_agree`` sites agree with the model turned by 180
    degrees about the overlap's centre, as likely as ``turned_chance`` from wrong alignments.
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
    look: str = "grid"
    turned_agree: int = 0
    turned_chance: float = 1.0
    check: str = "cfog-sites"  # the check's name in report.json: 'grid-held-out-lines' for a sheet's own grid

    @property
    def verified(self) -> bool:
        return self.verdict == "verified"

    def summary(self) -> str:
        """The check's evidence in a few words (what the front ends print beside the verdict)."""
        return f"{self.n_agree} of {self.n_sites} sites agree"

    def to_dict(self) -> dict:
        """The ``quality`` section of ``report.json`` (see docs/report.md)."""
        def num(v):
            return None if v is None or not np.isfinite(v) else float(v)

        return {"verdict": self.verdict, "reasons": list(self.reasons), "check": self.check,
                "tolerance_px": self.tolerance_px, "template_px": self.template_px, "n_sites": self.n_sites,
                "n_agree": self.n_agree, "n_contradict": self.n_contradict, "n_clear": self.n_clear,
                "chance_rate": self.chance_rate, "chance_probability": self.chance, "coverage": self.coverage,
                "estimated_error_px": num(self.error_px), "error_bound_px": num(self.error_bound_px),
                "local_scatter_px": num(self.scatter_px), "time_s": self.time_s, "z_hits": self.z_hits,
                "z_chance": self.z_chance, "z_mw": self.z_mw, "corroboration": self.corroboration, "look": self.look,
                "turned_agree": self.turned_agree, "turned_chance": self.turned_chance,
                "sites": [{"reference_px": [float(x), float(y)],
                           "offset_px": None if not np.isfinite(o).all() else [float(o[0]), float(o[1])],
                           "peak": num(p), "agree": bool(a), "contradict": bool(c)}
                          for (x, y), o, p, a, c in zip(self.sites_xy, self.offset_xy, self.peak, self.agree,
                                                        self.contradict)]}
