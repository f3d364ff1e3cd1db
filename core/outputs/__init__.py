"""Writing a registration's outputs: GeoTIFF, GCP VRT, QGIS ``.points``, GeoPackage, report.

:func:`write_outputs` writes every requested file through temporary names and renames them only
when all succeeded, so outputs appear whole or not at all.
"""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass, fields
from typing import Dict, Optional

from ..options import OutputOptions
from ..progress import Monitor
from .atomic import OutputSet, check_writable_folder
from .geotiff import write_geotiff, write_vrt
from .gpkg import write_gcp_layer
from .points import write_points
from .report import write_report


@dataclass(frozen=True)
class OutputPaths:
    """Where each output goes; None skips it."""

    geotiff: Optional[str] = None
    points: Optional[str] = None
    gpkg: Optional[str] = None
    vrt: Optional[str] = None
    report: Optional[str] = None

    @classmethod
    def in_folder(cls, folder: str, vrt: bool = False) -> "OutputPaths":
        """The CLI layout: registered.tif, gcps.points, gcps.gpkg, report.json (+ gcps.vrt)."""
        j = lambda name: os.path.join(folder, name)  # noqa: E731
        return cls(j("registered.tif"), j("gcps.points"), j("gcps.gpkg"), j("gcps.vrt") if vrt else None,
                   j("report.json"))

    def as_dict(self) -> Dict[str, str]:
        return {f.name: getattr(self, f.name) for f in fields(self) if getattr(self, f.name)}


def write_outputs(result, paths: OutputPaths, *, output: OutputOptions = OutputOptions(), progress=None,
                  is_canceled=None) -> Dict[str, str]:
    """Write the requested outputs of ``result``; returns {output name: absolute path}.

    ``output`` chooses the GeoTIFF's resampling and pixel grid; see
    :func:`hamta.core.outputs.geotiff.output_grid`.
    """
    monitor = Monitor(progress, is_canceled)
    wanted = {k: os.path.abspath(v) for k, v in paths.as_dict().items()}
    for folder in {os.path.dirname(p) for p in wanted.values()}:
        check_writable_folder(folder)
    with OutputSet() as out:
        if "geotiff" in wanted:
            write_geotiff(out.temp_for(wanted["geotiff"]), result, output.resampling, output.grid, output.resolution,
                          monitor.span(0.0, 0.9))
        if "vrt" in wanted:
            write_vrt(out.temp_for(wanted["vrt"]), result)
        if "points" in wanted:
            write_points(out.temp_for(wanted["points"]), result)
        if "gpkg" in wanted:
            write_gcp_layer(out.temp_for(wanted["gpkg"]), result)
        monitor.check()
        if "report" in wanted:
            report = result.to_report()
            report["outputs"] = wanted
            report["output_options"] = dataclasses.asdict(output)
            write_report(out.temp_for(wanted["report"]), report)
    monitor.report(1.0, "done")
    return wanted


__all__ = ["OutputPaths", "write_outputs"]
