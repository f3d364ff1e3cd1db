"""Studies the bench runs beside its family tables: each paper's own evaluation
(:mod:`hamta.bench.reproductions`) and the project's engineering goals (:mod:`hamta.bench.goals`:
the output writer against ``gdalwarp``, batch throughput, a Sentinel-2-sized scene).

A study splits its work into units (``units(config) -> list``), evaluates each unit in the bench's
worker pool (``run_unit(unit, config) -> list of row dicts``) and turns all rows into tables
(``tables(rows) -> list of {"title", "columns", "rows", "note"}``) that the bench prints and stores.
It runs when one of its ``methods`` is benchmarked and one of its ``families`` is selected. A study
with ``units = None`` is computed from the benchmark's own rows of its families.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Tuple


@dataclass(frozen=True)
class Study:
    name: str
    methods: Tuple[str, ...]
    families: Tuple[str, ...]
    units: Callable
    run_unit: Callable
    tables: Callable
