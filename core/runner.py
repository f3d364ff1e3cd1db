"""``run``: register, then write the outputs, as one job with one progress range.

The CLI, the Processing algorithms and the benchmark all call this; registering takes the first
80 % of the progress range and writing the rest. A result the independent check did not verify
gets no georeferenced output unless the caller accepts unverified results: only its report is
written (when asked for), and :class:`UnverifiedResult` says why.
"""
from __future__ import annotations

import dataclasses
import os
import time
from typing import Dict, Optional, Tuple

from .auto import AUTO
from .errors import OutputError, Refused, UnverifiedResult, UsageError
from .io.raster import input_files, open_raster
from .io.scope import run_scope
from .methods import get_method
from .options import OutputOptions, RegisterOptions
from .outputs import OutputPaths, write_outputs, write_refusal
from .outputs.atomic import check_creatable_folder
from .outputs.tags import verdict_text
from .outputs.warp import check_output_options
from .parallel import threaded
from .pipeline import register
from .progress import Monitor
from .reference import RasterReference, resolve_reference
from .result import RegistrationResult, params_dict

REGISTER_SHARE = 0.8
GRID = "grid"  # the sheet's own printed grid, no reference (hamta.core.grid)


@run_scope()
def run(target, reference, paths: Optional[OutputPaths] = None, *, method: str = AUTO, params=None,
        options: RegisterOptions = RegisterOptions(), output: OutputOptions = OutputOptions(),
        accept_unverified: bool = False, progress=None, is_canceled=None, map_chunks=None, fetcher=None
        ) -> Tuple[RegistrationResult, Dict[str, str]]:
    """Register ``target`` onto ``reference`` (see :func:`hamta.core.register`, which also explains
    ``map_chunks``) and write ``paths``. ``reference`` is text, a path or a resolved reference
    (:mod:`hamta.core.reference`); a map service (a tile-URL template, a QGIS XYZ or WMS layer source)
    is read through ``fetcher`` (a :class:`hamta.core.basemap.fetch.Fetcher`;
    by default one with the user's disk cache), see :mod:`hamta.core.remote`.

    Returns
    -------
    (RegistrationResult, dict)
        The result and {output name: absolute path} of what was written (empty without ``paths``).

    Raises
    ------
    UnverifiedResult
        The result did not verify and ``accept_unverified`` is False (its report is written).
    """
    monitor = Monitor(progress, is_canceled)
    by_grid = method == GRID or reference is None
    if by_grid:
        from .grid.register import GridParams

        params = GridParams.make(params, output)  # the hints and the sheet's CRS, checked before any work
    elif method == AUTO:
        if params:
            raise UsageError("method 'auto' takes no method parameters; choose a method to set them")
    else:
        get_method(method).make_params(params)  # a wrong name or parameter fails before any work
    reference = None if by_grid else resolve_reference(reference)
    raster = isinstance(reference, RasterReference)
    described_s = time.perf_counter()
    if paths is not None and paths.as_dict():
        inputs = threaded(lambda job: open_raster(*job), [(target, "target")] + ([(reference.path, "reference")]
                                                                                 if raster else []))
        check_destinations(paths, inputs, [] if not by_grid else [params.hints])
        if paths.raster:
            check_output_options(output, inputs[0], paths.raster)
    described_s = time.perf_counter() - described_s
    request = run_request(GRID if by_grid else method, params, options, accept_unverified)
    share = REGISTER_SHARE if paths is not None and paths.as_dict() else 1.0
    stage = monitor.span(0.0, share)
    if by_grid:
        from .grid.register import register_grid

        try:
            result = register_grid(target, params.sheet_crs, params.hints, step=params.step, output_crs=output.crs,
                                   options=options, progress=lambda f, m: stage.report(f, m), is_canceled=is_canceled)
        except Refused as exc:
            if paths is not None and (paths.report or paths.html):
                exc.written = write_refusal(exc.findings, paths, request)
            raise
    elif not raster:
        from .remote import register_remote  # its network code is imported only for a map service

        result = register_remote(target, reference.service, options, stage, fetcher=fetcher, method=method,
                                 params=params, map_chunks=map_chunks)
    else:
        result = register(target, reference.path, method=method, params=params, options=options,
                          progress=lambda f, m: stage.report(f, m), is_canceled=is_canceled, map_chunks=map_chunks)
    result = _opened_before(result, described_s)
    if share == 1.0:
        return result, {}
    stage = monitor.span(share, 1.0)
    if not result.verified and not accept_unverified:
        written = {}
        if paths.report or paths.html:  # the reports say why; in a run folder they replace the previous set whole
            written = write_outputs(result, OutputPaths(report=paths.report, html=paths.html, folder=paths.folder,
                                                            overwrite=paths.overwrite),
                                    output=output, is_canceled=is_canceled, request=request)
        raise UnverifiedResult(f"The registration of '{result.target.path}' is {verdict_text(result)}. No "
                               "georeferenced output was written; accept unverified results to write it anyway",
                               result, written)
    written = write_outputs(result, paths, output=output, progress=lambda f, m: stage.report(f, m),
                            is_canceled=is_canceled, request=request)
    return result, written


def _opened_before(result: RegistrationResult, seconds: float) -> RegistrationResult:
    """``result`` with the inputs' description, done before registering (to check the destinations),
    counted in its 'open' stage."""
    t = result.timings
    timings = dataclasses.replace(t, open=round(t.open + seconds, 4), total=round(t.total + seconds, 4))
    return dataclasses.replace(result, timings=timings)


def run_request(method: str, params, options: RegisterOptions, accept_unverified: bool) -> dict:
    """What a run is asked, as ``report.json`` keeps it (JSON types): a batch resumes a pair only for the same."""
    import json

    return json.loads(json.dumps({"method": method, "params": params_dict(params),
                                  "options": dataclasses.asdict(options), "accept_unverified": accept_unverified}))


def check_destinations(paths: OutputPaths, inputs, others=()) -> None:
    """Before any work: every destination can be written, and none is an input, a file an input
    reads (a VRT's sources, sidecar files) or one of ``others`` (paths read too: a sheet's hints)."""
    paths.check()
    for folder in {os.path.dirname(os.path.abspath(p)) for p in paths.as_dict().values()}:
        check_creatable_folder(folder)
    read = {os.path.realpath(f) for info in inputs for f in input_files(info)}
    read |= {os.path.realpath(f) for f in others if isinstance(f, (str, os.PathLike))}
    for kind, path in paths.as_dict().items():
        if os.path.realpath(path) in read:
            raise OutputError(f"The output '{path}' ({kind}) is one of the input files or a file they read; "
                              "choose another output path (inputs are never overwritten).")
    paths.check_ours()
