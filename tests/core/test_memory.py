"""A run caps the C library's heaps, so a long-lived process does not keep each thread's fragments."""
import os
import platform
import subprocess
import sys

import pytest

CHILD = r"""
import ctypes, os, sys, tempfile, threading
import numpy as np
from hamta.core.io.scope import run_scope

def heaps():
    libc = ctypes.CDLL("libc.so.6")
    libc.fopen.restype = ctypes.c_void_p
    libc.malloc_info.argtypes = [ctypes.c_int, ctypes.c_void_p]
    libc.fclose.argtypes = [ctypes.c_void_p]
    path = tempfile.mktemp()
    stream = libc.fopen(path.encode(), b"w")
    libc.malloc_info(0, stream)
    libc.fclose(stream)
    text = open(path).read()
    os.remove(path)
    return text.count("<heap nr=")

with run_scope():
    pass

together = threading.Barrier(16)

def work():
    together.wait()
    held = [np.ones(1000) for _ in range(2000)]
    together.wait()

threads = [threading.Thread(target=work) for _ in range(16)]
for t in threads:
    t.start()
for t in threads:
    t.join()
print(heaps())
"""


def _heaps(env):
    out = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    return int(out.stdout.strip().splitlines()[-1])


@pytest.mark.skipif(not sys.platform.startswith("linux") or "glibc" not in " ".join(platform.libc_ver()),
                    reason="glibc's heaps")
def test_threads_share_two_heaps_unless_the_user_chose():
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    assert _heaps(env) <= 2
    assert _heaps(dict(env, MALLOC_ARENA_MAX="6")) > 2
