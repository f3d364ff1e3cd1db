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
sites that decisively contradict the model (a clear peak elsewhere that beats the zero offset by more
than chance comparisons do: a peak elsewhere that the zero offset nearly matches is an uninformative
site, as speckle, water, shadow or repeated structure give), (3) agreeing sites spread over the
overlap, and (4) an error field whose RMS over the overlap, debiased and plus two standard errors, is
within the accuracy asked for. The field is grown from the sites near zero offset out to every site
that follows it (a missed turn or scale moves distant sites beyond the agreement radius, which a fit to
the near sites alone would not see), or is the field that more clear sites share. Local scatter
(parallax, change, modality) widens the bound; a systematic error shows in the field.

Coordinates: sites, offsets and tolerances are full-resolution reference pixels (corner convention).

This module holds the entry :func:`verify`, which reads the sites and correlates them; the parts
are :mod:`.params` (settings, result), :mod:`.sites` (where to look, what to read),
:mod:`.correlation` (FFT correlation surfaces), :mod:`.statistics` (chance), :mod:`.field` (the
error field) and :mod:`.verdict` (the verdict rule, also across two results).

References
----------
Ye, Y., Bruzzone, L., Shan, J., Bovolo, F., & Zhu, Q. (2019). Fast and robust matching for
multimodal remote sensing image registration. IEEE TGRS 57(11), 9059-9070 (CFOG).
Scheffler, D., Hollstein, A., Diedrich, H., Segl, K., & Hostert, P. (2017). AROSICS. Remote
Sensing 9(7), 676 (reliability of local shifts, checked after de-shifting).
"""
from __future__ import annotations

import time
from dataclasses import replace
from typing import Optional

import numpy as np

from ..io.raster import RasterInfo
from ..io.windows import WindowReader
from ..parallel import threaded
from ..progress import Monitor
from ..similarity.peak import peak_offset
from .correlation import SearchSpectrum, TemplateSpectrum, fast_length, margin, zero_score
from .field import error_field, fit_field, model_error
from .params import VERDICTS, Verification, VerifyParams
from .sites import (
    descriptors,
    footprint,
    grid_centre,
    overlap_grid,
    read_site,
    reference_overlap,
    reflections,
    search_descriptors,
    site_grid,
    structured,
    template_side,
)
from .statistics import binomial_tail, mann_whitney_greater
from .verdict import VERDICT_RANK, beats, corroborate, corroborating, error_bound, judge, model_distance, result_rank

__all__ = ["NULL_PARTNERS", "NULL_TURNS", "VERDICTS", "VERDICT_RANK", "Verification", "VerifyParams", "beats",
           "binomial_tail", "corroborate", "corroborating", "error_bound", "error_field", "fit_field", "footprint",
           "judge", "mann_whitney_greater", "model_distance", "model_error", "overlap_grid", "result_rank", "site_grid",
           "template_side", "verify"]

NULL_PARTNERS = 4  # other sites' target content each template is also compared with (wrong alignments)
NULL_TURNS = 3  # and, turned or mirrored (rot180, mirror x, mirror y), with the first three of those again


def verify(model, target: RasterInfo, target_bands, reference: RasterInfo, reference_bands,
           params: VerifyParams = VerifyParams(), monitor: Optional[Monitor] = None) -> Verification:
    """Check ``model`` (target px -> reference px, any model type) against the pixels of both rasters.

    The first look compares sites on a regular grid. When it does not verify the model but some sites
    support it, a second look compares sites placed where both images show structure (chosen from a
    lattice three times denser, no two templates overlapping), held to half the chance levels so that
    the two looks together keep within 1.5 times the first look's risk of verifying a wrong model. The
    look that judged better is returned; a second look that did not verify either is among its reasons.

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
    overlap = reference_overlap(outline, reference)
    side = template_side(overlap, params)
    params = replace(params, template_px=side)
    extent = overlap_grid(overlap)
    with WindowReader(target, target_bands) as targets, WindowReader(reference, reference_bands) as references:
        def read(points, mon):
            return threaded(lambda p: read_site(model, p, targets, references, side, params.search_px), points, mon,
                            "verifying")

        centre = grid_centre(overlap) if overlap is not None else np.zeros(2)
        sites = site_grid(outline, overlap, reference, side, params)
        pairs = read(sites, monitor.span(0.0, 0.2))
        mirror = reflections(sites, centre)
        first = judge(sites, *correlate(pairs, [pairs[j] if j >= 0 else None for j in mirror], side, params,
                                        monitor.span(0.2, 0.5)), extent, params)
        if first.verified or not second_look_worth(first):
            monitor.report(1.0, "verifying")
            return replace(first, time_s=round(time.perf_counter() - t0, 4))
        lattice = site_grid(outline, overlap, reference, side, params, step=side / 3.0)
        pairs = read(lattice, monitor.span(0.5, 0.75))
        mirror = reflections(lattice, centre)
        chosen = structured(lattice, pairs, side, params.search_px, params.max_sites)
        stricter = params.second_look()
        second = judge(lattice[chosen], *correlate([pairs[i] for i in chosen],
                                                   [pairs[mirror[i]] if mirror[i] >= 0 else None for i in chosen],
                                                   side, stricter, monitor.span(0.75, 1.0)), extent, stricter)
    monitor.report(1.0, "verifying")
    elapsed = round(time.perf_counter() - t0, 4)
    if VERDICT_RANK[second.verdict] > VERDICT_RANK[first.verdict]:
        return replace(second, time_s=elapsed, look="structure")
    again = (f"a second look at {second.n_sites} sites where both images show structure did not confirm it "
             f"({second.n_agree} agree)")
    return replace(first, reasons=first.reasons + (again,), time_s=elapsed)


