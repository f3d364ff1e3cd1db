"""Publishing a run's outputs as one set: whole or not at all, never mixed with another run's.

Every file of a run is written into a staging folder beside its destination (same file system,
so moves are atomic), with the set's manifest (``.hamta-manifest.json``: the run's id and files).
Publishing takes the destination folder's lock (``.hamta.lock``, ``fcntl.flock``: concurrent runs
into one folder publish one after the other) and commits by renaming a journal into the folder
(``.hamta-journal.json``: the staging folder, the files, the names of the folder's previous set this
run does not write). Then it moves each file it replaces into the staging folder, moves the new
files into place, moves the previous set's other files away (a rerun without ``--vrt`` drops the
old ``gcps.vrt``), renames the manifest in and removes the journal. A run killed at any instant
leaves either no journal (the folder holds the old set; the staging folder is a leftover) or a
journal the next run in that folder, or a batch resuming it, rolls forward (every step can be
redone): readers see exactly the old set or exactly the new one. If a move fails while the run is
alive (a disk error), what was moved is put back. Files the folder's manifest does not list (the
user's own) are never moved or removed by publishing. Staging folders carry their process id and a
tag of their host: the next run removes those of processes of this host that no longer exist or
were killed and not yet reaped (a killed run's leftovers); on a shared file system, another host's
are removed once a day old, since their process cannot be checked from here.
"""
from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import shutil
import socket
import time
import uuid
from typing import Dict, Iterable, Optional

from ..errors import OutputError

STAGING_PREFIX = ".hamta-staging-"
MANIFEST = ".hamta-manifest.json"
LOCK = ".hamta.lock"
SQLITE_PATH_MAX = 512
FOREIGN_LEFTOVER_AGE_S = 86400
HOST_TAG = hashlib.sha1(socket.gethostname().encode()).hexdigest()[:8]


def check_writable_folder(folder: str) -> None:
    """Create ``folder`` if needed and prove it is writable; raise :class:`OutputError` otherwise."""
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"Cannot create the output folder '{folder}': {exc.strerror or exc}.") from None
    if not os.path.isdir(folder):
        raise OutputError(f"The output folder '{folder}' is not a folder.")
    probe = os.path.join(folder, f".hamta-write-test-{uuid.uuid4().hex}")
    try:
        with open(probe, "wb"):
            pass
        os.remove(probe)
    except OSError as exc:
        raise OutputError(f"The output folder '{folder}' is not writable: {exc.strerror or exc}.") from None


def check_creatable_folder(folder: str) -> None:
    """Prove ``folder`` exists and is writable, or can be created, without creating anything."""
    folder = os.path.abspath(folder)
    probe = folder
    while not os.path.exists(probe):
        probe = os.path.dirname(probe)
    if not os.path.isdir(probe):
        raise OutputError(f"Cannot create the output folder '{folder}': '{probe}' is a file.")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise OutputError(f"The output folder '{folder}' cannot be written: '{probe}' is not writable.")


def check_output_path(path: str) -> None:
    """Refuse a destination whose name or path the file system cannot hold (before any work is done)."""
    folder, name = os.path.split(os.path.abspath(path))
    if not name:
        raise OutputError(f"The output path '{path}' names a folder, not a file.")
    if os.path.isdir(path):
        raise OutputError(f"The output path '{path}' is an existing folder.")
    try:
        name_max = os.pathconf(folder if os.path.isdir(folder) else "/", "PC_NAME_MAX")
        path_max = os.pathconf(folder if os.path.isdir(folder) else "/", "PC_PATH_MAX")
    except (OSError, ValueError):
        name_max, path_max = 255, 4096
    staged = len(os.path.join(folder, STAGING_PREFIX + "0" * 48, name).encode())  # the staged copy is longer
    limit = min(path_max, SQLITE_PATH_MAX)
    if len(name.encode()) > name_max or staged >= limit:
        raise OutputError(f"The output path '{path}' is too long ({len(path)} characters): names may have at most "
                          f"{name_max} and whole paths about {limit - 60} (SQLite, which writes the GeoPackage, "
                          "takes at most 512).")


