"""The FFTs of the cross-modal method's start-up path (phase congruency, the pose check), chosen by the stack.

Where numpy computes in single precision (numpy 2, the PyPI wheels), nothing here imports ``scipy.fft``: that
import costs a command-line run 0.13-0.2 s on current wheels (scipy 1.17 loads its array-API layer and
``scipy.special`` with it). There, the complex transforms (phase congruency's) are OpenCV's DFT: as accurate as
numpy's complex64 transforms (6e-8 from double precision on unit-sized values) and 2-3.5 times as fast as
numpy 2.4's at the sizes phase congruency takes (226-384 px), about 0.5 s less processor time per cross-modal
run (measured on the commit that made this module); the real transforms over channel stacks (the pose
check's) are numpy's, which keep float32 and complex64.

numpy 1.x computes every FFT in double precision, twice as slow as scipy's here, and Debian's OpenCV 4.6 DFT is
three times slower than the wheels' OpenCV 5 (scipy's on two threads is faster than either), so the interpreter
that QGIS embeds on Debian (numpy 1.24) uses scipy's for all of them. CFOG matching
(:mod:`hamta.core.matching.multimodal`) uses scipy's everywhere: its many real transforms of channel stacks run
three times faster there.
Arrays are indexed as numpy's FFTs index them; no coordinates.
"""
from __future__ import annotations

import cv2
import numpy as np

SINGLE_PRECISION = int(np.__version__.split(".")[0]) >= 2

__all__ = ["SINGLE_PRECISION", "fast_length", "fft2", "ifft2", "irfft2", "rfft2"]


def fast_length(n: int) -> int:
    """The smallest length >= ``n`` with no prime factor above 5, where FFTs are fastest (scipy's
    ``next_fast_len`` for real transforms gives the same)."""
    return cv2.getOptimalDFTSize(n)


def _opencv_fft2(image: np.ndarray) -> np.ndarray:
    """The (H, W) complex64 spectrum of a real 2-D array (computed in single precision), as numpy's ``fft2``."""
    spectrum = cv2.dft(np.ascontiguousarray(image, np.float32), flags=cv2.DFT_COMPLEX_OUTPUT)
    return spectrum.view(np.complex64)[..., 0]


def _opencv_ifft2(spectra: np.ndarray) -> np.ndarray:
    """The inverse transforms over the last two axes (complex64, scaled as numpy's ``ifft2``) of complex spectra."""
    spectra = np.ascontiguousarray(spectra, np.complex64)
    out = np.empty_like(spectra)
    flags = cv2.DFT_INVERSE | cv2.DFT_SCALE | cv2.DFT_COMPLEX_OUTPUT
    for source, target in zip(spectra.reshape((-1,) + spectra.shape[-2:]), out.reshape((-1,) + out.shape[-2:])):
        cv2.dft(_pairs(source), _pairs(target), flags=flags)
    return out


def _pairs(a: np.ndarray) -> np.ndarray:
    """A contiguous complex64 (H, W) array as the (H, W, 2) float32 view OpenCV reads and writes (no copy)."""
    return a.view(np.float32).reshape(a.shape + (2,))


if SINGLE_PRECISION:
    from numpy.fft import irfft2, rfft2

    fft2, ifft2 = _opencv_fft2, _opencv_ifft2
else:
    from functools import partial

    from scipy import fft as _scipy

    rfft2, irfft2 = _scipy.rfft2, _scipy.irfft2
    fft2, ifft2 = partial(_scipy.fft2, workers=-1), partial(_scipy.ifft2, workers=-1)
