"""One HTTP GET bounded against any server: a deadline for the whole request, a cap on the answer's bytes,
redirects to http(s) only, and an end within moments of a cancel.

Built on the standard library's ``http.client`` (its parser and header limits; TLS through ``ssl``'s
default context, which verifies certificates). No client library bounds a whole request: urllib3 and
httpx time each read, so a server that drips a byte a second never trips them, and ending a run at once
on Ctrl-C needs the socket in hand. :class:`Watch` shuts a request's socket down at its deadline or on a
cancel, which ends whatever read is waiting on it.
"""
from __future__ import annotations

import http.client
import socket
import ssl
import threading
import time
from dataclasses import dataclass
from typing import Dict, List, Optional
from urllib.parse import urljoin, urlsplit

from ..text import printable
from ..version import __version__

MAX_REDIRECTS = 5
CHUNK = 1 << 16
REDIRECT_STATUS = (301, 302, 303, 307, 308)


class Failure(Exception):
    """A request that did not bring a usable answer; ``retry``: whether asking again may help."""

    def __init__(self, text: str, retry: bool):
        super().__init__(text)
        self.retry = retry


class Canceled(Exception):
    """The run was canceled while the request was in flight."""


@dataclass
class Answer:
    status: int
    reason: str  # the server's words, made printable
    body: bytes
    complete: bool  # the body's end was marked (a length or the last chunk), not only a closed connection


class Watch:
    """The sockets of the requests in flight: each is shut down at its deadline, all of them on
    :meth:`cancel`; a daemon thread keeps the time until the cancel that ends every fetch, so nothing
    waits on it at exit."""

    def __init__(self):
        self._lock = threading.Condition()
        self._open: Dict[socket.socket, float] = {}
        self._expired = set()
        self.canceled = False
        self._thread: Optional[threading.Thread] = None

    def add(self, sock: socket.socket, deadline: float) -> socket.socket:
        """Watch ``sock`` (through a duplicate, which stays valid when TLS takes the original over)."""
        watched = sock.dup()
        with self._lock:
            if self.canceled:
                _shut(watched)
            self._open[watched] = deadline
            if self._thread is None:
                self._thread = threading.Thread(target=self._keep_time, name="hamta-http-watch", daemon=True)
                self._thread.start()
            self._lock.notify()
        return watched

    def done(self, watched: socket.socket) -> bool:
        """Stop watching; whether the socket was shut for its deadline."""
        with self._lock:
            self._open.pop(watched, None)
            expired = watched in self._expired
            self._expired.discard(watched)
        watched.close()
        return expired

    def cancel(self) -> None:
        with self._lock:
            self.canceled = True
            for watched in self._open:
                _shut(watched)
            self._lock.notify()

    def _keep_time(self) -> None:
        with self._lock:
            while not self.canceled:  # a cancel has shut every socket, and shuts any added later
                now = time.monotonic()
                for watched, deadline in list(self._open.items()):
                    if deadline <= now and watched not in self._expired:
                        self._expired.add(watched)
                        _shut(watched)
                pending = [d for w, d in self._open.items() if w not in self._expired]
                self._lock.wait(max(0.01, min(pending) - now) if pending else None)


def _shut(sock: socket.socket) -> None:
    try:
        sock.shutdown(socket.SHUT_RDWR)
    except OSError:
        pass


def get(url: str, watch: Watch, timeout_s: float, max_bytes: int) -> Answer:
    """GET ``url``, following up to ``MAX_REDIRECTS`` redirects to http(s) addresses; the whole exchange
    ends within ``timeout_s``; a body above ``max_bytes`` (declared or streamed) is refused. Raises
    :class:`Failure` (its text for a user, the server's words made printable) or :class:`Canceled`."""
    deadline = time.monotonic() + timeout_s
    for _ in range(MAX_REDIRECTS + 1):
        scheme = urlsplit(url).scheme.lower()
        if scheme not in ("http", "https"):
            raise Failure(f"redirected to a '{printable(scheme, 20)}:' address (only http and https are followed)",
                          retry=False)
        answer, location = _once(url, watch, deadline, timeout_s, max_bytes)
        if location is None:
            return answer
        url = urljoin(url, location)
    raise Failure(f"redirected more than {MAX_REDIRECTS} times", retry=False)


