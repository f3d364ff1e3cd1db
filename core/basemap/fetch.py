"""HTTP fetching for map services: parallel, bounded, retried, cached on disk, cancellable.

Only the standard library (``urllib``) is used. A response is cached under a hash of its URL,
so a rerun or a batch over the same area sends no request. Every failure ends as a
:class:`ServiceError` naming the host and what went wrong, never a traceback.
"""
from __future__ import annotations

import hashlib
import http.client
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
from .redact import redact

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

    ``timeout_s`` bounds each socket operation of a request; a time-out, a broken connection or
    answer, or a status in ``RETRY_STATUS`` is retried ``retries`` times after ``backoff_s``, doubled
    each time. ``max_requests`` caps the requests of the run, retries included (cache hits are
    free). ``cache`` is a folder (None: no disk cache); only answers that ``get_many``'s ``valid``
    accepts are kept there, so an error page is asked for again next time.
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

    def get_many(self, urls: Sequence[str], monitor=None, valid=None) -> List[Optional[bytes]]:
        """The body of each URL (None for a tile the service does not have), in order.

        ``monitor`` (a :class:`hamta.core.progress.Monitor`) gets progress and may cancel. ``valid(url,
        body)`` raises :class:`ServiceError` for a body that is not what was asked for (it is not cached).
        """
        start = time.perf_counter()
        bodies: List[Optional[bytes]] = [None] * len(urls)
        todo = []
        for i, url in enumerate(urls):
            cached = self._cached(url)
            if cached is None:
                todo.append(i)
            else:
                bodies[i] = cached
                self.stats.cache_hits += 1
        if todo and len(todo) > self.max_requests - self.stats.requests:
            raise ServiceError(f"The map service at {host(urls[todo[0]])} would need {len(todo)} more requests, above "
                               f"the cap of {self.max_requests} per run: choose a smaller search area.")
        done, stop = len(urls) - len(todo), threading.Event()
        pool = ThreadPoolExecutor(max_workers=max(1, self.workers))
        pending = {pool.submit(self._fetch, urls[i], stop, valid): i for i in todo}
        try:
            while pending:
                finished, _ = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
                for future in finished:
                    bodies[pending.pop(future)] = future.result()
                    done += 1
                if monitor is not None:
                    monitor.report(done / max(1, len(urls)), f"fetching tiles {done}/{len(urls)}")
        except BaseException:
            stop.set()  # requests in flight end at their time-out; nobody waits for them
            raise
        finally:
            pool.shutdown(wait=not stop.is_set(), cancel_futures=True)
            self.stats.seconds += time.perf_counter() - start
        return bodies

    def _fetch(self, url: str, stop: threading.Event, valid) -> Optional[bytes]:
        delay = self.backoff_s
        for attempt in range(self.retries + 1):
            with self._lock:
                if stop.is_set():
                    raise RegistrationCanceled("Registration canceled; no outputs were written.")
                if self.stats.requests >= self.max_requests:
                    raise ServiceError(f"The map service at {host(url)} was sent the {self.max_requests} requests a "
                                       "run may send (retries included): choose a smaller search area.")
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
            if body is not None:
                if valid is not None:
                    valid(url, body)
                self._store(url, body)
            return body
        return None  # not reached

    def _request(self, url: str) -> Optional[bytes]:
        """The body (None for a missing tile: HTTP 204 or 404, or an empty answer)."""
        request = urllib.request.Request(url, headers={"User-Agent": f"Hamta/{__version__} (georeferencing)"})
        try:
            with urllib.request.urlopen(request, timeout=self.timeout_s) as answer:
                body = answer.read()
                return None if answer.status in MISSING_STATUS or not body else body
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
        except (http.client.HTTPException, ConnectionError, OSError) as exc:  # a cut or garbled answer
            raise _Retry(f"the answer was broken off or garbled ({type(exc).__name__})") from None

    def _path(self, url: str) -> Optional[str]:
        if not self.cache:
            return None
        digest = hashlib.sha256(url.encode()).hexdigest()
        return os.path.join(self.cache, "http", digest[:2], digest)

    def _cached(self, url: str) -> Optional[bytes]:
        path = self._path(url)
        if path is None or not os.path.isfile(path):
            return None
        with open(path, "rb") as f:
            return f.read() or None

    def forget(self, url: str) -> None:
        """Drop ``url``'s cached answer (one found unusable)."""
        path = self._path(url)
        if path is not None and os.path.isfile(path):
            os.remove(path)

    def _store(self, url: str, body: bytes) -> None:
        path = self._path(url)
        if path is not None:
            write_whole(path, body)


def write_whole(path: str, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary name (a reader never sees part of it); a cache
    that cannot be written only costs a later refetch."""
    tmp = None
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".part")
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except OSError:
        if tmp is not None and os.path.exists(tmp):
            os.remove(tmp)


class _Retry(Exception):
    """A failure worth retrying; its text says what happened."""


def host(url: str) -> str:
    """The host (and port) of ``url``, without credentials."""
    parts = urlsplit(url)
    return parts.hostname + (f":{parts.port}" if parts.port else "") if parts.hostname else url
