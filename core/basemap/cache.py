"""Hamta's cache folder (map-service answers, areas read from them, layers QGIS rendered), kept so that
nobody else can turn it against its user.

The folder is made private (0700). One owned by another user, or writable by others, is refused with a
warning naming it; so is one Hamta cannot make or write (a file in the way, a read-only or full disk,
``/proc``). Inside it nothing follows a symbolic link: every folder on the way is checked to be a real
folder of this user, files are read with ``O_NOFOLLOW`` and written under a temporary name then renamed
(a rename replaces a planted link, never writes through it). A cache that fails means a warning and
no cache, never a failed run.
"""
from __future__ import annotations

import os
import stat
import tempfile
from typing import Optional


class Unusable(Exception):
    """The cache (or a folder in it) cannot be used safely; the text says why, naming it."""


def default_cache() -> str:
    """``$HAMTA_CACHE`` or the user's cache folder (``$XDG_CACHE_HOME/hamta``, ``~/.cache/hamta``)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.environ.get("HAMTA_CACHE") or os.path.join(base, "hamta")


class Cache:
    """A checked cache folder; :meth:`open` returns None (and says why in ``warnings``) when it is unusable."""

    def __init__(self, root: str):
        self.root = root

    @classmethod
    def open(cls, root: Optional[str], warnings: list) -> Optional["Cache"]:
        if not root:
            return None
        root = os.path.abspath(root)
        try:
            if not os.path.lexists(root):
                os.makedirs(root, mode=0o700)
            _check_folder(root)
            probe = tempfile.NamedTemporaryFile(dir=root, prefix=".probe-")
            probe.close()
        except (OSError, Unusable) as exc:
            warnings.append(f"The cache folder '{root}' is not used: {_why(exc)}. This run keeps nothing for the next "
                            "one; set HAMTA_CACHE to a private folder of yours to cache tiles.")
            return None
        return cls(root)

    def folder(self, *names: str) -> str:
        """The folder ``root/names…``, made (0700) where missing, each step checked; raises :class:`Unusable`."""
        path = self.root
        for name in names:
            path = os.path.join(path, name)
            try:
                os.mkdir(path, 0o700)
            except FileExistsError:
                pass
            except OSError as exc:
                raise Unusable(f"'{path}' cannot be made: {_why(exc)}") from None
            _check_folder(path)
        return path

    def read(self, path: str, max_bytes: int) -> Optional[bytes]:
        """The file at ``path`` (inside the cache), or None where there is none; a link, a non-file or a file
        above ``max_bytes`` is removed and read as none."""
        try:
            fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
        except FileNotFoundError:
            return None
        except OSError:
            self.remove(path)
            return None
        with os.fdopen(fd, "rb") as f:
            info = os.fstat(f.fileno())
            if not stat.S_ISREG(info.st_mode) or info.st_size > max_bytes:
                data = None
            else:
                data = f.read(max_bytes + 1)
        if not data or len(data) > max_bytes:
            self.remove(path)
            return None
        return data

    def write(self, path: str, data: bytes) -> bool:
        """Write ``data`` whole or not at all; False where it could not be written (a later run refetches)."""
        tmp = None
        try:
            fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".part")
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, path)
            return True
        except OSError:
            if tmp is not None:
                _unlink(tmp)
            return False

    def remove(self, path: str) -> None:
        """Remove an entry (a link itself, never what it points to); a folder in the way is left alone."""
        if not os.path.isdir(path) or os.path.islink(path):
            _unlink(path)


def _check_folder(path: str) -> None:
    info = os.lstat(path)
    if stat.S_ISLNK(info.st_mode):
        raise Unusable(f"'{path}' is a symbolic link")
    if not stat.S_ISDIR(info.st_mode):
        raise Unusable(f"'{path}' is not a folder")
    if hasattr(os, "getuid") and info.st_uid != os.getuid():
        raise Unusable(f"'{path}' belongs to another user")
    if info.st_mode & 0o022:
        raise Unusable(f"'{path}' can be written by other users (mode {stat.S_IMODE(info.st_mode):o})")


def _why(exc: BaseException) -> str:
    if isinstance(exc, Unusable):
        return str(exc)
    return exc.strerror.lower() if getattr(exc, "strerror", None) else type(exc).__name__


def _unlink(path: str) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass
