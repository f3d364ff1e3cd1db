"""Fuzzed map-server answers (status line, headers, body, timing, a cut or reset connection) played by
:class:`hamta.bench.hostile.HostileServer` to the fetcher: every answer ends, within its bounds, as a tile,
a missing tile or a :class:`ServiceError` whose message is printable and holds no secret; nothing else.
``make test`` runs a bounded profile; ``make fuzz`` runs ``HAMTA_FUZZ_EXAMPLES`` answers (its tally in
``$HAMTA_FUZZ_LOG``)."""
import json
import os
import struct
import time
import zlib

import cv2
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hamta.bench.hostile import SECRET, HostileServer
from hamta.core.basemap.fetch import Fetcher, ServiceError
from hamta.core.basemap.tiles import decode_tile

EXAMPLES = int(os.environ.get("HAMTA_FUZZ_EXAMPLES", 40)) if os.environ.get("HYPOTHESIS_PROFILE") == "long" else 40
LOG = os.environ.get("HAMTA_FUZZ_LOG")
GOOD = cv2.imencode(".png", np.random.default_rng(0).integers(0, 255, (256, 256, 4), dtype=np.uint8))[1].tobytes()


def _png_declaring(width, height):
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + ihdr + struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))


bodies = st.one_of(
    st.just(GOOD), st.binary(max_size=2048), st.builds(lambda b: b"\x89PNG" + b, st.binary(max_size=2048)),
    st.builds(lambda n: GOOD[:n], st.integers(0, len(GOOD))),
    st.builds(_png_declaring, st.integers(0, 2 ** 31 - 1), st.integers(0, 2 ** 31 - 1)),
    st.builds(lambda t: t.encode("utf-8", "replace"), st.text(max_size=300)),
)
statuses = st.one_of(st.sampled_from([200, 204, 206, 301, 302, 307, 308, 404, 429, 500, 503]), st.integers(0, 999))
header_lines = st.lists(st.one_of(
    st.sampled_from(["Content-Type: image/png", "Transfer-Encoding: chunked", "Connection: close",
                     "Content-Encoding: gzip", "Location: ftp://127.0.0.1/x", "Location: /ok/1/0/0.png",
                     f"Location: http://u:{SECRET}@127.0.0.1:1/?key={SECRET}", "Content-Length: 999999999999",
                     "Content-Length: -1", "Content-Length: abc", "Content-Length: 10"]),
    st.builds(lambda k, v: f"{k}: {v}", st.text("abcXYZ-", min_size=1, max_size=12),
              st.text(st.characters(min_codepoint=32, max_codepoint=0x7e), max_size=60))), max_size=6)


@st.composite
def answers(draw):
    status, reason = draw(statuses), draw(st.text(max_size=40).map(lambda t: t.replace("\r", "").replace("\n", "")))
    headers, body = draw(header_lines), draw(bodies)
    if draw(st.booleans()):
        headers = headers + [f"Content-Length: {len(body)}"]
    head = (f"HTTP/1.1 {status} {reason}\r\n" + "".join(h + "\r\n" for h in headers) + "\r\n").encode("utf-8")
    raw = head + body
    cut = draw(st.one_of(st.none(), st.integers(0, len(raw))))
    pause = draw(st.sampled_from([0.0, 0.0, 0.0, 0.1, 0.8]))
    at = draw(st.integers(0, len(raw)))
    pieces = [(raw[:at], 0.0), (raw[at:cut], pause)]
    return pieces, draw(st.booleans()), (status, headers, len(body), cut, pause)


@pytest.fixture(scope="module")
def server():
    hostile = HostileServer(tiles=None).start()
    yield hostile
    hostile.stop()


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(answer=answers())
def test_any_server_answer_ends_as_a_tile_a_missing_tile_or_a_clear_error(server, answer):
    pieces, reset, described = answer
    server.script = lambda path: (pieces, reset)
    fetcher = Fetcher(cache=None, timeout_s=0.5, retries=1, backoff_s=0.0, budget_s=5.0)
    url = f"{server.url}/fuzz/1/0/0.png?key={SECRET}"
    start = time.monotonic()
    try:
        [(_, tile)] = list(fetcher.each([url], lambda u, b: decode_tile(u, b, 256)))
        outcome = "tile" if tile is not None else "missing"
        assert tile is None or (tile.shape == (4, 256, 256) and tile.dtype == np.uint8)
        message = ""
    except ServiceError as exc:
        outcome, message = "error", str(exc)
    took = time.monotonic() - start
    assert message.isprintable() and SECRET not in message, message
    assert took < 2 * 0.5 + 1.0, took  # two tries of 0.5 s each, and the machine's slack
    if LOG:
        with open(LOG, "a") as f:
            f.write(json.dumps({"answer": repr(described), "outcome": outcome, "rc": 1 if outcome == "error" else 0,
                                "time_s": round(took, 3)}) + "\n")
