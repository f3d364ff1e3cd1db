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

from ..descriptors.cfog import peak_offset
from ..io.raster import RasterInfo, open_dataset
from ..progress import Monitor
from .correlation import SearchSpectrum, TemplateSpectrum, turned, zero_score
from .field import error_field, shared_error
from .params import VERDICTS, Verification, VerifyParams
from .sites import footprint, overlap_grid, read_site, reference_overlap, site_grid, template_side
from .statistics import binomial_tail, mann_whitney_greater
from .verdict import VERDICT_RANK, corroborate, corroborating, judge, model_distance, result_rank

__all__ = ["NULL_PARTNERS", "NULL_TURNS", "VERDICTS", "VERDICT_RANK", "Verification", "VerifyParams", "binomial_tail",
           "corroborate", "corroborating", "error_field", "footprint", "judge", "mann_whitney_greater",
           "model_distance", "overlap_grid", "result_rank", "shared_error", "site_grid", "template_side", "verify"]

NULL_PARTNERS = 4  # other sites' target content each template is also compared with (wrong alignments)
NULL_TURNS = 3  # and, turned or mirrored (rot180, mirror x, mirror y), with the first three of those again


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
    overlap = reference_overlap(outline, reference)
    side = template_side(overlap, params)
    sites = site_grid(outline, overlap, reference, side, params)
    tmpls, patches = [], []
    with open_dataset(target) as tds, open_dataset(reference) as rds:
        for i, p in enumerate(sites):
            pair = read_site(model, p, target, target_bands, tds, reference, reference_bands, rds, side,
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
    tmpls = [None if t is None else TemplateSpectrum(t, shape) for t in stacks]
    patches = [None if p is None else SearchSpectrum(p, side) for p in patches]
    usable = [i for i in range(n) if tmpls[i] is not None and patches[i] is not None]
    for rank, i in enumerate(usable):
        m = len(usable)
        step = max(m // (NULL_PARTNERS + 1), 1)
        others = [usable[(rank + k * step) % m] for k in range(1, NULL_PARTNERS + 1)]
        pairs = [(i, tmpls[i])] + [(j, tmpls[i]) for j in others]
        pairs += [(j, TemplateSpectrum(t, shape)) for j, t in zip(others, turned(stacks[i]))]
        for c, (j, template) in enumerate(pairs):
            if c > 0 and j == i:
                continue
            surface = patches[j].ncc(template, params.search_px)
            zero_z[i, c] = zero_score(surface, params.search_px)
            offset, peak = peak_offset(surface, params.search_px)
            peaks[i, c] = peak
            if offset is not None:
                offsets[i, c] = offset
        if rank % 8 == 0:
            monitor.report(0.5 + 0.5 * rank / max(len(usable), 1), "verifying")
    monitor.report(1.0, "verifying")
    extent = overlap_grid(overlap)
    return judge(sites, offsets, peaks, zero_z, extent, replace(params, template_px=side), time.perf_counter() - t0)
