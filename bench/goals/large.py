"""The Sentinel-2-sized case against its goals (issue 16): time with outputs, memory, the IO floor.

Computed from the ``large`` family's rows: each method (and each variant, e.g. ``auto[local=1]``)
registered the pair and wrote every output; the IO floor (both files read once plus one
``gdalwarp`` of the target, :mod:`hamta.bench.io_floor`) was measured in the same worker first.
"""
from __future__ import annotations

from ..study import Study


def tables(rows) -> list:
    body = []
    for r in rows:
        floor = (r.get("io_floor") or {}).get("floor_s")
        body.append([r["case"], r["method"], "yes" if r["success"] else "no",
                     "–" if r["rmse_cp"] is None else f"{r['rmse_cp']:.3f}", r.get("verdict") or "–",
                     f"{r['time_s']:.1f}", "–" if not floor else f"{floor:.1f}",
                     "–" if not floor else f"{r['time_s'] / floor:.2f}", f"{r['peak_rss_mb']:.0f}"])
    return [{"title": "large: a Sentinel-2-sized pair (10980 px uint16 reference, 8000 px target, georeferencing "
                      "error and a smooth 3 px displacement field), outputs written",
             "columns": ["case", "method", "success", "RMSE_cp px", "verdict", "time s (with outputs)",
                         "IO floor s", "time / floor", "peak MB"], "rows": body,
             "note": "Goals: global model <= 60 s and <= 2 GB; with local correction (local=1) <= 120 s and <= 2 GB; "
                     "within 3x the IO floor (reading both files once + one gdalwarp of the target, same run). "
                     "Check points are a 25 x 25 grid over the whole target, so the global model's error includes "
                     "the displacement field it cannot follow."}]


STUDY = Study("large", ("sift", "auto"), ("large",), None, None, tables)
