"""Judging a registration against ground truth (definitions of EVALUATION.md)."""
from __future__ import annotations

from typing import Optional

import numpy as np

from ..core.errors import HamtaError

CORRECT_MATCH_PX = 3.0
LOOSE_MATCH_PX = 10.0  # "nearly right": for methods whose papers judged matches by eye


def judge(case, result=None, error: Optional[BaseException] = None) -> dict:
    """Metrics of one registration of ``case``: the returned mapping's check-point error, the
    method's correct matches, the verdict of the independent check (a confident wrong answer is a
    verified result beyond the tolerance; a false flag a right result left unverified), and the
    self-reported figures. ``result`` is None on failure. A method that returned no matches has
    precision 0. Cases without truth (``case.truth`` None) must not verify. An ``error`` that is not
    a HamtaError (a bug inside a method: MethodCrashed) is a crash, never a success."""
    row = {"success": False, "rmse_cp": None, "max_cp": None, "ncm": 0, "ncm_loose": 0, "n_matches": 0,
           "precision": 0.0, "rmse_px": None, "rms_loo_px": None, "n_gcps": 0, "error": None, "verdict": None,
           "verified": False, "false_verified": False, "false_flagged": False, "method_used": None,
           "crashed": error is not None and not isinstance(error, HamtaError)}
    if result is not None:
        v = result.verification
        matrix = getattr(result.model, "matrix", None)
        row.update(verdict=v.verdict if v else None, verified=bool(result.verified), method_used=result.method,
                   quality={k: x for k, x in (v.to_dict() if v else {}).items() if k != "sites"},
                   auto=None if result.auto is None else result.auto.to_dict(),
                   model_matrix=None if matrix is None else np.asarray(matrix).tolist())
    if case.truth is None:  # nothing to find: any verified result is a confident wrong answer
        row.update(success=(result is None or not result.verified) and not row["crashed"],
                   false_verified=bool(result and result.verified),
                   error=None if error is None else f"{type(error).__name__}: {error}")
        if result is not None:
            row.update(rmse_px=result.stats.rmse_px, n_gcps=result.stats.n_gcps)
        return row
    corr = result.correspondences if result is not None else getattr(error, "correspondences", None)
    if corr is not None and len(corr):
        err = np.linalg.norm(case.truth(corr.target_px) - corr.reference_px, axis=1)
        row["ncm"] = int((err <= CORRECT_MATCH_PX).sum())
        row["ncm_loose"] = int((err <= LOOSE_MATCH_PX).sum())
        row["n_matches"] = int(len(corr))
        row["precision"] = row["ncm"] / len(corr)
    if result is None:
        row["error"] = f"{type(error).__name__}: {error}" if error is not None else "no result"
        return row
    e = case.errors(result.model)
    rmse = float(np.sqrt(np.mean(e ** 2)))
    right = bool(rmse <= case.tolerance_px)
    if "smooth" in case.info:  # the nonrigid family: the error where the field is smooth at the window scale
        smooth = np.asarray(case.info["smooth"], bool)
        row["rmse_cp_smooth"] = float(np.sqrt(np.mean(e[smooth] ** 2))) if smooth.any() else None
    row.update(rmse_cp=rmse, max_cp=float(e.max()), success=right, rmse_px=result.stats.rmse_px,
               rms_loo_px=result.stats.rms_loo_px, n_gcps=result.stats.n_gcps,
               false_verified=result.verified and not right, false_flagged=right and not result.verified)
    return row
