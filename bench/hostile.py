"""A misbehaving map server on 127.0.0.1, for the suite's hostile-server matrix and the fuzz of answers.

``HostileServer(tiles).start()`` answers ``/<fault>/{z}/{x}/{y}.png`` (XYZ) and ``/<fault>/wms?…`` (WMS
GetMap, EPSG:3857) on raw sockets, so it can send what no well-behaved server would: bombs, endless
or dripping bodies, cut connections, escape sequences, bad redirects. ``tiles`` (a
:class:`hamta.bench.tileserver.TileServer`, not started) renders the good answers. ``FAULTS`` names
each fault. ``script`` (set by the fuzz) replaces the fault table: a function of the request's path that
returns the raw answer as a list of (bytes, pause in s) pieces and whether to close after it.
Nothing here is imported by the product.
"""
from __future__ import annotations

import socket
import struct
import threading
import time
import zlib
from urllib.parse import parse_qsl, urlsplit

from ..core.basemap.services import HALF_WORLD

SECRET = "SECRET-Do-Not-Print"


def _png_header(width: int, height: int) -> bytes:
    """A PNG that declares ``width`` x ``height`` (one scan line of data): a decompression bomb's header."""
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0" * (4 * width + 1)))
            + chunk(b"IEND", b""))


def _jpeg_header(width: int, height: int) -> bytes:
    """A small real JPEG whose frame header is rewritten to declare ``width`` x ``height``."""
    import cv2
    import numpy as np

    data = bytearray(cv2.imencode(".jpg", np.full((16, 16, 3), 128, np.uint8))[1].tobytes())
    at = data.index(b"\xff\xc0")
    data[at + 5:at + 9] = struct.pack(">HH", height, width)
    return bytes(data)


def _response(status: str, body: bytes, headers=(), length=True) -> bytes:
    head = [f"HTTP/1.1 {status}"] + list(headers) + ([f"Content-Length: {len(body)}"] if length else [])
    return ("\r\n".join(head) + "\r\n\r\n").encode("latin-1") + body


ESCAPES = "\x1b]0;pwned\x07\x1b[2J\rFAKE: registration verified\x1b[0m"

# fault -> what to send (see HostileServer._plan); 'nth' faults hit every third request only.
FAULTS = (
    "png-bomb-60k", "png-bomb-30k", "jpeg-bomb", "png-5000px", "tiff-bomb", "gif-bomb",
    "length-1e12-slow", "endless-chunked", "endless-close", "oversized-length", "oversized-streamed",
    "drip-body", "drip-headers", "silent", "slow-first-byte",
    "escape-body", "escape-reason", "escape-header", "escape-redirect",
    "cut-headers-nth", "cut-body-nth", "cut-headers-all", "cut-body-all", "reset-nth", "reset-all",
    "garbage-status", "http09", "bad-length", "negative-length", "bad-chunk", "too-many-headers", "long-header",
    "redirect-ftp", "redirect-file", "redirect-loop", "redirect-no-location", "redirect-good",
    "status-500", "status-503", "status-429", "status-403", "status-401", "status-418", "flaky-503",
    "empty-close", "empty-length0", "html-200", "truncated-png", "random-png-magic", "gzip-bomb",
    "continue-100", "http10-good", "small-tile", "grey-tile", "secret-redirect",
)


