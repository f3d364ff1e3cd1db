"""What a reproduction of a paper's own evaluation is (see :mod:`hamta.bench.reproductions`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Tuple


@dataclass(frozen=True)
class Reproduction:
    name: str
    methods: Tuple[str, ...]
    families: Tuple[str, ...]
    units: Callable
    run_unit: Callable
    tables: Callable
