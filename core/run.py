"""``run``: register, then write the outputs, as one job with one progress range.

The CLI, the Processing algorithms and the benchmark all call this; registering takes the first
80 % of the progress range and writing the rest.
"""
from __future__ import annotations

from typing import Dict, Optional, Tuple

from .options import OutputOptions, RegisterOptions
from .outputs import OutputPaths, write_outputs
from .pipeline import register
from .progress import Monitor
from .result import RegistrationResult

REGISTER_SHARE = 0.8


def run(target, reference, paths: Optional[OutputPaths] = None, *, method: str = "sift", params=None,
        options: RegisterOptions = RegisterOptions(), output: OutputOptions = OutputOptions(), progress=None,
        is_canceled=None) -> Tuple[RegistrationResult, Dict[str, str]]:
    """Register ``target`` onto ``reference`` (see :func:`hamta.core.register`) and write ``paths``.

    Returns
    -------
    (RegistrationResult, dict)
        The result and {output name: absolute path} of what was written (empty without ``paths``).
    """
    monitor = Monitor(progress, is_canceled)
    share = REGISTER_SHARE if paths is not None and paths.as_dict() else 1.0
    stage = monitor.span(0.0, share)
    result = register(target, reference, method=method, params=params, options=options,
                      progress=lambda f, m: stage.report(f, m), is_canceled=is_canceled)
    if share == 1.0:
        return result, {}
    stage = monitor.span(share, 1.0)
    written = write_outputs(result, paths, output=output, progress=lambda f, m: stage.report(f, m),
                            is_canceled=is_canceled)
    return result, written
