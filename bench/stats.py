"""Summary statistics of benchmark rows that ignore missing values (None)."""
from __future__ import annotations

import numpy as np


def median(values):
    v = [x for x in values if x is not None]
    return float(np.median(v)) if v else None


def p90(values):
    v = [x for x in values if x is not None]
    return float(np.percentile(v, 90)) if v else None
