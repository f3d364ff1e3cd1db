"""Phase congruency from log-Gabor filters (Kovesi's PC2 and PC3 measures) and RIFT's maps.

Kovesi, P. (1999). Image features from phase congruency. Videre 1(3), 1-26; and Kovesi, P.
(2003). Phase congruency detects corners and edges. DICTA 2003. The measure (eqs. 7-8 of spec 002)

    PC = sum_o sum_n W_o [A_no (cos(phi_no - mean_phi_o) - |sin(phi_no - mean_phi_o)|) - T_o]+
         / (sum_o sum_n A_no + eps)

is computed with ``nscale`` log-Gabor scales and ``norient`` orientations in the frequency
domain, a Rayleigh noise model estimated from the smallest scale per orientation (threshold
``T = (mean + k sigma) / 1.7`` as in Kovesi's ``phasecong2``) and the frequency-spread weight W.
PC lies in [0, 1] and does not depend on image contrast.

:func:`log_gabor_maps` is the ``phasecong3`` form RIFT uses (Li, Hu & Ai 2020, IEEE TIP 29:3296):
a raised-cosine angular spread, phase congruency per orientation, its maximum and minimum moments
(edge and corner maps), and the orientation-amplitude stack CS_o = sum_s |EO_so| whose arg max over
orientations is the Maximum Index Map (MIM).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..fourier import fft2, ifft2


@dataclass(frozen=True)
class PhaseCongruencyParams:
    """Kovesi's ``phasecong2`` defaults (spec 002, section 2.10).

    ``angular`` is the angular spread of the filters: 'gaussian' (``phasecong2``, width
    ``pi / norient / d_theta_on_sigma``) or 'cosine' (``phasecong3``: a raised cosine reaching zero
    at the neighbouring orientation); ``threshold_divisor`` scales the noise threshold
    (``phasecong2`` divides it by 1.7, ``phasecong3`` does not).
    """

    nscale: int = 4
    norient: int = 6
    min_wavelength: float = 3.0
    mult: float = 2.1
    sigma_onf: float = 0.55
    d_theta_on_sigma: float = 1.2
    k: float = 2.0
    cut_off: float = 0.5
    g: float = 10.0
    eps: float = 1e-4
    angular: str = "gaussian"
    threshold_divisor: float = 1.7


# RIFT / RIFT2's call: phasecong3(im, 4, 6, 3, 'mult', 1.6, 'sigmaOnf', 0.75, 'g', 3, 'k', 1): four
# scales from a 3-px wavelength (3-15 px, the structures that survive modality changes), six
# orientations 30 degrees apart (the MIM's resolution), a broad radial bandwidth, a soft weight.
RIFT_PARAMS = PhaseCongruencyParams(mult=1.6, sigma_onf=0.75, k=1.0, g=3.0, angular="cosine", threshold_divisor=1.0)


@lru_cache(maxsize=8)
def _filters(rows: int, cols: int, params: PhaseCongruencyParams):
    """Per orientation, the complex64-ready filters (log-Gabor x angular spread) of every scale,
    stacked (nscale, rows, cols)."""
    p = params
    fy = np.fft.fftfreq(rows)[:, None]
    fx = np.fft.fftfreq(cols)[None, :]
    radius = np.sqrt(fx ** 2 + fy ** 2)
    radius[0, 0] = 1.0
    theta = np.arctan2(-fy, fx)
    lowpass = 1.0 / (1.0 + (radius / 0.45) ** (2 * 15))
    log_gabor = []
    for s in range(p.nscale):
        fo = 1.0 / (p.min_wavelength * p.mult ** s)
        lg = np.exp(-(np.log(radius / fo)) ** 2 / (2 * math.log(p.sigma_onf) ** 2)) * lowpass
        lg[0, 0] = 0.0
        log_gabor.append(lg)
    theta_sigma = math.pi / p.norient / p.d_theta_on_sigma
    sin_t, cos_t = np.sin(theta), np.cos(theta)
    out = []
    for o in range(p.norient):
        angle = o * math.pi / p.norient
        ds = sin_t * math.cos(angle) - cos_t * math.sin(angle)
        dc = cos_t * math.cos(angle) + sin_t * math.sin(angle)
        if p.angular == "cosine":
            spread = (np.cos(np.minimum(np.abs(np.arctan2(ds, dc)) * p.norient / 2, math.pi)) + 1) / 2
        else:
            spread = np.exp(-np.arctan2(ds, dc) ** 2 / (2 * theta_sigma ** 2))
        out.append(np.stack([(lg * spread).astype(np.float32) for lg in log_gabor]))
    return out


def _orientations(image: np.ndarray, p: PhaseCongruencyParams):
    """Per orientation: (summed amplitude over scales, frequency-spread-weighted noise-thresholded
    energy), both (H, W) float32."""
    img = image.astype(np.float32)
    rows, cols = img.shape
    spectrum = fft2(img)
    eps = np.float32(p.eps)
    for filters in _filters(rows, cols, p):
        eo = ifft2(spectrum * filters)  # every scale at once: same values, faster
        amplitude = np.abs(eo)
        sum_an = amplitude.sum(axis=0)
        max_an = amplitude.max(axis=0)
        sum_e = eo.real.sum(axis=0)
        sum_o = eo.imag.sum(axis=0)
        x_energy = np.sqrt(sum_e ** 2 + sum_o ** 2) + eps
        mean_e, mean_o = sum_e / x_energy, sum_o / x_energy
        energy = np.zeros((rows, cols), np.float32)
        for e in eo:
            energy += e.real * mean_e + e.imag * mean_o - np.abs(e.real * mean_o - e.imag * mean_e)
        tau = np.median(amplitude[0]) / math.sqrt(math.log(4))
        total_tau = tau * (1 - (1 / p.mult) ** p.nscale) / (1 - 1 / p.mult)
        noise_mean = total_tau * math.sqrt(math.pi / 2)
        noise_sigma = total_tau * math.sqrt((4 - math.pi) / 2)
        threshold = np.float32((noise_mean + p.k * noise_sigma) / p.threshold_divisor)
        energy = np.maximum(energy - threshold, 0.0)
        width = (sum_an / (max_an + eps) - 1) / max(p.nscale - 1, 1)
        weight = 1.0 / (1.0 + np.exp((p.cut_off - width) * p.g))
        yield sum_an, weight * energy


def phase_congruency(image: np.ndarray, params: PhaseCongruencyParams = PhaseCongruencyParams()) -> np.ndarray:
    """(H, W) float32 phase congruency of ``image``."""
    rows, cols = image.shape
    energy_all = np.zeros((rows, cols), np.float32)
    an_all = np.zeros((rows, cols), np.float32)
    for sum_an, energy in _orientations(image, params):
        energy_all += energy
        an_all += sum_an
    return (energy_all / (an_all + np.float32(params.eps))).astype(np.float32)


def log_gabor_maps(image: np.ndarray, params: PhaseCongruencyParams = RIFT_PARAMS):
    """RIFT's maps of ``image``: a dict with ``mim`` (H, W) int (arg max over orientations of
    the scale-summed amplitude), ``cs`` (norient, H, W) that amplitude stack, and ``M`` / ``m``
    (H, W) the maximum (edge) and minimum (corner) moments of phase congruency over orientations."""
    rows, cols = image.shape
    cs = np.empty((params.norient, rows, cols), np.float32)
    a = np.zeros((rows, cols), np.float32)
    b, c = np.zeros_like(a), np.zeros_like(a)
    eps = np.float32(params.eps)
    for o, (sum_an, energy) in enumerate(_orientations(image, params)):
        cs[o] = sum_an
        pc = energy / (sum_an + eps)
        angle = o * math.pi / params.norient
        cx, cy = pc * np.float32(math.cos(angle)), pc * np.float32(math.sin(angle))
        a += cx * cx
        b += cx * cy
        c += cy * cy
    a, b, c = a / (params.norient / 2), 4 * b / params.norient, c / (params.norient / 2)
    denom = np.sqrt(b ** 2 + (a - c) ** 2) + eps
    return {"mim": np.argmax(cs, axis=0), "cs": cs, "M": (c + a + denom) / 2, "m": (c + a - denom) / 2}
