"""Reproductions of each paper's own evaluation, run by ``hamta bench`` next to the family tables.

A reproduction evaluates each case (``per_case(case) -> list of row dicts``, run in the bench's
worker pool) and turns all rows into tables (``tables(rows, cases) -> list of dicts``
``{"title", "columns", "rows", "note"}``) that the bench prints and stores. It runs when one of its
``methods`` is benchmarked and its ``families`` are selected.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Tuple


@dataclass(frozen=True)
class Reproduction:
    name: str
    methods: Tuple[str, ...]
    families: Tuple[str, ...]
    per_case: Callable
    tables: Callable


def all_reproductions():
    from .rilbp import REPRODUCTION as rilbp

    return [rilbp]