def second_look_worth(first: Verification) -> bool:
    """Whether a model the grid did not verify has support enough to look again: sites that agree or
    that lift their correlation at zero offset above chance."""
    return first.n_agree >= 2 or first.z_hits >= 3


def correlate(pairs, reflected, side: int, params: VerifyParams, monitor: Monitor):
    """(offsets, peaks, zero_z, margins, turned) of each site's template (a :func:`read_site` pair, or None)
    against the target at its own site (column 0) and, for chance, at ``NULL_PARTNERS`` other sites and
    turned or mirrored at ``NULL_TURNS`` of those; ``turned`` is (offsets, peaks) of the model turned by
    180 degrees about the grid's centre: the site's template turned, against the target at the site's
    reflection (``reflected``, a pair or None per site). Sites are prepared and compared on threads."""
    n = len(pairs)
    columns = 1 + NULL_PARTNERS + NULL_TURNS
    offsets = np.full((n, columns, 2), np.nan)
    peaks = np.full((n, columns), np.nan)
    zero_z = np.full((n, columns), np.nan)
    margins = np.full((n, columns), np.nan)
    turned_offsets, turned_peaks = np.full((n, 2), np.nan), np.full(n, np.nan)
    s = params.search_px
    shape = (fast_length(side + 2 * s),) * 2

    def prepare(pair):
        if id(pair) not in own:  # a reflection read for the turn only: its search area is all it needs
            return None, SearchSpectrum(search_descriptors(pair), side, shape)
        template, search = descriptors(pair)
        spectrum = TemplateSpectrum(template, shape)
        return (spectrum,) + spectrum.turned(), SearchSpectrum(search, side, shape)

    usable = [i for i in range(n) if pairs[i] is not None]
    areas = {id(pairs[i]): pairs[i] for i in usable}  # the sites' own
    own = set(areas)
    for p in (reflected[i] for i in usable):
        if p is not None:
            areas.setdefault(id(p), p)
    by_area = dict(zip(areas, threaded(prepare, list(areas.values()), monitor.span(0.0, 0.5), "verifying")))
    templates = {i: by_area[id(pairs[i])][0] for i in usable}
    spectra = {key: search for key, (_, search) in by_area.items()}
    m = len(usable)

    def compare(rank: int):
        i = usable[rank]
        step = max(m // (NULL_PARTNERS + 1), 1)
        others = [usable[(rank + k * step) % m] for k in range(1, NULL_PARTNERS + 1)]
        comparisons = [(i, templates[i][0])] + [(j, templates[i][0]) for j in others]
        comparisons += list(zip(others, templates[i][1:]))
        rows = []
        for c, (j, template) in enumerate(comparisons):
            if c > 0 and j == i:
                continue
            surface = spectra[id(pairs[j])].ncc(template, s)
            rows.append((c, zero_score(surface, s), margin(surface, s, params.agree_px)) + peak_offset(surface, s))
        turn = None if reflected[i] is None else peak_offset(spectra[id(reflected[i])].ncc(templates[i][1], s), s)
        return rows, turn

    for i, (rows, turn) in zip(usable, threaded(compare, range(m), monitor.span(0.5, 1.0), "verifying")):
        for c, z, g, offset, peak in rows:
            zero_z[i, c], margins[i, c], peaks[i, c] = z, g, peak
            if offset is not None:
                offsets[i, c] = offset
        if turn is not None:
            turned_peaks[i] = turn[1]
            if turn[0] is not None:
                turned_offsets[i] = turn[0]
    return offsets, peaks, zero_z, margins, (turned_offsets, turned_peaks)
