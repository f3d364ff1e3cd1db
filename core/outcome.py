"""What a registration reports besides its model: its statistics, the time of each stage and, for
'auto', each method it tried. Frozen records with documented fields; ``to_dict`` gives the
``report.json`` form (schema in docs/report.md), which they keep unchanged."""
from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace
from typing import Mapping, Optional, Tuple


@dataclass(frozen=True)
class Stats:
    """Counts and self-reported residual figures of a registration (never its accuracy: that is the
    check's, :class:`hamta.core.verify.Verification`). Residuals are reference pixels.

    Attributes
    ----------
    n_keypoints_target, n_keypoints_reference : int
        Features each image gave the method.
    n_matches, n_inliers : int
        Correspondences the method returned, and those the robust estimation kept.
    n_gcps : int
        Well-spread inliers the model was fitted on.
    n_refined : int
        Correspondences refined at full resolution (0 when not refined).
    rmse_px, max_residual_px : float
        RMS and largest residual of the GCPs under the model.
    rms_loo_px : float, optional
        Leave-one-out RMS of the GCPs (None when no GCP can be left out).
    refined : bool
        Whether the full-resolution refinement ran.
    peak_rss_mb : float, optional
        Peak resident memory of the process so far (None where the OS does not say).
    """

    n_keypoints_target: int
    n_keypoints_reference: int
    n_matches: int
    n_inliers: int
    n_gcps: int
    n_refined: int
    rmse_px: float
    rms_loo_px: Optional[float]
    max_residual_px: float
    refined: bool
    peak_rss_mb: Optional[float]

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class Timings:
    """Seconds spent in each stage of one registration; ``local`` and ``auto_total`` are None when
    there was no local correction or no 'auto'.

    ``open`` and ``read`` the inputs, ``match`` (the method), ``estimate`` (robust fit), ``refine``
    (full resolution), ``fit`` (the final model on the GCPs), ``local`` (the local correction),
    ``verify`` (the independent check), ``total`` (their sum) and ``auto_total`` (the whole of
    'auto', every method tried included).
    """

    open: float = 0.0
    read: float = 0.0
    match: float = 0.0
    estimate: float = 0.0
    refine: float = 0.0
    fit: float = 0.0
    local: Optional[float] = None
    verify: float = 0.0
    total: float = 0.0
    auto_total: Optional[float] = None

    @classmethod
    def from_laps(cls, laps: Mapping[str, float]) -> "Timings":
        """The stages' times from ``{stage: seconds}`` laps, with their total."""
        return cls(**laps, total=round(sum(laps.values()), 4))

    @property
    def wall(self) -> float:
        """The time the user waited for the registration ('auto' included)."""
        return self.total if self.auto_total is None else self.auto_total

    def to_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self) if getattr(self, f.name) is not None}


@dataclass(frozen=True)
class Attempt:
    """One method 'auto' tried.

    Attributes
    ----------
    method, params : str, dict
        What ran (``params``: the method parameters the step set).
    why : str
        What the step is for.
    outcome : str
        'verified', 'suspect' or 'failed' (the check's verdict), 'no model', 'stopped' (the time
        budget ran out during it) or 'skipped' (before it started).
    reason : str
        Why, in the check's or the method's words.
    time_s : float
        Seconds it took.
    accepted : bool
        Whether its result is the one returned.
    """

    method: str
    params: Mapping[str, object]
    why: str
    outcome: str
    reason: str
    time_s: float
    accepted: bool = False

    def to_dict(self) -> dict:
        return {"method": self.method, "params": dict(self.params), "why": self.why, "outcome": self.outcome,
                "reason": self.reason, "time_s": self.time_s, "accepted": self.accepted}


@dataclass(frozen=True)
class AutoRun:
    """The methods 'auto' tried, in order, and the index of the one whose result it returned."""

    attempts: Tuple[Attempt, ...]
    chosen: Optional[int]

    @classmethod
    def of(cls, attempts, chosen: Optional[int]) -> "AutoRun":
        """The run of ``attempts``, the ``chosen`` one marked accepted."""
        return cls(tuple(replace(a, accepted=i == chosen) for i, a in enumerate(attempts)), chosen)

    def to_dict(self) -> dict:
        return {"attempts": [a.to_dict() for a in self.attempts], "chosen": self.chosen}


def attempt_lines(run: Optional[AutoRun]):
    """One line per attempt, the accepted one marked: the same words in the CLI and the Processing log."""
    if run is None:
        return []
    return [f"{'*' if a.accepted else ' '} tried {a.method}{_params(a.params)}: {a.outcome} ({a.time_s:.1f} s) - "
            f"{a.reason}" for a in run.attempts]


def _params(params) -> str:
    return "" if not params else "[" + ",".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                               for k, v in params.items()) + "]"
