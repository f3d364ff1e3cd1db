"""Reproductions of each paper's own evaluation, run by ``hamta bench`` next to the family tables.

A reproduction splits its work into units (``units(config) -> list``), evaluates each unit in
the bench's worker pool (``run_unit(unit, config) -> list of row dicts``) and turns all rows into
tables (``tables(rows) -> list of {"title", "columns", "rows", "note"}``) that the bench prints and
stores. It runs when one of its ``methods`` is benchmarked and one of its ``families`` is selected.
A reproduction with ``units = None`` is computed from the benchmark's own rows of its families.
``writing`` is the project's own study of its output writer against ``gdalwarp``, run the same way.
"""
from __future__ import annotations

from .base import Reproduction

__all__ = ["Reproduction", "all_reproductions"]


def all_reproductions():
    from .batch import REPRODUCTION as batch
    from .large import REPRODUCTION as large
    from .lines_spectral import REPRODUCTION as lines_spectral
    from .ndsift import REPRODUCTION as ndsift
    from .rilbp import REPRODUCTION as rilbp
    from .sibrif import REPRODUCTION as sibrif
    from .writing import REPRODUCTION as writing

    return [rilbp, sibrif, ndsift, lines_spectral, writing, large, batch]