class HostileServer:
    def __init__(self, tiles, drip_s: float = 0.5):
        self.tiles, self.drip_s = tiles, drip_s
        self.requests = 0
        self.script = None
        self._counts = {}
        self._lock = threading.Lock()
        self._sock = None
        self._open = set()

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self._sock.getsockname()[1]}"

    def xyz(self, fault: str) -> str:
        return f"{self.url}/{fault}/{{z}}/{{x}}/{{y}}.png?api-key={SECRET}"

    def wms(self, fault: str) -> str:
        return (f"contextualWMSLegend=0&crs=EPSG:3857&format=image/png&layers=photo&styles="
                f"&url={self.url}/{fault}/wms?X-Auth-Token={SECRET}")

    def start(self) -> "HostileServer":
        self._sock = socket.create_server(("127.0.0.1", 0))
        self._sock.listen(64)
        threading.Thread(target=self._accept, daemon=True).start()
        return self

    def stop(self) -> None:
        if self._sock is not None:
            self._sock.close()
            self._sock = None
        for conn in list(self._open):
            try:
                conn.close()
            except OSError:
                pass

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()

    def _accept(self) -> None:
        while self._sock is not None:
            try:
                conn, _ = self._sock.accept()
            except OSError:
                return
            self._open.add(conn)
            threading.Thread(target=self._serve, args=(conn,), daemon=True).start()

    def _serve(self, conn: socket.socket) -> None:
        try:
            request = b""
            conn.settimeout(10)
            while b"\r\n\r\n" not in request and len(request) < 65536:
                data = conn.recv(4096)
                if not data:
                    return
                request += data
            path = request.split(b" ", 2)[1].decode("latin-1")
            with self._lock:
                self.requests += 1
            pieces, reset = (self.script or self._plan)(path)
            for data, pause in pieces:
                if pause:
                    time.sleep(pause)
                if data:
                    conn.sendall(data)
            if reset:
                conn.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        except (OSError, IndexError, ValueError):
            pass
        finally:
            self._open.discard(conn)
            try:
                conn.close()
            except OSError:
                pass

    def good(self, path: str) -> bytes:
        """The PNG a well-behaved server would send for ``path``."""
        parts = urlsplit(path)
        steps = [p for p in parts.path.split("/") if p]
        if steps[-1] == "wms":
            q = {k.upper(): v for k, v in parse_qsl(parts.query)}
            return self.tiles.render([float(v) for v in q["BBOX"].split(",")], int(q["WIDTH"]), int(q["HEIGHT"]),
                                     "photo")
        z, x, y = int(steps[-3]), int(steps[-2]), int(steps[-1].split(".")[0])
        size = 2 * HALF_WORLD / 2 ** z
        return self.tiles.render([-HALF_WORLD + x * size, HALF_WORLD - (y + 1) * size, -HALF_WORLD + (x + 1) * size,
                                  HALF_WORLD - y * size], 256, 256, "photo")

    def _plan(self, path: str):
        """(pieces, reset) for ``path``: the fault named by its first step, applied to this request."""
        fault = path.split("/")[1]
        with self._lock:
            n = self._counts[fault] = self._counts.get(fault, 0) + 1
            first = path not in self._counts
            self._counts[path] = True
        png = lambda: _response("200 OK", self.good(path), ["Content-Type: image/png"])  # noqa: E731
        drip = self.drip_s
        if fault.endswith("-nth") and n % 3:
            return [(png(), 0)], False
        plans = {
            "png-bomb-60k": lambda: [(_response("200 OK", _png_header(60000, 60000)), 0)],
            "png-bomb-30k": lambda: [(_response("200 OK", _png_header(30000, 30000)), 0)],
            "jpeg-bomb": lambda: [(_response("200 OK", _jpeg_header(60000, 60000)), 0)],
            "png-5000px": lambda: [(_response("200 OK", _png_header(5000, 5000)), 0)],
            "tiff-bomb": lambda: [(_response("200 OK", _tiff_header(50000, 50000)), 0)],
            "gif-bomb": lambda: [(_response("200 OK", b"GIF89a" + struct.pack("<HH", 65535, 65535) + b"\0" * 32), 0)],
            "length-1e12-slow": lambda: [(b"HTTP/1.1 200 OK\r\nContent-Length: 1000000000000\r\n\r\n", 0)]
            + [(b"\0" * 100, drip)] * 40,
            "endless-chunked": lambda: [(b"HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n", 0)]
            + [(b"10000\r\n" + b"\x89PNG" * 16384 + b"\r\n", 0)] * 4000,
            "endless-close": lambda: [(b"HTTP/1.1 200 OK\r\n\r\n\x89PNG", 0)] + [(b"\0" * 65536, 0)] * 4000,
            "oversized-length": lambda: [(_response("200 OK", b"\x89PNG" + b"\0" * (9 << 20)), 0)],
            "oversized-streamed": lambda: [(b"HTTP/1.1 200 OK\r\nConnection: close\r\n\r\n" + b"\x89PNG"
                                            + b"\0" * (9 << 20), 0)],
            "drip-body": lambda: [(b"HTTP/1.1 200 OK\r\nContent-Length: 2000\r\n\r\n", 0)]
            + [(b"\x89", drip)] * 2000,
            "drip-headers": lambda: [(bytes([c]), drip) for c in b"HTTP/1.1 200 OK\r\nX-Slow: " + b"a" * 2000],
            "silent": lambda: [(b"", 60)],
            "slow-first-byte": lambda: [(b"", 60), (png(), 0)],
            "escape-body": lambda: [(_response("200 OK", ESCAPES.encode() + SECRET.encode()), 0)],
            "escape-reason": lambda: [(_response("500 " + ESCAPES, b"", []), 0)],
            "escape-header": lambda: [(_response("302 Found", b"", ["Location: ftp://x/" + ESCAPES]), 0)],
            "escape-redirect": lambda: [(_response("302 Found", b"", ["Location: gopher" + ESCAPES + "://x"]), 0)],
            "cut-headers-nth": lambda: [(b"HTTP/1.1 200 OK\r\nContent-Ty", 0)],
            "cut-body-nth": lambda: [(png()[:-300], 0)],
            "cut-headers-all": lambda: [(b"HTTP/1.1 200 OK\r\nContent-Ty", 0)],
            "cut-body-all": lambda: [(png()[:-300], 0)],
            "reset-nth": lambda: [(b"HTTP/1.1 2", 0)],
            "reset-all": lambda: [(b"", 0)],
            "garbage-status": lambda: [(b"HELLO WORLD\r\n\r\n", 0)],
            "http09": lambda: [(self.good(path), 0)],
            "bad-length": lambda: [(b"HTTP/1.1 200 OK\r\nContent-Length: abc\r\n\r\n\x89PNG", 0)],
            "negative-length": lambda: [(b"HTTP/1.1 200 OK\r\nContent-Length: -5\r\n\r\n\x89PNG", 0)],
            "bad-chunk": lambda: [(b"HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\nZZZ\r\n\x89PNG", 0)],
            "too-many-headers": lambda: [(b"HTTP/1.1 200 OK\r\n" + b"X-A: b\r\n" * 500 + b"\r\n", 0)],
            "long-header": lambda: [(b"HTTP/1.1 200 OK\r\nX-A: " + b"b" * 200000 + b"\r\n\r\n", 0)],
            "redirect-ftp": lambda: [(_response("302 Found", b"", ["Location: ftp://127.0.0.1/x.png"]), 0)],
            "redirect-file": lambda: [(_response("301 Moved", b"", ["Location: file:///etc/passwd"]), 0)],
            "redirect-loop": lambda: [(_response("302 Found", b"", [f"Location: {path}"]), 0)],
            "redirect-no-location": lambda: [(_response("302 Found", b""), 0)],
            "redirect-good": lambda: [(_response("307 Temporary", b"", ["Location: " + path.replace(
                "/redirect-good/", "/http10-good/", 1)]), 0)],
            "secret-redirect": lambda: [(_response("302 Found", b"", [
                f"Location: http://user:{SECRET}@127.0.0.1:1/x?token={SECRET}"]), 0)],
            "status-500": lambda: [(_response("500 Internal Server Error", b"oops " + SECRET.encode()), 0)],
            "status-503": lambda: [(_response("503 Service Unavailable", b"busy"), 0)],
            "status-429": lambda: [(_response("429 Too Many Requests", b"slow down", ["Retry-After: 3600"]), 0)],
            "status-403": lambda: [(_response("403 Forbidden", b"no"), 0)],
            "status-401": lambda: [(_response("401 Unauthorized", b"no", ['WWW-Authenticate: Basic realm="x"']),
                                    0)],
            "status-418": lambda: [(_response("418 I'm a teapot", b"tea"), 0)],
            "flaky-503": lambda: [(_response("503 Busy", b"busy"), 0)] if first else [(png(), 0)],
            "empty-close": lambda: [(b"HTTP/1.1 200 OK\r\nConnection: close\r\n\r\n", 0)],
            "empty-length0": lambda: [(_response("200 OK", b""), 0)],
            "html-200": lambda: [(_response("200 OK", b"<html>" + ESCAPES.encode() + b"</html>",
                                            ["Content-Type: text/html"]), 0)],
            "truncated-png": lambda: [(_response("200 OK", self.good(path)[:200]), 0)],
            "random-png-magic": lambda: [(_response("200 OK", b"\x89PNG" + bytes(range(256)) * 8), 0)],
            "gzip-bomb": lambda: [(_response("200 OK", zlib.compress(b"\0" * (50 << 20)),
                                             ["Content-Encoding: gzip"]), 0)],
            "continue-100": lambda: [(b"HTTP/1.1 100 Continue\r\n\r\n", 0), (png(), 0)],
            "http10-good": lambda: [(b"HTTP/1.0 200 OK\r\nContent-Type: image/png\r\n\r\n" + self.good(path), 0)],
            "small-tile": lambda: [(_response("200 OK", _small(self.good(path))), 0)],
            "grey-tile": lambda: [(_response("200 OK", _grey(self.good(path))), 0)],
        }
        plan = plans.get(fault)
        if plan is None:
            return [(_response("404 Not Found", b"no such fault"), 0)], False
        return plan(), fault.startswith("reset")


def _tiff_header(width: int, height: int) -> bytes:
    """A little-endian TIFF of one 8-bit band that declares ``width`` x ``height``."""
    entries = [(256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, 8), (259, 3, 1, 1), (262, 3, 1, 1),
               (273, 4, 1, 8), (277, 3, 1, 1), (278, 4, 1, height), (279, 4, 1, width * height)]
    ifd = struct.pack("<H", len(entries)) + b"".join(struct.pack("<HHII", *e) for e in entries) + b"\0\0\0\0"
    return b"II*\x00" + struct.pack("<I", 8) + ifd


def _small(png: bytes) -> bytes:
    import cv2
    import numpy as np

    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_UNCHANGED)
    return cv2.imencode(".png", cv2.resize(image, (128, 128), interpolation=cv2.INTER_AREA))[1].tobytes()


def _grey(png: bytes) -> bytes:
    import cv2
    import numpy as np

    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_GRAYSCALE)
    return cv2.imencode(".jpg", image)[1].tobytes()
