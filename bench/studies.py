"""Every study the bench runs (see :mod:`hamta.bench.study`)."""
from __future__ import annotations


def all_studies():
    """Every study, the papers' reproductions first."""
    from .goals.basemap import STUDY as basemap
    from .goals.basemap_dates import STUDY as basemap_dates
    from .goals.basemap_real import STUDY as basemap_real
    from .goals.basemap_requests import STUDY as basemap_requests
    from .goals.batch import STUDY as batch
    from .goals.large import STUDY as large
    from .goals.scanned import STUDY as scanned
    from .goals.scanned_random import STUDY as scanned_random
    from .goals.scanned_random import TUNE_STUDY as scanned_random_tune
    from .goals.speed import STUDY as speed
    from .goals.writing import STUDY as writing
    from .goals.years_apart import STUDY as years_apart
    from .reproductions.lines_spectral import STUDY as lines_spectral
    from .reproductions.ndsift import STUDY as ndsift
    from .reproductions.rilbp import STUDY as rilbp
    from .reproductions.sibrif import STUDY as sibrif

    return [rilbp, sibrif, ndsift, lines_spectral, writing, large, batch, basemap, basemap_real, basemap_dates,
            basemap_requests,
            speed, years_apart, scanned, scanned_random, scanned_random_tune]