class OutputSet:
    """Hands out staging paths for final paths; publishes them all together on success, discards
    them on error (see the module docstring).

    Use as a context manager::

        with OutputSet(run_id, owned={"/out": ("registered.tif", "gcps.vrt")}) as out:
            write_x(out.temp_for("/out/registered.tif"))
        # published here, or nothing changed if the block raised

    ``owned`` maps a folder to the names that form its set: those this run does not write are
    removed when it publishes there. ``scratch`` gives a staging subfolder for intermediate files.
    """

    def __init__(self, run_id: Optional[str] = None, owned: Optional[Dict[str, Iterable[str]]] = None):
        self.run_id = run_id or uuid.uuid4().hex
        self.owned = {os.path.abspath(k): tuple(v) for k, v in (owned or {}).items()}
        self._staging: Dict[str, str] = {}
        self._finals: Dict[str, str] = {}

    def _stage(self, folder: str) -> str:
        if folder not in self._staging:
            check_writable_folder(folder)
            remove_leftovers(folder)
            path = os.path.join(folder, f"{STAGING_PREFIX}{os.getpid()}-{uuid.uuid4().hex[:12]}-{HOST_TAG}")
            try:
                os.mkdir(path)
            except OSError as exc:
                raise OutputError(f"Cannot write in the output folder '{folder}': {exc.strerror or exc}.") from None
            self._staging[folder] = path
        return self._staging[folder]

    def temp_for(self, final_path: str) -> str:
        final_path = os.path.abspath(final_path)
        folder, name = os.path.split(final_path)
        temp = os.path.join(self._stage(folder), name)
        self._finals[final_path] = temp
        return temp

    def scratch(self, final_path: str) -> str:
        """A private folder for intermediate files, removed with the staging folder."""
        folder = os.path.dirname(os.path.abspath(final_path))
        path = os.path.join(self._stage(folder), f"scratch-{uuid.uuid4().hex[:8]}")
        os.mkdir(path)
        return path

    def __enter__(self) -> "OutputSet":
        return self

    def __exit__(self, exc_type, exc, tb):
        try:
            if exc_type is None:
                for folder in sorted(self._staging):
                    self._publish(folder)
        finally:
            for path in self._staging.values():
                shutil.rmtree(path, ignore_errors=True)
        return False

    def _publish(self, folder: str) -> None:
        staging = self._staging[folder]
        names = sorted(os.path.basename(f) for f in self._finals if os.path.dirname(f) == folder)
        with open(os.path.join(staging, MANIFEST), "w", encoding="utf-8") as f:
            json.dump({"run_id": self.run_id, "published": time.strftime("%Y-%m-%dT%H:%M:%S"),
                       "files": {n: os.path.getsize(os.path.join(staging, n)) for n in names}}, f, indent=1)
        os.mkdir(os.path.join(staging, REPLACED))
        try:
            for name in names + [MANIFEST]:
                _sync(os.path.join(staging, name))
            _sync(staging)
        except OSError as err:
            raise OutputError(f"Could not write the outputs to the disk in '{folder}' ({err.strerror or err}); the "
                              "folder was left as it was.") from None
        with signals_deferred(), folder_lock(folder):
            _recover_locked(folder)
            previous = published_files(folder)
            stale = [n for n in self.owned.get(folder, ()) if n not in names and n in previous]
            journal = {"run_id": self.run_id, "staging": os.path.basename(staging), "files": names, "stale": stale}
            try:
                _write_durably(os.path.join(staging, JOURNAL), journal)
                os.replace(os.path.join(staging, JOURNAL), os.path.join(folder, JOURNAL))  # the commit
                _roll_forward(folder, journal)
            except OSError as err:
                with contextlib.suppress(OSError):
                    _roll_back(folder, journal)
                raise OutputError(f"Could not publish the outputs in '{folder}' ({err.strerror or err}); the "
                                  "folder was left as it was.") from None


REPLACED = "replaced"
JOURNAL = ".hamta-journal.json"


def published_files(folder: str) -> Dict[str, int]:
    """{name: size} of the set Hamta last published in ``folder`` (its manifest), empty when none."""
    try:
        with open(os.path.join(folder, MANIFEST), encoding="utf-8") as f:
            files = json.load(f).get("files", {})
        return {str(k): int(v) for k, v in files.items()} if isinstance(files, dict) else {}
    except (OSError, ValueError, TypeError, AttributeError):
        return {}


def recover(folder: str) -> None:
    """Finish a publication a killed run committed in ``folder`` (its journal), under the folder's lock."""
    if os.path.isfile(os.path.join(folder, JOURNAL)):
        with folder_lock(folder):
            _recover_locked(folder)


def _recover_locked(folder: str) -> None:
    """Roll a committed publication forward: once its journal is in the folder, the new set is the
    folder's, whatever instant the run was killed at (every step below can be redone)."""
    path = os.path.join(folder, JOURNAL)
    try:
        with open(path, encoding="utf-8") as f:
            journal = json.load(f)
        str(journal["staging"]), list(journal["files"]), list(journal["stale"])
    except FileNotFoundError:
        return
    except (OSError, ValueError, KeyError, TypeError):  # written durably before it was renamed in: not ours
        raise OutputError(f"The output folder '{folder}' holds an unreadable '{JOURNAL}'; remove it and rerun.")
    _roll_forward(folder, journal)


