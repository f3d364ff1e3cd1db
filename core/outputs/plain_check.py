"""The independent check in plain words for the report: one sentence per finding, lengths in
reference px and, outside pixel mode, in map units; numbers escaped, sentences HTML.
"""
from __future__ import annotations

import math
from typing import List, Optional

import numpy as np

from ..verify import VerifyParams
from .html_text import _e
from .scale import MapScale, _both


def _odds(p: float) -> str:
    """A small probability as 'about once in 40 000 tries' (plain words for an analyst)."""
    if not math.isfinite(p) or p >= 0.5:
        return "easily"
    if p < 1e-9:
        return "less than once in a billion tries"
    n = 1.0 / p
    digits = 10 ** max(0, math.floor(math.log10(n)) - 1)  # two significant digits
    n = round(n / digits) * digits
    if n >= 1e6:
        return f"about once in {n / 1e6:.2g} million tries"
    return f"about once in {n:,.0f} tries".replace(",", "\u2009")


def _plain_check(v, scale: Optional[MapScale]) -> List[str]:
    """The independent check in plain words, one sentence per item; numbers escaped."""
    params = VerifyParams(tolerance_px=v.tolerance_px)
    params = params.second_look() if v.look == "structure" else params
    other = int(v.n_sites - np.count_nonzero(v.agree | v.contradict))
    if v.n_sites == 0:
        return ["No site of the overlap could be compared (too small an overlap, masked pixels, or no detail)."]

    def sites(n: int) -> str:
        return f"{n} site" + ("" if n == 1 else "s")

    out = [f"At <b>{v.n_agree} of {sites(v.n_sites)}</b> checked, the two images line up where the model puts them: "
           f"the best match lies within {_both(params.agree_px, scale, '.0f')} of the model's position."]
    if v.look == "structure":
        out.append("These sites are a second look, placed where both images show detail: a regular grid of sites "
                   "had not been enough to decide, so this look is held to a stricter standard.")
    if v.n_contradict:
        out.append(f"At <b>{sites(v.n_contradict)}</b> the images clearly match better somewhere else, by more than "
                   "chance gives: the ground changed there, or the model is wrong there.")
    else:
        out.append("No site clearly matches better somewhere else.")
    if other:
        out.append(f"{sites(other)} gave no clear answer (too little detail, such as water or uniform fields, or "
                   "changes between the images).")
    by_peaks = v.chance <= params.max_chance
    by_shape = v.z_chance <= params.max_z_chance and v.z_mw <= params.max_rank_chance
    if by_peaks:
        out.append(f"A wrong alignment of these two images would line up at so many sites {_odds(v.chance)}: "
                   "the agreement is real.")
    elif by_shape:
        out.append(f"At <b>{v.z_hits} of {v.n_sites}</b> sites the two images match better at the model's position "
                   f"than when shifted slightly; a wrong alignment would not do this ({_odds(v.z_chance)}).")
    else:
        out.append(f"A wrong alignment of these two images would line up this well {_odds(min(v.chance, v.z_chance))}"
                   ", so this agreement alone does not prove the model.")
    if v.error_px is not None and v.error_bound_px is not None:
        out.append(f"From the sites that line up, the error of the alignment is estimated at "
                   f"<b>{_both(v.error_px, scale)}</b>, and at most <b>{_both(v.error_bound_px, scale)}</b> with a "
                   f"safety margin; the accuracy asked for was {_both(v.tolerance_px, scale)}.")
    else:
        out.append("Too few sites line up to estimate the error of the alignment.")
    if v.coverage is not None and math.isfinite(v.coverage):
        out.append(f"The sites that support the model spread over {v.coverage * 100:.0f} % of the compared area's "
                   f"width and height (at least {params.min_coverage * 100:.0f} % is needed to vouch for the whole "
                   "image).")
    if v.corroboration:
        c = v.corroboration
        out.append(f"Confirmed by a second method: <b>{_e(c.get('method', ''))}</b> found an alignment that agrees "
                   f"with this one within {_both(c.get('distance_px'), scale)}, and the check partly supported each.")
    return out
