"""The FFTs of the cross-modal method's start-up path (hamta.core.fourier)."""
import subprocess
import sys

import numpy as np
from scipy import fft as scipy_fft

from hamta.core import fourier


def test_fast_lengths_are_scipys():
    expected = [scipy_fft.next_fast_len(n, True) for n in range(1, 3000)]
    assert [fourier.fast_length(n) for n in range(1, 3000)] == expected


def test_transforms_keep_single_precision_and_give_scipys_values():
    rng = np.random.default_rng(3)
    image = rng.standard_normal((3, 50, 36)).astype(np.float32)
    spectrum = fourier.rfft2(image, (60, 40), axes=(1, 2))
    assert spectrum.dtype == np.complex64
    assert np.allclose(spectrum, scipy_fft.rfft2(image, (60, 40), axes=(1, 2)), rtol=0, atol=1e-4)
    back = fourier.irfft2(spectrum, (60, 40), axes=(1, 2))
    assert back.dtype == np.float32 and np.allclose(back[:, :50, :36], image, rtol=0, atol=1e-5)
    full = fourier.fft2(image[0])
    assert full.dtype == np.complex64 and np.allclose(full, scipy_fft.fft2(image[0]), rtol=0, atol=1e-4)
    assert np.allclose(fourier.ifft2(full).real, image[0], rtol=0, atol=1e-5)


def test_opencvs_complex_transforms_give_numpys_values_in_single_precision():
    """The OpenCV path (numpy 2 stacks), checked on every stack: odd and prime sizes, a stack of spectra."""
    rng = np.random.default_rng(5)
    image = rng.standard_normal((37, 50)).astype(np.float32)
    spectrum = fourier._opencv_fft2(image)
    assert spectrum.dtype == np.complex64 and spectrum.shape == image.shape
    assert np.allclose(spectrum, np.fft.fft2(image.astype(np.float64)), rtol=0, atol=2e-4)
    stack = (rng.standard_normal((2, 3, 37, 50)) + 1j * rng.standard_normal((2, 3, 37, 50))).astype(np.complex64)
    back = fourier._opencv_ifft2(stack)
    assert back.dtype == np.complex64 and back.shape == stack.shape
    assert np.allclose(back, np.fft.ifft2(stack.astype(np.complex128)), rtol=0, atol=1e-6)
    assert np.allclose(fourier._opencv_ifft2(spectrum), image, rtol=0, atol=1e-5)


def test_the_cross_modal_method_imports_scipys_fft_only_where_numpy_computes_in_double():
    code = "import sys, hamta.core.methods.xmodal; print('scipy.fft' in sys.modules)"
    out = subprocess.run([sys.executable, "-P", "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == str(not fourier.SINGLE_PRECISION)
