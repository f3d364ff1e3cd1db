"""Phase congruency from log-Gabor filters (Kovesi's PC2 measure).

Kovesi, P. (1999). Image features from phase congruency. Videre 1(3), 1-26; and Kovesi, P.
(2003). Phase congruency detects corners and edges. DICTA 2003. The measure (eqs. 7-8 of spec 002)

    PC = sum_o sum_n W_o [A_no (cos(phi_no - mean_phi_o) - |sin(phi_no - mean_phi_o)|) - T_o]+
         / (sum_o sum_n A_no + eps)

is computed with ``nscale`` log-Gabor scales and ``norient`` orientations in the frequency
domain, a Rayleigh noise model estimated from the smallest scale per orientation (threshold
``T = (mean + k sigma) / 1.7`` as in Kovesi's ``phasecong2``) and the frequency-spread weight W.
PC lies in [0, 1] and does not depend on image contrast.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import fft


@dataclass(frozen=True)
class PhaseCongruencyParams:
    """Kovesi's ``phasecong2`` defaults (spec 002, section 2.10)."""

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


@lru_cache(maxsize=4)
def _filters(rows: int, cols: int, params: PhaseCongruencyParams):
    """Per orientation, the complex64-ready filters (log-Gabor x angular spread) of every scale."""
    p = params
    fy = fft.fftfreq(rows)[:, None]
    fx = fft.fftfreq(cols)[None, :]
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
        spread = np.exp(-np.arctan2(ds, dc) ** 2 / (2 * theta_sigma ** 2))
        out.append([(lg * spread).astype(np.float32) for lg in log_gabor])
    return out


def phase_congruency(image: np.ndarray, params: PhaseCongruencyParams = PhaseCongruencyParams()) -> np.ndarray:
    """(H, W) float32 phase congruency of ``image``."""
    p = params
    img = image.astype(np.float32)
    rows, cols = img.shape
    spectrum = fft.fft2(img, workers=-1).astype(np.complex64)
    energy_all = np.zeros((rows, cols), np.float32)
    an_all = np.zeros((rows, cols), np.float32)
    eps = np.float32(p.eps)
    for filters in _filters(rows, cols, params):
        eo = [fft.ifft2(spectrum * f, workers=-1) for f in filters]
        amplitude = [np.abs(e) for e in eo]
        sum_an = np.sum(amplitude, axis=0)
        max_an = np.max(amplitude, axis=0)
        sum_e = np.sum([e.real for e in eo], axis=0)
        sum_o = np.sum([e.imag for e in eo], axis=0)
        x_energy = np.sqrt(sum_e ** 2 + sum_o ** 2) + eps
        mean_e, mean_o = sum_e / x_energy, sum_o / x_energy
        energy = np.zeros((rows, cols), np.float32)
        for e in eo:
            energy += e.real * mean_e + e.imag * mean_o - np.abs(e.real * mean_o - e.imag * mean_e)
        tau = np.median(amplitude[0]) / math.sqrt(math.log(4))
        total_tau = tau * (1 - (1 / p.mult) ** p.nscale) / (1 - 1 / p.mult)
        noise_mean = total_tau * math.sqrt(math.pi / 2)
        noise_sigma = total_tau * math.sqrt((4 - math.pi) / 2)
        threshold = np.float32((noise_mean + p.k * noise_sigma) / 1.7)
        energy = np.maximum(energy - threshold, 0.0)
        width = (sum_an / (max_an + eps) - 1) / max(p.nscale - 1, 1)
        weight = 1.0 / (1.0 + np.exp((p.cut_off - width) * p.g))
        energy_all += weight * energy
        an_all += sum_an
    return (energy_all / (an_all + eps)).astype(np.float32)
