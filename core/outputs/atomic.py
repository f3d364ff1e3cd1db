"""Write several output files so that they appear whole or not at all."""
from __future__ import annotations

import os
import uuid
from typing import Dict

from ..errors import OutputError


def check_writable_folder(folder: str) -> None:
    """Create ``folder`` if needed and prove it is writable; raise :class:`OutputError` otherwise."""
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"Cannot create the output folder '{folder}': {exc.strerror or exc}.") from None
    probe = os.path.join(folder, f".hamta-write-test-{uuid.uuid4().hex}")
    try:
        with open(probe, "wb"):
            pass
        os.remove(probe)
    except OSError as exc:
        raise OutputError(f"The output folder '{folder}' is not writable: {exc.strerror or exc}.") from None


class OutputSet:
    """Hands out temporary paths beside the final ones; renames all on success, removes all on error.

    Use as a context manager::

        with OutputSet() as out:
            write_x(out.temp_for("/data/a.tif"))
            write_y(out.temp_for("/data/b.json"))
        # both renamed here, or neither exists if the block raised
    """

    def __init__(self):
        self._temps: Dict[str, str] = {}

    def temp_for(self, final_path: str) -> str:
        final_path = os.path.abspath(final_path)
        folder, name = os.path.split(final_path)
        check_writable_folder(folder)
        stem, ext = os.path.splitext(name)
        temp = os.path.join(folder, f".{stem}.hamta-{uuid.uuid4().hex[:8]}{ext}")
        self._temps[final_path] = temp
        return temp

    def __enter__(self) -> "OutputSet":
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is not None:
            self._discard()
            return False
        try:
            for final, temp in self._temps.items():
                os.replace(temp, final)
        except OSError as err:
            self._discard()
            raise OutputError(f"Could not move the output into place at '{final}': {err.strerror or err}.") from None
        return False

    def _discard(self) -> None:
        for temp in self._temps.values():
            for path in (temp, temp + ".aux.xml", temp + ".ovr"):
                if os.path.exists(path):
                    os.remove(path)
