"""HTTP fetching for map services: parallel, bounded, retried, cached on disk, cancellable.

Only the standard library (``urllib``) is used. A response is cached under a hash of its URL,
so a rerun or a batch over the same area sends no request. Every failure ends as a
:class:`ServiceError` naming the host and what went wrong, never a traceback.
"""
from __future__ import annotations

import hashlib
import os
import socket
import tempfile
import threading
import time
import urllib.error
import urllib.request
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from typing import List, Optional, Sequence
from urllib.parse import urlsplit

from ..errors import InputError, RegistrationCanceled
from ..version import __version__

RETRY_STATUS = (429, 500, 502, 503, 504)  # worth asking again after a pause
MISSING_STATUS = (204, 404)  # a tile outside the layer's coverage: empty, not a failure


class ServiceError(InputError):
    """A map service could not deliver: unreachable, an HTTP error, a time-out or too many requests."""


def default_cache() -> str:
    """``$HAMTA_CACHE`` or the user's cache folder (``$XDG_CACHE_HOME/hamta``, ``~/.cache/hamta``)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.environ.get("HAMTA_CACHE") or os.path.join(base, "hamta")


@dataclass
class FetchStats:
    """What a run asked the network for: requests sent, answers taken from the cache, bytes received."""

    requests: int = 0
    cache_hits: int = 0
    missing: int = 0
    bytes: int = 0
    seconds: float = 0.0

    def to_dict(self) -> dict:
        return {"requests": self.requests, "cache_hits": self.cache_hits, "missing": self.missing,
                "bytes": self.bytes, "seconds": round(self.seconds, 3)}


@dataclass
class Fetcher:
    """Fetches URLs for one run.

    ``timeout_s`` bounds each request; a time-out, a reset connection or a status in
    ``RETRY_STATUS`` is retried ``retries`` times after ``backoff_s``, doubled each time.
    ``max_requests`` caps the requests of the run (cache hits are free). ``cache`` is a folder
    (None: no disk cache).
    """

    cache: Optional[str] = field(default_factory=default_cache)
    timeout_s: float = 15.0
    retries: int = 3
    backoff_s: float = 0.5
    workers: int = 8
    max_requests: int = 2000
    stats: FetchStats = field(default_factory=FetchStats)

    def __post_init__(self):
        self._lock = threading.Lock()

    def get_many(self, urls: Sequence[str], monitor=None) -> List[Optional[bytes]]:
        """The body of each URL (None for a tile the service does not have), in order.

        ``monitor`` (a :class:`hamta.core.progress.Monitor`) gets progress and may cancel.
        """
        start = time.perf_counter()
        bodies: List[Optional[bytes]] = [None] * len(urls)
        todo = []
        for i, url in enumerate(urls):
            cached = self._cached(url)
            if cached is None:
                todo.append(i)
            else:
                bodies[i] = cached or None
                self.stats.cache_hits += 1
        if len(todo) > self.max_requests - self.stats.requests:
            raise ServiceError(f"The map service at {host(urls[todo[0]])} would need {len(todo)} more requests, above "
                               f"the cap of {self.max_requests} per run: choose a smaller search area.")
        done = len(urls) - len(todo)
        stop = threading.Event()
        with ThreadPoolExecutor(max_workers=max(1, self.workers)) as pool:
            pending = {pool.submit(self._fetch, urls[i], stop): i for i in todo}
            try:
                while pending:
                    finished, _ = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
                    for future in finished:
                        bodies[pending.pop(future)] = future.result()
                        done += 1
                    if monitor is not None:
                        monitor.report(done / max(1, len(urls)), "fetching the reference")
            except BaseException:
                stop.set()
                for future in pending:
                    future.cancel()
                raise
        self.stats.seconds += time.perf_counter() - start
        return bodies

    def _fetch(self, url: str, stop: threading.Event) -> Optional[bytes]:
        delay = self.backoff_s
        for attempt in range(self.retries + 1):
            if stop.is_set():
                raise RegistrationCanceled("Registration canceled; no outputs were written.")
            with self._lock:
                self.stats.requests += 1
            try:
                body = self._request(url)
            except _Retry as exc:
                if attempt == self.retries:
                    raise ServiceError(f"The map service at {host(url)} did not answer properly after "
                                       f"{self.retries + 1} {'try' if self.retries == 0 else 'tries'}: {exc} "
                                       f"({redact(url)}).") from None
                stop.wait(delay)
                delay *= 2
                continue
            with self._lock:
                self.stats.bytes += len(body or b"")
                self.stats.missing += body is None
            self._store(url, body)
            return body
        return None  # not reached

    def _request(self, url: str) -> Optional[bytes]:
        request = urllib.request.Request(url, headers={"User-Agent": f"Hamta/{__version__} (georeferencing)"})
        try:
            with urllib.request.urlopen(request, timeout=self.timeout_s) as answer:
                if answer.status in MISSING_STATUS:
                    return None
                return answer.read()
        except urllib.error.HTTPError as exc:
            if exc.code in MISSING_STATUS:
                return None
            if exc.code in RETRY_STATUS:
                raise _Retry(f"HTTP {exc.code} {exc.reason}") from None
            raise ServiceError(f"The map service at {host(url)} refused a request: HTTP {exc.code} {exc.reason} "
                               f"({redact(url)}).") from None
        except (socket.timeout, TimeoutError):
            raise _Retry(f"no answer within {self.timeout_s:g} s") from None
        except urllib.error.URLError as exc:
            reason = exc.reason
            if isinstance(reason, (socket.timeout, TimeoutError)):
                raise _Retry(f"no answer within {self.timeout_s:g} s") from None
            if isinstance(reason, ConnectionRefusedError):
                raise ServiceError(f"The map service at {host(url)} cannot be reached: the connection was refused "
                                   "(is the server running?).") from None
            raise ServiceError(f"The map service at {host(url)} cannot be reached: {reason}.") from None
        except (ConnectionError, OSError) as exc:
            raise _Retry(f"the connection failed ({exc})") from None

    def _path(self, url: str) -> Optional[str]:
        if not self.cache:
            return None
        digest = hashlib.sha256(url.encode()).hexdigest()
        return os.path.join(self.cache, "http", digest[:2], digest)

    def _cached(self, url: str) -> Optional[bytes]:
        """The cached body (b'' for a known-missing tile), or None when not cached."""
        path = self._path(url)
        if path is None or not os.path.isfile(path):
            return None
        with open(path, "rb") as f:
            return f.read()

    def _store(self, url: str, body: Optional[bytes]) -> None:
        path = self._path(url)
        if path is None:
            return
        try:
            os.makedirs(self.cache, mode=0o700, exist_ok=True)  # the user's own: other users neither read nor plant
            os.makedirs(os.path.dirname(path), exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".part")
            with os.fdopen(fd, "wb") as f:
                f.write(body or b"")
            os.replace(tmp, path)
        except OSError:
            pass  # a cache that cannot be written only costs a later refetch


class _Retry(Exception):
    """A failure worth retrying; its text says what happened."""


def host(url: str) -> str:
    """The host (and port) of ``url``, without credentials."""
    parts = urlsplit(url)
    return parts.hostname + (f":{parts.port}" if parts.port else "") if parts.hostname else url


def redact(url: str) -> str:
    """``url`` without user name, password or key-like query values (for messages and reports)."""
    from urllib.parse import parse_qsl, urlencode, urlunsplit

    parts = urlsplit(url)
    netloc = parts.hostname or ""
    if parts.port:
        netloc += f":{parts.port}"
    secret = ("key", "token", "apikey", "api_key", "access_token", "password", "passwd", "signature", "sig")
    query = [(k, "***" if k.lower() in secret else v) for k, v in parse_qsl(parts.query, keep_blank_values=True)]
    text = urlunsplit((parts.scheme, netloc, parts.path, urlencode(query, safe="{}/,:*"), ""))
    return text.replace("%7B", "{").replace("%7D", "}")
