"""Writing a registration's outputs: the warped raster, GCP VRT, QGIS ``.points``, GeoPackage, reports.

:func:`write_outputs` writes every requested file into a staging folder and publishes them as one
set (:mod:`hamta.core.outputs.atomic`), so outputs appear whole or not at all and never mixed with
another run's.
"""
from __future__ import annotations

import contextlib
import dataclasses
import errno
import os
import uuid
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, fields
from typing import Dict, Iterable, Optional, Tuple

from ..errors import ForeignFiles, OutputError, UsageError
from ..io.scope import release_datasets
from ..options import OutputOptions
from ..progress import Monitor
from .atomic import OutputSet, check_output_path, check_writable_folder, published_files, recover
from .gpkg import is_geopackage, write_gcp_layer
from .html import read_previews, write_html_report
from .model_vrt import write_vrt
from .points import write_points
from .report import write_report
from .warp import write_warped


@dataclass(frozen=True)
class OutputPaths:
    """Where each output goes; None skips it. ``raster`` is the warped target (GeoTIFF, COG or
    VRT, see :mod:`hamta.core.outputs.warp`), ``html`` the visual quality report."""

    raster: Optional[str] = None
    points: Optional[str] = None
    gpkg: Optional[str] = None
    vrt: Optional[str] = None
    report: Optional[str] = None
    html: Optional[str] = None
    folder: Optional[str] = None  # a run folder whose whole set of names belongs to Hamta (the CLI layout)
    overwrite: bool = False  # a run folder's files that Hamta did not write may be replaced
    gpkg_layer: str = "gcps"  # the GCP layer's name; other layers of an existing GeoPackage are kept

    LAYOUT = {"raster": "registered.tif", "points": "gcps.points", "gpkg": "gcps.gpkg", "vrt": "gcps.vrt",
              "report": "report.json", "html": "report.html"}
    OTHER_NAMES = ("registered.vrt",)  # the raster's name in the VRT format

    @classmethod
    def in_folder(cls, folder: str, vrt: bool = False, raster_format: str = "gtiff",
                  only: Optional[Iterable[str]] = None, overwrite: bool = False) -> "OutputPaths":
        """The CLI layout: registered.tif (registered.vrt in the VRT format), gcps.points, gcps.gpkg,
        report.json, report.html, or only the outputs named in ``only`` (names of :attr:`LAYOUT`; what
        is not asked for is not computed); gcps.vrt too with ``vrt``. Publishing there replaces the folder's
        previous set whole (a rerun without ``vrt`` removes gcps.vrt)."""
        wanted = set(cls.LAYOUT) - {"vrt"} if only is None else set(cls.parse(only))
        if vrt:
            wanted.add("vrt")
        names = {k: os.path.join(folder, v) for k, v in cls.LAYOUT.items() if k in wanted}
        if raster_format == "vrt":
            names["raster"] = os.path.join(folder, "registered.vrt")
        return cls(folder=folder, overwrite=overwrite, **names)

    @classmethod
    def parse(cls, names: Iterable[str]) -> Tuple[str, ...]:
        """Output names checked against :attr:`LAYOUT` (a ``ValueError`` names the known ones)."""
        names = tuple(n.strip().lower() for n in names if n.strip())
        unknown = sorted(set(names) - set(cls.LAYOUT))
        if unknown or not names:
            raise UsageError(f"unknown output(s) {', '.join(unknown) or '(none given)'}; choose from "
                             f"{', '.join(cls.LAYOUT)}")
        return names

    def as_dict(self) -> Dict[str, str]:
        return {f.name: getattr(self, f.name) for f in fields(self)
                if getattr(self, f.name) and f.name not in ("folder", "gpkg_layer", "overwrite")}

    def owned(self) -> Dict[str, tuple]:
        """{folder: names of its set} for the CLI layout, else nothing."""
        if self.folder is None:
            return {}
        return {os.path.abspath(self.folder): tuple(self.LAYOUT.values()) + self.OTHER_NAMES}

    def check(self) -> None:
        """Refuse unusable destinations before any work is done (names too long, folders...)."""
        for path in self.as_dict().values():
            check_output_path(path)

    def check_ours(self) -> None:
        """In a run folder, refuse to replace files Hamta did not write there (the user's own), unless
        ``overwrite``; a publication a killed run committed there is finished first."""
        if self.folder is None or self.overwrite or not os.path.isdir(self.folder):
            return
        recover(self.folder)
        ours = published_files(self.folder)
        foreign = sorted(os.path.basename(p) for p in self.as_dict().values()
                         if os.path.lexists(p) and os.path.basename(p) not in ours)
        if foreign:
            raise ForeignFiles(f"The output folder '{self.folder}' holds {', '.join(foreign)}, which Hamta did not "
                               "write there; choose another folder, or allow replacing them")


