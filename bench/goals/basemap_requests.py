"""The requests a basemap search sends (issue 55): ``hamta bench --families basemap-requests``.

The worst case for a tile budget: a layer with data everywhere and at every zoom (the tile server's
``texture`` style, a blurred noise per tile), searched for a real photo that is not in it (a NAIP window
turned 30 degrees, saved as PNG) in areas 3, 10, 30 and 100 times the photo's side. Every run should end
with a report (not verified: the photo is not there), never an error, within
:data:`hamta.core.remote.SEARCH_REQUESTS` requests; the notes say which zooms the budget left out.
"""
from __future__ import annotations

import os
import shutil
import tempfile
import time

from ..study import Study
from .basemap import rotated_target
from .basemap_real import FOLDER

SIDES = (3.0, 10.0, 30.0, 100.0)
PHOTO = "naip_20160816.tif"


def available(data_dir: str) -> bool:
    return os.path.exists(os.path.join(data_dir, FOLDER, PHOTO))


def units(config):
    """``(side,)`` for each search area side, in photo footprint sides."""
    return [(side,) for side in (SIDES if not config.quick else (10.0,))]


def run_unit(unit, config) -> list:
    """One row: the photo searched for in the texture layer: outcome, places tried, requests sent, seconds."""
    from ...core import RegisterOptions, run
    from ...core.basemap.fetch import Fetcher
    from ...core.errors import HamtaError
    from ...core.remote import SEARCH_REQUESTS
    from ..tileserver import TileServer

    (side,) = unit
    folder = os.path.join(config.out_dir, "cases", "basemap-requests")
    os.makedirs(folder, exist_ok=True)
    case = rotated_target(os.path.join(config.data_dir, FOLDER, PHOTO), os.path.join(folder, f"photo_{side:g}x.png"),
                          (467.0, 360.0), (400, 500), 1.0, 30.0)
    cache = tempfile.mkdtemp(prefix="hamta-bench-cache-")
    row = {"side": side, "budget": SEARCH_REQUESTS}
    try:
        with TileServer(os.path.join(config.data_dir, FOLDER, PHOTO)) as server:
            t0 = time.perf_counter()
            try:
                result, _ = run(case.path, server.xyz("texture"), None, options=RegisterOptions(
                    extent=case.search_area(side * side), auto_budget_s=60), fetcher=Fetcher(cache=cache))
                row.update(outcome=result.verification.verdict, places=len(result.reference_service["places"]),
                           skipped=[n for n in result.notes if "was not searched" in n])
            except HamtaError as exc:
                row.update(outcome=f"error: {exc}", places=None, skipped=[])
            row.update(time_s=time.perf_counter() - t0, requests=server.requests)
    finally:
        shutil.rmtree(cache, ignore_errors=True)
    return [row]


def tables(rows) -> list:
    body = [[f"{r['side']:g}x", r["outcome"], "–" if r["places"] is None else r["places"], r["requests"],
             "yes" if r["requests"] <= r["budget"] and not r["outcome"].startswith("error") else "no",
             f"{r['time_s']:.1f}", "; ".join(r["skipped"]) or "–"] for r in sorted(rows, key=lambda r: r["side"])]
    return [{"title": "basemap-requests: a layer with data everywhere, a photo that is not in it",
             "columns": ["area", "outcome", "places tried", "requests", "within the budget, no error", "time s",
                         "zooms left out"], "rows": body,
             "note": "Area: the search area's side in photo footprint sides. Goal (issue 55): every run a report "
                     "(here not verified), none an error, at most 400 requests at any area size."}]


STUDY = Study("basemap-requests", ("auto",), ("basemap-requests",), units, run_unit, tables)
