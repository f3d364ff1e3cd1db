"""Private folders of this process for files a run makes for itself (map service areas read without a disk
cache, a sheet's frame), removed when the process ends."""
from __future__ import annotations


def process_folder(prefix: str) -> str:
    """A new private folder of this process, removed at exit."""
    import atexit
    import shutil
    import tempfile

    folder = tempfile.mkdtemp(prefix=prefix)
    atexit.register(shutil.rmtree, folder, True)
    return folder
