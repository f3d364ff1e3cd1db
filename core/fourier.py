"""The FFTs of the cross-modal method's start-up path (phase congruency, the pose check): numpy's where numpy
computes in single precision (numpy 2), scipy's before.

numpy 2's FFTs keep float32 and complex64, and using them spares a command-line run the import of ``scipy.fft``,
0.13-0.2 s on current wheels (scipy 1.17 loads its array-API layer and ``scipy.special`` with it). They are not
as fast: numpy 2.4's inverse transforms take about the time of scipy's on one thread, its forward transforms in
single precision three to five times as long, which the pose check's 30 forward transforms per run feel; a whole
``xmodal`` run is still faster by the import (docs/benchmarks.md, ninth round). numpy 1.x computes every FFT in
double precision, twice as slow as scipy's here, so the interpreter that QGIS embeds on Debian (numpy 1.24) keeps
scipy's, on every core as before, and pays its import once per session. CFOG matching
(:mod:`hamta.core.matching.multimodal`) keeps scipy's: its many real transforms of channel stacks run three times
faster there.
Arrays are indexed as numpy's and scipy's FFTs index them; no coordinates.
"""
from __future__ import annotations

import cv2
import numpy as np

SINGLE_PRECISION = int(np.__version__.split(".")[0]) >= 2

if SINGLE_PRECISION:
    from numpy.fft import fft2, ifft2, irfft2, rfft2
else:
    from functools import partial

    from scipy import fft as _scipy

    fft2, ifft2 = partial(_scipy.fft2, workers=-1), partial(_scipy.ifft2, workers=-1)
    rfft2, irfft2 = _scipy.rfft2, _scipy.irfft2

__all__ = ["SINGLE_PRECISION", "fast_length", "fft2", "ifft2", "irfft2", "rfft2"]


def fast_length(n: int) -> int:
    """The smallest length >= ``n`` with no prime factor above 5, where FFTs are fastest (scipy's
    ``next_fast_len`` for real transforms gives the same)."""
    return cv2.getOptimalDFTSize(n)
