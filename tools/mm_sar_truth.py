"""How far the Optical-SAR ground truth of the multimodal set can be trusted, from a bench run.

Usage: python tools/mm_sar_truth.py BENCH_JSON [METHOD ...]

For every registration of the ``mm-sar`` family that returned a linear model M, it compares M with
the published map G, scale-corrected (see ``bench/multimodal_set.py``): A = M o G^-1 is what M adds
to G. If G were right, a right M gives A = identity and a wrong M an arbitrary A. What the runs
show instead is A = a pure rotation (scale 1) about the reference image's centre, by an angle that
varies from pair to pair: G misses a rotation of the images about their centre. The table counts,
per method and verdict, the results whose A has that form (scale within 3 %, fixed point within 6 px
of the centre), and scores every result three ways: against G as published, against the
bench's truth (G turned to the angle of the SAR image's collar, ``bench/sar_truth.py``), and against
the best rotation of G about the centre ("rotation-free": scale, position and shape must be right, the
angle is not checked).
"""
from __future__ import annotations

import collections
import json
import math
import sys

import numpy as np

from hamta.bench.families import default_data_dir
from hamta.bench.multimodal_set import build
from hamta.bench.sar_truth import rotation_about
from hamta.core.coords import apply_matrix
from hamta.core.io.raster import open_raster

TOLERANCE_PX = 15.0


def rms(a, b) -> float:
    return float(np.sqrt(np.mean(np.sum((a - b) ** 2, axis=1))))


def analyse(row, data_dir: str) -> dict:
    case = build("mm-sar", int(row["case"]), data_dir)
    published = np.array(build("mm-sar", int(row["case"]), data_dir, published_truth=True)
                         .info["target_px_to_reference_px"])
    truth = np.array(case.info["target_px_to_reference_px"])
    m = np.array(row["model_matrix"])
    pts = case.check_points
    mapped = apply_matrix(m, pts)
    ref, tgt = open_raster(case.reference, "reference"), open_raster(case.target, "target")
    g = published @ np.diag([ref.width / tgt.width, ref.height / tgt.height, 1.0])  # scale-corrected
    centre = np.array([ref.width / 2.0, ref.height / 2.0])
    a = m @ np.linalg.inv(g)
    scale = math.sqrt(abs(np.linalg.det(a[:2, :2])))
    angle = math.degrees(math.atan2(a[1, 0], a[0, 0]))
    try:
        fixed = np.linalg.solve(np.eye(2) - a[:2, :2], a[:2, 2]) if abs(angle) > 2 else centre
    except np.linalg.LinAlgError:
        fixed = np.array([np.inf, np.inf])
    best = min(rms(mapped, apply_matrix(rotation_about(t, centre) @ g, pts)) for t in np.arange(-180, 180, 0.25))
    from hamta.core.estimation.models import LinearModel
    from hamta.core.io.raster import resolve_bands
    from hamta.core.verify import VerifyParams, verify

    check = verify(LinearModel("affine", truth), tgt, resolve_bands(tgt, None), ref, resolve_bands(ref, None),
                   VerifyParams(tolerance_px=TOLERANCE_PX))
    return {"published": rms(mapped, apply_matrix(published, pts)), "truth_verified": check.verified,
            "corrected": rms(mapped, apply_matrix(truth, pts)), "rotation_free": best,
            "rotation_about_centre": abs(scale - 1) < 0.03 and float(np.linalg.norm(fixed - centre)) < 6.0,
            "angle": angle}


def main(path: str, methods) -> int:
    with open(path) as f:
        rows = [r for r in json.load(f)["cases"] if r["family"] == "mm-sar" and r.get("model_matrix")]
    data_dir = default_data_dir()
    table = collections.defaultdict(collections.Counter)
    for row in rows:
        if methods and row["method"] not in methods:
            continue
        a = analyse(row, data_dir)
        key = (row["method"], row["verdict"])
        table[key]["results"] += 1
        table[key]["A = rotation about the centre"] += a["rotation_about_centre"]
        for name in ("published", "corrected", "rotation_free"):
            table[key][f"<= 15 px vs {name}"] += a[name] <= TOLERANCE_PX
        table[key]["the bench's truth itself verified"] += a["truth_verified"]
    columns = ["results", "A = rotation about the centre", "<= 15 px vs published", "<= 15 px vs corrected",
               "<= 15 px vs rotation_free", "the bench's truth itself verified"]
    print("| method | verdict | " + " | ".join(columns) + " |")
    print("|---" * (len(columns) + 2) + "|")
    for (method, verdict), counts in sorted(table.items(), key=lambda kv: (kv[0][0], str(kv[0][1]))):
        print(f"| {method} | {verdict} | " + " | ".join(str(counts[c]) for c in columns) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], set(sys.argv[2:])))
