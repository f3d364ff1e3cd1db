"""``report.json``: the stable, documented summary of a registration (see docs/report.md)."""
from __future__ import annotations

import json
import math


def clean(value):
    """JSON-safe copy: NaN/inf become null, numpy scalars become Python numbers."""
    if isinstance(value, dict):
        return {str(k): clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def write_report(path: str, report: dict) -> None:
    with open(path, "w", encoding="utf-8") as f:
        json.dump(clean(report), f, indent=1, allow_nan=False)
        f.write("\n")


def read_report(path: str) -> dict:
    with open(path, encoding="utf-8") as f:
        return json.load(f)