def _roll_forward(folder: str, journal: dict) -> None:
    staging = os.path.join(folder, journal["staging"])
    backup = os.path.join(staging, REPLACED)
    os.makedirs(backup, exist_ok=True)
    for name in journal["files"]:
        _move_in(staging, backup, folder, name)
    for name in journal["stale"]:
        if os.path.lexists(os.path.join(folder, name)):
            os.replace(os.path.join(folder, name), os.path.join(backup, name))
    _move_in(staging, backup, folder, MANIFEST)  # the old manifest kept too, for a roll back
    os.remove(os.path.join(folder, JOURNAL))
    shutil.rmtree(staging, ignore_errors=True)


def _move_in(staging: str, backup: str, folder: str, name: str) -> None:
    new, final = os.path.join(staging, name), os.path.join(folder, name)
    if os.path.lexists(new):  # not yet moved: the folder's file, if any, is the old one
        if os.path.lexists(final):
            os.replace(final, os.path.join(backup, name))
        os.replace(new, final)


def _roll_back(folder: str, journal: dict) -> None:
    """Undo a publication that failed while its run was alive (a disk error): the old set returns, with
    its manifest."""
    staging = os.path.join(folder, journal["staging"])
    backup = os.path.join(staging, REPLACED)
    moved = journal["files"] + [MANIFEST]
    for name in moved + journal["stale"]:
        new, final, old = (os.path.join(staging, name), os.path.join(folder, name), os.path.join(backup, name))
        if name in moved and not os.path.lexists(new) and os.path.lexists(final):
            os.replace(final, new)
        if os.path.lexists(old):
            os.replace(old, final)
    with contextlib.suppress(FileNotFoundError):
        os.remove(os.path.join(folder, JOURNAL))


def _sync(path: str) -> None:
    """Flush a staged file (or folder) to the disk before the journal commits the set, so that a power cut
    after the commit cannot leave a published file short. A folder cannot be flushed on every system (not
    on Windows): there the files' own flushes are what is kept."""
    if os.path.isdir(path):
        with contextlib.suppress(OSError):
            fd = os.open(path, os.O_RDONLY)
            try:
                os.fsync(fd)
            finally:
                os.close(fd)
        return
    with open(path, "rb+") as f:
        _flush(f)


def _flush(f) -> None:
    """os.fsync, where the file system has it."""
    try:
        os.fsync(f.fileno())
    except OSError as err:
        if err.errno not in (errno.EINVAL, errno.ENOTSUP, errno.ENOSYS):
            raise


def _write_durably(path: str, content: dict) -> None:
    with open(path, "w", encoding="utf-8") as f:
        json.dump(content, f)
        f.flush()
        _flush(f)


@contextlib.contextmanager
def signals_deferred():
    """Hold Ctrl-C and SIGTERM until the block ends (publishing is never left half done); the held
    signal is handled right after, as it would have been. A no-op off the main thread."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held, previous = [], {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        previous[sig] = signal.signal(sig, lambda signum, frame: held.append((signum, frame)))
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        for signum, frame in held[:1]:
            handler = previous[signum]
            if callable(handler):
                handler(signum, frame)
            elif handler == signal.SIG_DFL:
                signal.raise_signal(signum)


@contextlib.contextmanager
def folder_lock(folder: str):
    """An exclusive lock on ``folder``'s outputs (blocking); a no-op where ``fcntl`` is missing."""
    try:
        import fcntl
    except ImportError:  # Windows: publication is still staged and rolled back, only not serialised
        yield
        return
    fd = os.open(os.path.join(folder, LOCK), os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        fcntl.flock(fd, fcntl.LOCK_UN)
        os.close(fd)


def remove_leftovers(folder: str) -> None:
    """Finish a killed run's committed publication, then remove staging folders of runs that no longer
    exist (see the module docstring)."""
    recover(folder)
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if not name.startswith(STAGING_PREFIX):
            continue
        path = os.path.join(folder, name)
        pid, _, rest = name[len(STAGING_PREFIX):].partition("-")
        host = rest.partition("-")[2] or HOST_TAG
        if not pid.isdigit():
            continue
        gone = False
        if host == HOST_TAG:
            gone = not _alive(int(pid))
        else:
            with contextlib.suppress(OSError):
                gone = time.time() - os.path.getmtime(path) > FOREIGN_LEFTOVER_AGE_S
        if gone:
            shutil.rmtree(path, ignore_errors=True)


def _alive(pid: int) -> bool:
    """Whether process ``pid`` of this host runs; a killed process its parent has not reaped yet
    (a zombie) does not."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except OSError as exc:
        return exc.errno == errno.EPERM
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            return f.read().rpartition(b")")[2].split()[0] != b"Z"
    except (OSError, IndexError):
        return True
