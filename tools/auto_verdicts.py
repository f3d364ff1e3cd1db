"""``auto``'s verdicts on the first pairs of each multimodal category, to compare library stacks.

Usage: python tools/auto_verdicts.py OUT.jsonl [N]        (run once in each interpreter)
       python tools/auto_verdicts.py --compare A.jsonl B.jsonl

One JSON line per pair: verdict, method, sites, agreeing sites, bound, RMS error against the set's truth,
the model, and the OpenCV and numpy versions. ``--compare`` counts identical verdicts and lists the pairs
that differ with both models' largest difference.
"""
from __future__ import annotations

import json
import sys

import numpy as np


def run(out: str, n: int) -> None:
    import cv2

    from hamta.bench.families import build_case, default_data_dir, family_specs
    from hamta.bench.multimodal_set import CATEGORIES
    from hamta.core import RegisterOptions
    from hamta.core.runner import run as register

    with open(out, "w") as fh:
        for family in CATEGORIES:
            for spec in family_specs(family)[:n]:
                case = build_case(spec, "", 1024, default_data_dir())
                result, _ = register(case.target, case.reference, None,
                                     options=RegisterOptions(tolerance_px=case.tolerance_px, pixel_mode=True))
                v = result.verification
                fh.write(json.dumps({
                    "family": family, "case": spec.name, "verdict": v.verdict, "method": result.method,
                    "sites": v.n_sites, "agree": v.n_agree, "bound": v.error_bound_px,
                    "rmse": float(np.sqrt(np.mean(case.errors(result.model) ** 2))),
                    "model": np.asarray(getattr(result.model, "matrix", np.eye(3))).tolist(),
                    "opencv": cv2.__version__, "numpy": np.__version__}) + "\n")
                fh.flush()


def compare(a: str, b: str) -> None:
    first = {(r["family"], r["case"]): r for r in map(json.loads, open(a))}
    second = {(r["family"], r["case"]): r for r in map(json.loads, open(b))}
    keys = [k for k in first if k in second]
    same = [k for k in keys if first[k]["verdict"] == second[k]["verdict"]]
    print(f"{len(same)} of {len(keys)} verdicts identical")
    for k in keys:
        x, y = first[k], second[k]
        if x["verdict"] != y["verdict"]:
            gap = float(np.abs(np.array(x["model"]) - np.array(y["model"])).max())
            print(f"{k[0]} {k[1]}: {x['verdict']} ({x['method']}) / {y['verdict']} ({y['method']}); models differ by "
                  f"up to {gap:.2f}")


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        compare(sys.argv[2], sys.argv[3])
    else:
        run(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 20)
