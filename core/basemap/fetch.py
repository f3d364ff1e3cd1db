"""Fetching map-service tiles: parallel, bounded, retried, cached on disk, cancellable.

Each request goes through :mod:`hamta.core.basemap.http` (a deadline for the whole request, a cap on
its bytes, redirects to http(s) only). A time-out, a cut or garbled answer or a status in
``RETRY_STATUS`` is asked again; a tile that still fails is a failure of the run, never an empty tile
(only HTTP 204 and 404 are: outside the layer's coverage). Answers are decoded by the caller's
``decode`` in the worker threads, as they arrive, so no more than the tiles in flight are held as
bytes; only answers that decode are cached (:mod:`hamta.core.basemap.cache`), and a cached one that no
longer decodes is dropped and fetched again. The workers are daemon threads and a cancel shuts their
sockets: Ctrl-C ends a run at once, whatever the server does. Every failure ends as a
:class:`ServiceError` naming the host and what went wrong (the server's words made printable).
"""
from __future__ import annotations

import hashlib
import os
import queue
import threading
import time
from dataclasses import dataclass, field
from typing import Callable, Iterator, List, Optional, Sequence, Tuple
from urllib.parse import urlsplit

from ..errors import InputError
from . import http
from .cache import Cache, Unusable, default_cache
from .redact import redact

RETRY_STATUS = (408, 425, 429, 500, 502, 503, 504)  # worth asking again after a pause
MISSING_STATUS = (204, 404)  # a tile outside the layer's coverage: empty, not a failure


class ServiceError(InputError):
    """A map service could not deliver: unreachable, an HTTP error, a time-out, a bad or oversized
    answer, or too many requests."""


class BadAnswer(Exception):
    """Raised by a ``decode`` for an answer that is not what was asked for (its text says what it is)."""


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
    """Fetches the tiles of one run.

    ``timeout_s`` bounds each request whole (connection, headers and body); a failure worth retrying
    is asked again ``retries`` times after ``backoff_s``, doubled each time. ``max_requests`` caps the
    requests of the run, retries included (cache hits are free); ``max_bytes`` one answer's bytes;
    ``max_run_bytes`` and ``budget_s`` what the run receives and the time it spends fetching in all.
    ``cache`` is a folder (None: no disk cache); one that cannot be used safely is not used, with a
    line in ``warnings``.
    """

    cache: Optional[str] = field(default_factory=default_cache)
    timeout_s: float = 15.0
    retries: int = 3
    backoff_s: float = 0.5
    workers: int = 8
    max_requests: int = 2000
    max_bytes: int = 8 << 20
    max_run_bytes: int = 512 << 20
    budget_s: float = 600.0
    stats: FetchStats = field(default_factory=FetchStats)
    warnings: List[str] = field(default_factory=list)

    def __post_init__(self):
        self._lock = threading.Lock()
        self.store = Cache.open(self.cache, self.warnings)
        if self.store is None:
            self.cache = None

    def folder(self, name: str) -> Optional[str]:
        """The cache's subfolder ``name`` (made private), or None without a usable cache (with a warning)."""
        if self.store is None:
            return None
        try:
            return self.store.folder(name)
        except Unusable as exc:
            self._give_up_cache(exc)
            return None

    def _give_up_cache(self, exc: Unusable) -> None:
        """Go on without the cache, saying why once."""
        with self._lock:
            if self.store is not None:
                self.warnings.append(f"The cache folder '{self.store.root}' is not used: {exc}.")
            self.store, self.cache = None, None

    def each(self, urls: Sequence[str], decode: Callable[[str, bytes], object], monitor=None
             ) -> Iterator[Tuple[int, Optional[object]]]:
        """``(i, decode(urls[i], body))`` for each URL as its answer arrives (``None`` for a tile the
        service does not have). ``decode`` runs in the worker threads and raises :class:`BadAnswer` for
        a body that is not what was asked for (not cached; a cached one is dropped and fetched again).
        ``monitor`` (a :class:`hamta.core.progress.Monitor`) gets progress and may cancel."""
        start = time.perf_counter()
        tasks: "queue.Queue[int]" = queue.Queue()
        for i in range(len(urls)):
            tasks.put(i)
        results: "queue.Queue" = queue.Queue()
        watch = http.Watch()
        run = _Run(self, urls, decode, watch, tasks, results)
        for _ in range(max(1, min(self.workers, len(urls)))):
            threading.Thread(target=run.work, name="hamta-fetch", daemon=True).start()
        done = 0
        try:
            while done < len(urls):
                try:
                    i, value, error = results.get(timeout=0.1)
                except queue.Empty:
                    if monitor is not None:
                        monitor.check()
                    continue
                if error is not None:
                    raise error
                done += 1
                if monitor is not None:
                    monitor.report(done / len(urls), f"fetching tiles {done}/{len(urls)}")
                yield i, value
        finally:
            watch.cancel()  # workers still at it stop at once; nobody waits for them
            self.stats.seconds += time.perf_counter() - start

    def forget(self, url: str) -> None:
        """Drop ``url``'s cached answer."""
        store = self.store  # read once: a worker may give the cache up meanwhile
        if store is not None:
            store.remove(_entry(store, url))

    def cached(self, url: str) -> Optional[bytes]:
        """``url``'s cached answer, or None."""
        store = self.store
        return None if store is None else store.read(_entry(store, url), self.max_bytes)

    def keep(self, url: str, body: bytes) -> None:
        """Cache ``body`` as ``url``'s answer (where the cache is usable)."""
        store = self.store
        if store is None:
            return
        path = _entry(store, url)
        try:
            store.folder("http", os.path.basename(os.path.dirname(path)))
        except Unusable as exc:
            self._give_up_cache(exc)
            return
        store.write(path, body)

    def count_request(self, url: str) -> None:
        """Count one request to ``url``, within the run's caps."""
        with self._lock:
            if self.stats.requests >= self.max_requests:
                raise ServiceError(f"The map service at {host(url)} was sent the {self.max_requests} requests a "
                                   "run may send (retries included): choose a smaller search area.")
            self.stats.requests += 1

    def count_bytes(self, url: str, size: int) -> None:
        """Count ``size`` bytes received from ``url``, within the run's cap."""
        with self._lock:
            self.stats.bytes += size
            if self.stats.bytes > self.max_run_bytes:
                raise ServiceError(f"The map service at {host(url)} sent more than the {self.max_run_bytes >> 20} MB "
                                   "a run may receive: choose a smaller search area.")

    def count_cache_hit(self) -> None:
        with self._lock:
            self.stats.cache_hits += 1

    def count_missing(self) -> None:
        """Count one tile the service does not have."""
        with self._lock:
            self.stats.missing += 1