def _once(url: str, watch: Watch, deadline: float, timeout_s: float, max_bytes: int):
    """One exchange: (the answer, None) or (None, the address a redirect points to)."""
    if watch.canceled:
        raise Canceled()
    parts = urlsplit(url)
    remaining = deadline - time.monotonic()
    if remaining <= 0:
        raise Failure(f"gave no whole answer within {timeout_s:g} s", retry=True)
    try:
        port = parts.port
    except ValueError:
        raise Failure("has an address whose port is not a number", retry=False) from None
    kind = WatchedHTTPSConnection if parts.scheme.lower() == "https" else WatchedConnection
    conn = kind.watched_by(watch, deadline, parts.hostname or "", port, timeout=remaining)
    path = (parts.path or "/") + (f"?{parts.query}" if parts.query else "")
    try:
        conn.request("GET", path, headers={"User-Agent": f"Hamta/{__version__} (georeferencing)",
                                           "Accept-Encoding": "identity"})
        response = conn.getresponse()
        reason = printable(response.reason, 80)
        if response.status in REDIRECT_STATUS:
            location = response.getheader("Location")
            if not location:
                raise Failure(f"answered HTTP {response.status} {reason} without a Location", retry=False)
            return None, location
        body, complete = _body(response, max_bytes) if 200 <= response.status < 300 else (b"", True)
        return Answer(response.status, reason, body, complete), None
    except (Failure, Canceled):
        raise
    except (OSError, http.client.HTTPException, ValueError) as exc:
        expired = any([watch.done(w) for w in conn.held])  # every one released
        conn.held.clear()
        if watch.canceled:
            raise Canceled() from None
        if expired or isinstance(exc, (socket.timeout, TimeoutError)):
            raise Failure(f"gave no whole answer within {timeout_s:g} s", retry=True) from None
        raise _failure(exc) from None
    finally:
        for w in conn.held:
            watch.done(w)
        conn.close()


class WatchedConnection(http.client.HTTPConnection):
    """An HTTP connection whose socket :meth:`connect` hands to ``watch`` as soon as it is connected, to be
    shut at ``deadline`` or on a cancel; ``held`` keeps the duplicates to release through :meth:`Watch.done`."""

    watch: Watch
    deadline: float
    held: List[socket.socket]

    @classmethod
    def watched_by(cls, watch: Watch, deadline: float, host: str, port: Optional[int], timeout: float):
        """A connection to ``host``:``port`` (``timeout``: seconds, for each socket operation) watched by ``watch``."""
        conn = cls(host, port, timeout=timeout)
        conn.watch, conn.deadline, conn.held = watch, deadline, []
        return conn

    def connect(self) -> None:
        """Connect as the standard library does, then watch the socket."""
        super().connect()
        self.held.append(self.watch.add(self.sock, self.deadline))


class WatchedHTTPSConnection(http.client.HTTPSConnection, WatchedConnection):
    """HTTPS over a :class:`WatchedConnection`: ``HTTPSConnection.connect`` opens the connection through
    ``super().connect()``, which these bases make :meth:`WatchedConnection.connect`, so the socket is watched
    from before the TLS handshake; the handshake is the standard library's own (its default context: the
    certificate verified, the URL's host sent as SNI and checked against the certificate)."""


def _body(response, max_bytes: int):
    declared = response.getheader("Content-Length")
    if declared is not None and declared.strip().isdigit() and int(declared) > max_bytes:
        raise Failure(f"announced an answer of {int(declared):,} bytes, above the {max_bytes:,} a tile may have",
                      retry=False)
    chunks, size = [], 0
    while True:
        chunk = response.read(CHUNK)
        if not chunk:
            break
        size += len(chunk)
        if size > max_bytes:
            raise Failure(f"sent more than the {max_bytes:,} bytes a tile may have", retry=False)
        chunks.append(chunk)
    if declared is not None and declared.strip().isdigit() and size < int(declared):
        raise Failure(f"broke its answer off ({size:,} of {int(declared):,} bytes)", retry=True)
    return b"".join(chunks), bool(response.chunked or declared is not None)


def _failure(exc: BaseException) -> Failure:
    if isinstance(exc, ConnectionRefusedError):
        return Failure("refused the connection (is the server running?)", retry=False)
    if isinstance(exc, socket.gaierror):
        return Failure("cannot be reached: its name cannot be resolved (is the address right, the network up?)",
                       retry=False)
    if isinstance(exc, ssl.SSLCertVerificationError):
        return Failure(f"has a certificate that cannot be trusted ({printable(exc.verify_message, 80)})", retry=False)
    return Failure(f"broke its answer off or garbled it ({type(exc).__name__})", retry=True)