def write_outputs(result, paths: OutputPaths, *, output: OutputOptions = OutputOptions(), progress=None,
                  is_canceled=None, request: Optional[dict] = None) -> Dict[str, str]:
    """Write the requested outputs of ``result``; returns {output name: absolute path}.

    ``output`` chooses the warped raster's format, CRS, grid, resampling and fill; see
    :mod:`hamta.core.outputs.warp`. ``request`` (what the run was asked: method, parameters,
    options) is kept in ``report.json``, so that a batch resumes a pair only for the same request.
    """
    monitor = Monitor(progress, is_canceled)
    wanted = {k: os.path.abspath(v) for k, v in paths.as_dict().items()}
    paths.check()
    paths.check_ours()
    for folder in {os.path.dirname(p) for p in wanted.values()}:
        check_writable_folder(folder)
    run_id = uuid.uuid4().hex
    result = dataclasses.replace(result, run_id=run_id)
    with OutputSet(run_id, paths.owned()) as out, write_errors_named(), ThreadPoolExecutor(1) as aside:
        html = None
        if "html" in wanted:  # beside the other writers (its figures and GDAL's warping both release the GIL)
            previews = read_previews(result)
            html = aside.submit(write_html_report, out.temp_for(wanted["html"]), result, monitor.silent(),
                                outputs=wanted, previews=previews)
        release_datasets()  # nothing reads the inputs' blocks again: GDAL may free them for the warp
        if "raster" in wanted:
            write_warped(out.temp_for(wanted["raster"]), result, output, monitor.span(0.0, 0.85),
                         scratch=out.scratch(wanted["raster"]))
        if "vrt" in wanted:
            write_vrt(out.temp_for(wanted["vrt"]), result, scratch=out.scratch(wanted["vrt"]))
        if "points" in wanted:
            write_points(out.temp_for(wanted["points"]), result)
        if "gpkg" in wanted:
            existing = wanted["gpkg"] if is_geopackage(wanted["gpkg"]) and paths.folder is None else None
            write_gcp_layer(out.temp_for(wanted["gpkg"]), result, paths.gpkg_layer, base=existing)
        if "report" in wanted:
            report = result.to_report()
            report.update(run_id=run_id, outputs=wanted, output_options=dataclasses.asdict(output), request=request)
            write_report(out.temp_for(wanted["report"]), report)
        if html is not None:
            monitor.report(0.9, "writing the quality report")
            html.result()
        monitor.check()  # the last moment a cancel stops the run: publishing is not interrupted
    monitor.report(1.0, "done")
    return wanted


@contextlib.contextmanager
def write_errors_named():
    """Writers' OS, GDAL and SQLite errors (disk full, permissions...) as :class:`OutputError`."""
    import sqlite3

    from rasterio.errors import RasterioError

    try:
        yield
    except OutputError:
        raise
    except (OSError, RasterioError, sqlite3.Error) as exc:
        reason = "the disk is full" if getattr(exc, "errno", None) == errno.ENOSPC or "No space" in str(exc) \
            else (getattr(exc, "strerror", None) or str(exc))
        raise OutputError(f"Could not write the outputs: {reason}. Nothing was written.") from None


def write_refusal(findings: dict, paths: OutputPaths, request: Optional[dict] = None) -> Dict[str, str]:
    """The report and HTML report (whichever ``paths`` asks for) of a run that found nothing to register (see
    :mod:`hamta.core.outputs.refusal`)."""
    from .refusal import write_refusal as write

    return write(findings, paths, request)


__all__ = ["OutputPaths", "write_outputs", "write_refusal"]
