"""Correlating a site's template with the target, in the frequency domain: the spectra of CFOG
descriptor templates and search areas (:class:`TemplateSpectrum`, :class:`SearchSpectrum`), whose
product gives the normalised cross-correlation surface over the search range, the template turned
and mirrored (wrong alignments for the chance estimate), how far a surface's zero-offset value
stands above the rest, and how far its best value away from zero exceeds its best value near zero.
Coordinates: surfaces are indexed by offset in full-resolution reference pixels, ``s`` (the search
range) at zero offset.
"""
from __future__ import annotations

import copy
from functools import lru_cache

import numpy as np

from ..fourier import fast_length  # noqa: F401 (the site canvases' length, used by verify)


def turned(stack: np.ndarray):
    """The CFOG template turned by 180 degrees and mirrored in x and in y, its orientation channels
    following (orientations are modulo 180 degrees, so a half turn keeps them; a mirror reverses them)."""
    reverse = np.r_[0, np.arange(len(stack) - 1, 0, -1)]
    return (stack[:, ::-1, ::-1], stack[reverse][:, :, ::-1], stack[reverse][:, ::-1, :])


class TemplateSpectrum:
    """A (C, t, t) descriptor template, zero-mean over all channels, as the conjugate spectrum of its
    zero-padded ``shape`` canvas, with its norm."""

    def __init__(self, template: np.ndarray, shape):
        t = template - template.mean()
        self.norm = float(np.sqrt((t ** 2).sum()))
        spectrum = np.fft.rfft2(t, shape, axes=(1, 2))
        self.spectrum = np.conj(spectrum, out=spectrum)
        self.size, self.side = template.size, template.shape[-1]

    def turned(self) -> tuple:
        """The spectra of the :func:`turned` templates, from this one: turning or mirroring a real
        template conjugates its spectrum or reverses its frequencies, times a phase ramp (no FFT)."""
        c, n, half = self.spectrum.shape
        both, x, y = _ramps(n, half, self.side)
        reverse = np.r_[0, np.arange(c - 1, 0, -1)]
        flipped_y = self.spectrum[np.ix_(reverse, (-np.arange(n)) % n)]
        np.conj(flipped_y, out=flipped_y)
        mirrored_x = np.conj(flipped_y)
        spectra = (np.multiply(both, self.spectrum), np.multiply(x, mirrored_x, out=mirrored_x),
                   np.multiply(y, flipped_y, out=flipped_y))
        return tuple(self._with(np.conj(g, out=g)) for g in spectra)

    def _with(self, spectrum: np.ndarray) -> "TemplateSpectrum":
        other = copy.copy(self)
        other.spectrum = spectrum
        return other


class SearchSpectrum:
    """A (C, t + 2s, t + 2s) descriptor search area as spectra of its zero-padded ``shape`` canvas (at least
    the area's size; any larger size gives the same surface), with its window sums for NCC."""

    def __init__(self, search: np.ndarray, side: int, shape=None):
        self.shape = tuple(shape or search.shape[1:])
        self.spectrum = np.fft.rfft2(search, self.shape, axes=(1, 2))
        self.s1 = window_sums(search.sum(axis=0, dtype=np.float64), side)
        squares = search.astype(np.float64)
        self.s2 = window_sums(np.square(squares, out=squares).sum(axis=0), side)

    def ncc(self, template: "TemplateSpectrum", s: int) -> np.ndarray:
        """(2s + 1, 2s + 1) normalised cross-correlation surface (as :func:`ncc_surface`), ``s`` at most the
        search area's margin around the template."""
        # irfft2, as numpy computes it (columns, then rows), with the rows no surface needs left out
        columns = np.fft.ifft((self.spectrum * template.spectrum).sum(axis=0), self.shape[0], axis=0)
        num = np.fft.irfft(columns[:2 * s + 1], self.shape[1], axis=1)[:, :2 * s + 1]
        s1, s2 = self.s1[:2 * s + 1, :2 * s + 1], self.s2[:2 * s + 1, :2 * s + 1]
        var = np.maximum(s2 - s1 ** 2 / template.size, 0.0)
        return num / np.maximum(np.sqrt(var) * template.norm, 1e-9)


@lru_cache(maxsize=None)
def _ramps(n: int, half: int, side: int):
    """Phase ramps that move a turned or mirrored ``side`` px template back to the canvas's corner: in
    both axes, in x, in y (read only, shared)."""
    ky, kx = np.arange(n)[:, None], np.arange(half)[None, :]
    ramp = -2j * np.pi * (side - 1) / n
    return tuple(_frozen(np.exp(ramp * k)) for k in (ky + kx, kx + 0 * ky, ky + 0 * kx))


def window_sums(a: np.ndarray, side: int) -> np.ndarray:
    """Sums of ``a`` over every ``side`` x ``side`` window inside it, indexed by the window's top-left corner,
    from cumulative sums in double precision."""
    c = np.zeros((a.shape[0] + 1, a.shape[1] + 1))
    c[1:, 1:] = np.cumsum(np.cumsum(a, axis=0), axis=1)
    return c[side:, side:] - c[:-side, side:] - c[side:, :-side] + c[:-side, :-side]


def margin(surface: np.ndarray, s: int, radius: float) -> float:
    """How far the surface's best value beyond ``radius`` of zero offset exceeds its best value within."""
    inside = _disc(s, radius)
    return float(surface[~inside].max() - surface[inside].max())


def zero_score(surface: np.ndarray, s: int) -> float:
    """How far the correlation at zero offset stands above the surface's values 4 px or more away
    (in their standard deviations)."""
    ring = surface[_ring(s)]
    return float((surface[s, s] - ring.mean()) / max(float(ring.std()), 1e-6))


@lru_cache(maxsize=None)
def _disc(s: int, radius: float) -> np.ndarray:
    """(2s + 1, 2s + 1) True within ``radius`` of zero offset (a surface's mask, the same for every site)."""
    yy, xx = np.mgrid[-s:s + 1, -s:s + 1]
    return _frozen(xx * xx + yy * yy <= radius * radius)


@lru_cache(maxsize=None)
def _ring(s: int) -> np.ndarray:
    """(2s + 1, 2s + 1) True 4 px or more from zero offset along x or y."""
    yy, xx = np.mgrid[-s:s + 1, -s:s + 1]
    return _frozen(np.maximum(np.abs(xx), np.abs(yy)) >= 4)


def _frozen(mask: np.ndarray) -> np.ndarray:
    mask.setflags(write=False)  # shared by every call: read only
    return mask
