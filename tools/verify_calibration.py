"""Does the independent check's verdict and error bound follow the true error? A calibration study.

Usage: python tools/verify_calibration.py OUT.jsonl [--tolerance 3] [--jobs 2]

Every case of the bench families with exact ground truth (rotation, scale, affine, overlap, speckle,
multimodal, georeferenced, crops; and the real development pairs, whose truth is hand-picked) is
checked with its true model made wrong by a known amount: shifted by 0.5-6 px, turned about the overlap's
centre or scaled so that the RMS error is 1-6 px. The true error of each model is its RMS distance from
the truth over the case's check points. The table counts, per family, the models verified with a true
error within 2 px, between 2 px and the tolerance, and beyond it (confident wrong answers), and how often
a verified model's error bound covers its true error.
"""
from __future__ import annotations

import argparse
import collections
import concurrent.futures as cf
import json
import math
import sys

import numpy as np

from hamta.bench.families import build_case, default_data_dir, family_specs
from hamta.core.estimation.models import fit_model
from hamta.core.io.raster import open_raster, resolve_bands
from hamta.core.verify import VerifyParams, verify

FAMILIES = ("rotation", "scale", "affine", "overlap", "speckle", "multimodal", "georeferenced", "pairs", "crops")
SHIFTS_PX = (0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0)
TURNS_PX = (1.0, 2.0, 3.0, 4.0, 6.0)
SCALES_PX = (2.0, 4.0)


class Perturbed:
    """``base`` (target px -> reference px) followed by the 3 x 3 map ``p`` of reference px."""

    def __init__(self, p: np.ndarray, base):
        self.p, self.base = p, base

    def apply(self, xy):
        q = self.base.apply(xy)
        h = np.column_stack([q, np.ones(len(q))]) @ self.p.T
        return h[:, :2] / h[:, 2:]


def perturbations(centre: np.ndarray, radius: float, rng) -> list:
    """(label, 3 x 3 map of reference px): none, shifts, turns and scalings about ``centre`` whose RMS
    over points ``radius`` from it is the label's px."""
    out = [("none", np.eye(3))]
    for d in SHIFTS_PX:
        a = rng.uniform(0, 2 * math.pi)
        out.append((f"shift{d}", np.array([[1, 0, d * math.cos(a)], [0, 1, d * math.sin(a)], [0, 0, 1.0]])))
    for e in TURNS_PX:
        a = e / radius * rng.choice([-1, 1])
        r = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        m = np.eye(3)
        m[:2, :2], m[:2, 2] = r, centre - r @ centre
        out.append((f"turn{e}", m))
    for e in SCALES_PX:
        s = 1 + e / radius
        out.append((f"scale{e}", np.array([[s, 0, centre[0] * (1 - s)], [0, s, centre[1] * (1 - s)], [0, 0, 1.0]])))
    return out


def study(args) -> list:
    family, name, tolerance, folder = args
    spec = next(s for s in family_specs(family) if s.name == name)
    case = build_case(spec, folder, 1024, default_data_dir())
    t, r = open_raster(case.target), open_raster(case.reference)
    gx, gy = np.meshgrid(np.linspace(0, t.width, 25), np.linspace(0, t.height, 25))
    src = np.column_stack([gx.ravel(), gy.ravel()])
    dst = case.truth(src)
    ok = np.isfinite(dst).all(axis=1)
    base = fit_model("polynomial-3" if family == "georeferenced" else "projective", src[ok], dst[ok])
    points = case.check_points
    true = case.check_truth if case.check_truth is not None else case.truth(points)
    centre = true.mean(axis=0)
    radius = float(np.sqrt(np.mean(np.sum((true - centre) ** 2, axis=1))))
    rows = []
    for label, p in perturbations(centre, radius, np.random.default_rng(spec.seed)):
        model = Perturbed(p, base)
        error = float(np.sqrt(np.mean(np.sum((model.apply(points) - true) ** 2, axis=1))))
        v = verify(model, t, resolve_bands(t, None), r, resolve_bands(r, None), VerifyParams(tolerance_px=tolerance))
        rows.append({"family": family, "case": name, "perturbation": label, "true_error_px": error,
                     "verdict": v.verdict, "look": v.look, "error_px": v.error_px, "bound_px": v.error_bound_px,
                     "reasons": list(v.reasons)})
    return rows


def table(rows: list, tolerance: float) -> str:
    by = collections.defaultdict(list)
    for r in rows:
        by[r["family"]].append(r)
    lines = [f"| family | models | true ≤ 2 px: verified | 2–{tolerance:g} px: verified | > {tolerance:g} px: verified "
             "(wrong) | bound covers the true error (verified) |", "|---|---|---|---|---|---|"]
    for family, rs in list(by.items()) + [("all", rows)]:
        def share(xs):
            return f"{sum(r['verdict'] == 'verified' for r in xs)}/{len(xs)}"
        near = [r for r in rs if r["true_error_px"] <= 2.0]
        mid = [r for r in rs if 2.0 < r["true_error_px"] <= tolerance]
        far = [r for r in rs if r["true_error_px"] > tolerance]
        bounded = [r for r in rs if r["verdict"] == "verified" and r["bound_px"] is not None]
        covered = sum(r["bound_px"] >= r["true_error_px"] for r in bounded)
        cover = f"{covered}/{len(bounded)} ({100 * covered / max(len(bounded), 1):.1f} %)"
        lines.append(f"| {family} | {len(rs)} | {share(near)} | {share(mid)} | {share(far)} | {cover} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--tolerance", type=float, default=3.0)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--cases", default="calibration-cases", help="folder for the generated cases")
    args = parser.parse_args(argv)
    keys = [(f, s.name, args.tolerance, args.cases) for f in FAMILIES for s in family_specs(f)]
    rows = []
    with cf.ProcessPoolExecutor(args.jobs) as pool, open(args.out, "w") as fh:
        for batch in pool.map(study, keys):
            rows.extend(batch)
            fh.write("".join(json.dumps(r) + "\n" for r in batch))
    print(table(rows, args.tolerance))
    return 0


if __name__ == "__main__":
    sys.exit(main())
