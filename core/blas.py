"""Whether numpy's matrix products run on an optimised BLAS in this process.

QGIS's executables (``qgis``, ``qgis_process``) on Linux link GSL, whose reference CBLAS (``libgslcblas``)
is then loaded before Python. ELF symbol lookup takes the first definition loaded, so numpy's calls to
``cblas_sgemm`` go to GSL's textbook loops instead of OpenBLAS: a large matrix product takes 30 to 50
times longer there. Code whose speed rests on large matrix products asks :func:`reference_blas` and takes
another route (OpenCV's brute force) where it is true. Coordinates: none.
"""
from __future__ import annotations

import ctypes
import os
from functools import lru_cache


class _DlInfo(ctypes.Structure):
    _fields_ = [("dli_fname", ctypes.c_char_p), ("dli_fbase", ctypes.c_void_p),
                ("dli_sname", ctypes.c_char_p), ("dli_saddr", ctypes.c_void_p)]


# PyPI's numpy wheels carry their own OpenBLAS under renamed symbols, which nothing else defines.
OWN_BLAS = ("scipy-openblas", "openblas64")


@lru_cache(maxsize=1)
def reference_blas() -> bool:
    """True when numpy's ``cblas_sgemm`` is the process-wide one and that is GSL's reference CBLAS."""
    import numpy as np

    if os.name != "posix":
        return False  # Windows and macOS bind each library's symbols to its own dependencies
    config = getattr(np.__config__, "CONFIG", {})  # numpy 1.26 and later
    if str(config.get("Build Dependencies", {}).get("blas", {}).get("name", "")).startswith(OWN_BLAS):
        return False
    try:
        process = ctypes.CDLL(None)
        address = ctypes.cast(process.cblas_sgemm, ctypes.c_void_p).value
        info = _DlInfo()
        if not process.dladdr(ctypes.c_void_p(address), ctypes.byref(info)):
            return False
    except (AttributeError, OSError):  # no global cblas_sgemm: numpy's own BLAS serves it
        return False
    return b"gslcblas" in (info.dli_fname or b"")