def _entry(store: Cache, url: str) -> str:
    """Where ``url``'s answer is kept: under a digest of the URL, in one of 256 folders."""
    digest = hashlib.sha256(url.encode()).hexdigest()
    return os.path.join(store.root, "http", digest[:2], digest)


class _Run:
    """The shared state of one :meth:`Fetcher.each`: its workers take URLs until none is left, an error
    ends the run, or the run is canceled."""

    def __init__(self, fetcher: Fetcher, urls, decode, watch: http.Watch, tasks, results):
        self.fetcher, self.urls, self.decode, self.watch = fetcher, urls, decode, watch
        self.tasks, self.results = tasks, results
        self.deadline = time.monotonic() + max(0.0, fetcher.budget_s - fetcher.stats.seconds)

    def work(self) -> None:
        while not self.watch.canceled:
            try:
                i = self.tasks.get_nowait()
            except queue.Empty:
                return
            try:
                self.results.put((i, self.one(self.urls[i]), None))
            except http.Canceled:
                return
            except BaseException as exc:  # handed to the caller's thread, which raises it
                self.results.put((i, None, exc))
                return

    def one(self, url: str):
        """The decoded answer for ``url`` (None for a missing tile): from the cache, or the network."""
        f = self.fetcher
        cached = f.cached(url)
        if cached is not None:
            try:
                value = self.decode(url, cached)
                f.count_cache_hit()
                return value
            except BadAnswer:
                f.forget(url)
        body = self.fetched(url)
        if body is None:
            f.count_missing()
            return None
        try:
            value = self.decode(url, body)
        except BadAnswer as exc:
            raise ServiceError(f"The map service at {host(url)} {exc} ({redact(url)}).") from None
        f.keep(url, body)
        return value

    def fetched(self, url: str) -> Optional[bytes]:
        """:meth:`request`, asked again after a failure worth retrying, ``retries`` times, pausing ``backoff_s``
        doubled each time; raises :class:`ServiceError` for the failure that ends it."""
        f = self.fetcher
        delay, attempt = f.backoff_s, 0
        while True:
            f.count_request(url)
            try:
                return self.request(url)
            except http.Failure as exc:
                if not exc.retry:
                    raise ServiceError(f"The map service at {host(url)} {exc} ({redact(url)}).") from None
                if attempt == f.retries:
                    tries = f"{f.retries + 1} {'try' if f.retries == 0 else 'tries'}"
                    raise ServiceError(f"The map service at {host(url)} did not answer properly after {tries}: the "
                                       f"last time it {exc} ({redact(url)}).") from None
            self._pause(delay)
            delay, attempt = delay * 2, attempt + 1

    def request(self, url: str) -> Optional[bytes]:
        """The body of a 2xx answer (None for a missing tile); raises :class:`http.Failure`."""
        f = self.fetcher
        left = self.deadline - time.monotonic()
        if left <= 0:
            raise ServiceError(f"The map service at {host(url)} took more than the {f.budget_s:g} s a run may spend "
                               "fetching: choose a smaller search area or try again later.")
        answer = http.get(url, self.watch, min(f.timeout_s, left), f.max_bytes)
        f.count_bytes(url, len(answer.body))
        if answer.status in MISSING_STATUS or (answer.status == 200 and not answer.body and answer.complete):
            return None
        if answer.status in RETRY_STATUS or (200 <= answer.status < 300 and not answer.body):
            raise http.Failure(f"answered HTTP {answer.status} {answer.reason}".strip(), retry=True)
        if not 200 <= answer.status < 300:
            raise http.Failure(f"refused a request: HTTP {answer.status} {answer.reason}".strip(), retry=False)
        return answer.body

    def _pause(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while not self.watch.canceled and time.monotonic() < end:
            time.sleep(min(0.05, end - time.monotonic()))
        if self.watch.canceled:
            raise http.Canceled()


def host(url: str) -> str:
    """The host (and port) of ``url``, without credentials."""
    try:
        parts = urlsplit(url)
        return parts.hostname + (f":{parts.port}" if parts.port else "") if parts.hostname else redact(url)
    except ValueError:
        return redact(url)
