"""Load a ``.points`` file with QGIS's own reader and print what it read as JSON.

QGIS keeps its Georeferencer in libqgis_app, outside the Python API, so this calls the exported
C++ function ``QgsGCPList::loadGcps`` (QGIS 3.22) through ctypes and decodes the returned
``QList<QgsGcpPoint>``: two QgsPointXY (x, y, isEmpty: 24 bytes each), the destination CRS (a
shared-data pointer and a QString validation hint: 16 bytes) and the enabled flag at byte 64. It runs in a
subprocess so that a layout mismatch on another QGIS version cannot crash the test session.
Usage: python3 qgis_points_reader.py FILE.points
"""
import ctypes
import json
import os
import struct
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
from qgis.core import Qgis, QgsApplication, QgsCoordinateReferenceSystem  # noqa: E402
from qgis.PyQt import sip  # noqa: E402

app = QgsApplication([], False)
app.initQgis()
core = ctypes.CDLL("libQt5Core.so.5", mode=ctypes.RTLD_GLOBAL)
lib = ctypes.CDLL(f"libqgis_app.so.{Qgis.QGIS_VERSION.split('-')[0]}", mode=ctypes.RTLD_GLOBAL)

def qstring(text):
    buf = ctypes.create_string_buffer(8)
    f = core._ZN7QString15fromUtf8_helperEPKci
    f.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
    f.restype = ctypes.c_void_p
    data = text.encode()
    f(buf, data, len(data))
    return buf

path = qstring(sys.argv[1])
err = qstring("")
default_crs = QgsCoordinateReferenceSystem("EPSG:4326")
actual_crs = QgsCoordinateReferenceSystem()
out = ctypes.create_string_buffer(8)
load = lib._ZN10QgsGCPList8loadGcpsERK7QStringRK28QgsCoordinateReferenceSystemRS3_RS0_
load.argtypes = [ctypes.c_void_p] * 5
load.restype = ctypes.c_void_p
load(out, path, sip.unwrapinstance(default_crs), sip.unwrapinstance(actual_crs), err)
d = struct.unpack("<Q", out.raw)[0]
ref, alloc, begin, end = struct.unpack("<iiii", ctypes.string_at(d, 16))
points = []
for i in range(begin, end):
    elem = struct.unpack("<Q", ctypes.string_at(d + 16 + 8 * i, 8))[0]
    sx, sy, _, dx, dy, _ = struct.unpack("<ddQddQ", ctypes.string_at(elem, 48))
    flag = ctypes.string_at(elem + 64, 1)[0]
    if flag not in (0, 1):
        sys.exit(f"unexpected QgsGcpPoint layout: enabled byte is {flag}")
    points.append([dx, dy, sx, sy, bool(flag)])
print(json.dumps({"crs_authid": actual_crs.authid(), "crs_valid": actual_crs.isValid(), "points": points}))
