"""What a batch registers: one :class:`Job` per target/reference pair, its reference resolved.

Sources: a CSV file or a GeoPackage table with a ``target`` column and optional ``reference``,
``method``, ``model``, ``extent`` (a search area, see :mod:`hamta.core.extent`), ``crs`` and ``hints`` (a
scanned sheet georeferenced by its own printed grid: the CRS its printed coordinates count in, and a QGIS
``.points`` file of two or three crossings) and ``output`` columns (rasters relative to the list's folder; a
reference may also be a map service or a GDAL string, kept as written:
:func:`hamta.core.reference.resolve_reference`, once per row); or a folder or glob pattern of targets, all
registered onto one reference (a raster or a VRT mosaic), or each by its own grid (a map series: the sheets'
CRS given, no reference). A row without a reference is a sheet by its grid where it, or the batch, names the
sheets' CRS. A row's
``output`` is a folder inside ``out``, relative to it: an absolute path, a ``..`` that leaves
``out``, or two rows with the same folder are refused before any work. A job without its own output
folder gets ``<out>/<target name>`` (made unique when names repeat or another row uses it).
"""
from __future__ import annotations

import csv
import glob
import hashlib
import os
import sqlite3
from dataclasses import dataclass
from typing import List, Optional, Union

from ..errors import InputError
from ..extent import parse_extent
from ..methods import get_method
from ..options import MODEL
from ..reference import Reference, resolve_reference

RASTER_EXTENSIONS = (".tif", ".tiff", ".vrt", ".jp2", ".img", ".jpg", ".jpeg", ".png", ".nc", ".hdf", ".h5")


@dataclass(frozen=True)
class Job:
    """One pair: the target, its resolved reference (None: a scanned sheet georeferenced by its own printed grid,
    whose printed coordinates count in ``sheet_crs``, from the ``hints`` file where given), where its outputs go,
    and the method/model when they differ from the batch's."""

    target: str
    reference: Optional[Reference]
    out: str
    method: Optional[str] = None
    model: Optional[str] = None
    extent: Optional[str] = None
    sheet_crs: Optional[str] = None
    hints: Optional[str] = None

    @property
    def key(self) -> str:
        """A stable id of the job (same inputs, method, search area and output folder: same key)."""
        text = "|".join([self.target, self.reference_text, self.out, self.method or "", self.model or ""]
                        + ([self.extent] if self.extent else []))
        return hashlib.sha1(text.encode()).hexdigest()[:16]

    @property
    def reference_text(self) -> str:
        if self.reference is not None:
            return self.reference.text
        return f"grid:{self.sheet_crs or ''}:{self.hints or ''}"

    @property
    def reference_label(self) -> str:
        return self.reference.label if self.reference is not None else "its own printed grid"

    @property
    def name(self) -> str:
        return os.path.basename(self.out)


def read_jobs(source: str, out: str, reference: Union[str, Reference, None] = None,
              sheet_crs: Optional[str] = None) -> List[Job]:
    """The jobs of ``source`` (a .csv or .gpkg list, a folder, or a glob of targets with ``reference``:
    text, resolved here, or a resolved reference; or, without one, ``sheet_crs``: scanned sheets georeferenced by
    their own grid)."""
    if source.lower().endswith((".csv", ".gpkg")) and not os.path.exists(source):
        raise InputError(f"The job list '{source}' does not exist.")
    if source.lower().endswith(".csv") and os.path.isfile(source):
        rows = _csv_rows(source)
    elif source.lower().endswith(".gpkg") and os.path.isfile(source):
        rows = _gpkg_rows(source)
    else:
        if reference is None and not sheet_crs:
            raise InputError(f"'{source}' is not a .csv or .gpkg job list; targets from a folder or pattern need a "
                             "reference (--reference), or, for scanned sheets georeferenced by their own printed "
                             "grid, the CRS of their printed coordinates (--sheet-crs).")
        rows = [{"target": t} for t in _targets(source)]
        if not rows:
            raise InputError(f"No raster matches '{source}'.")
    base = os.path.dirname(os.path.abspath(source)) if os.path.isfile(source) else os.getcwd()
    return _jobs(rows, base, out, reference, f"the job list '{source}'", sheet_crs)


def jobs_for_targets(targets: List[str], reference: Union[str, Reference, None], out: str,
                     sheet_crs: Optional[str] = None) -> List[Job]:
    """One job per target onto ``reference`` (text or a resolved reference), or without one each by its own grid
    (its printed coordinates in ``sheet_crs``), each into ``<out>/<target name>`` (unique)."""
    return _jobs([{"target": t} for t in targets], os.getcwd(), out, reference, "the targets", sheet_crs)


def _jobs(rows: list, base: str, out: str, reference, source: str, sheet_crs: Optional[str] = None) -> List[Job]:
    """Jobs from ``rows`` (dicts of the list's columns), rasters relative to ``base``; a row without a reference
    where none is given is a sheet by its grid, in its ``crs`` or ``sheet_crs``, its hints from its ``hints`` column
    or else the Georeferencer's ``<raster>.points`` beside it."""
    root = os.path.abspath(out)
    default = _reference(reference, os.getcwd())
    outputs = _outputs(rows, root, source)
    jobs, used = [], set(outputs.values())
    for i, row in enumerate(rows, start=1):
        target = _path(row.get("target"), base)
        if not target:
            raise InputError(f"Row {i} of {source} has no target.")
        ref = _reference(row.get("reference"), base) or default
        crs = (row.get("crs") or "").strip() or sheet_crs
        hints = _path(row.get("hints"), base)
        if not ref and not hints and os.path.isfile(target + ".points"):
            hints = target + ".points"  # where QGIS's Georeferencer saves a raster's points
        if not ref and not crs:
            raise InputError(f"Row {i} of {source} has no reference, and no --reference was given (a scanned sheet "
                             "by its own grid: a 'crs' column, or --sheet-crs).")
        if ref and hints:
            raise InputError(f"Row {i} of {source} has a reference and hints: hints are for a sheet by its own grid.")
        folder = outputs.get(i) or _unique(os.path.join(root, _stem(target)), used)
        used.add(folder)
        if not _inside(os.path.realpath(folder), os.path.realpath(root)):
            raise InputError(f"Row {i} of {source}: its output folder '{folder}' leads outside the output folder "
                             f"'{root}' through a symbolic link; remove the link or choose another output.")
        extent = (row.get("extent") or "").strip() or None
        if extent is not None:
            try:
                parse_extent(extent)
            except ValueError as exc:
                raise InputError(f"Row {i} of {source}: {exc}.") from None
        method, model = (row.get("method") or "").strip() or None, (row.get("model") or "").strip() or None
        try:
            if method is not None:
                get_method(method)
            if model is not None:
                MODEL.check(model)
        except ValueError as exc:
            raise InputError(f"Row {i} of {source}: {exc}.") from None
        jobs.append(Job(target, ref, folder, method, model, extent, None if ref else crs, None if ref else hints))
    return jobs


def _outputs(rows: list, root: str, source: str) -> dict:
    """The output folder of each row (numbered from 1) that names one; each inside ``root``, and
    no two the same."""
    folders, row_of = {}, {}
    for i, row in enumerate(rows, start=1):
        value = row.get("output")
        value = value.strip() if isinstance(value, str) else ""
        if not value:
            continue
        folder = os.path.normpath(os.path.join(root, value))
        if os.path.isabs(value) or not _inside(folder, root):
            raise InputError(f"Row {i} of {source}: the output '{value}' is not a folder inside the output folder "
                             f"'{root}' (give a relative path, without '..' leaving it).")
        if folder in row_of:
            raise InputError(f"Rows {row_of[folder]} and {i} of {source} have the same output folder '{folder}'; "
                             "each pair needs its own.")
        folders[i], row_of[folder] = folder, i
    return folders


def _inside(folder: str, root: str) -> bool:
    try:
        return folder != root and os.path.commonpath([folder, root]) == root
    except ValueError:  # another drive
        return False


def _csv_rows(path: str) -> list:
    rows = []
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            reader = csv.DictReader(f)
            for r in reader:
                if None in r:
                    raise InputError(f"Row {len(rows) + 1} (line {reader.line_num}) of the job list '{path}' has "
                                     f"{len(reader.fieldnames) + len(r[None])} fields, more than the "
                                     f"{len(reader.fieldnames)} columns of its header (quote a value that holds a "
                                     "comma).")
                rows.append({(k or "").strip().lower(): (v or "").strip() for k, v in r.items()})
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise InputError(f"The job list '{path}' could not be read as CSV ({exc}).") from None
    if rows and "target" not in rows[0]:
        raise InputError(f"The job list '{path}' has no 'target' column (columns: target, reference, method, model, "
                         "extent, crs, hints, output).")
    return rows


def _gpkg_rows(path: str) -> list:
    try:
        with sqlite3.connect(f"file:{path}?mode=ro", uri=True) as con:
            tables = [r[0] for r in con.execute("SELECT table_name FROM gpkg_contents")]
            for table in tables:
                cols = [r[1].lower() for r in con.execute(f'PRAGMA table_info("{table}")')]
                if "target" in cols:
                    cur = con.execute(f'SELECT * FROM "{table}"')
                    names = [d[0].lower() for d in cur.description]
                    return [{k: v if isinstance(v, str) else None for k, v in zip(names, r)} for r in cur]
    except sqlite3.Error as exc:
        raise InputError(f"The job list '{path}' is not a readable GeoPackage ({exc}).") from None
    raise InputError(f"No table of the GeoPackage '{path}' has a 'target' column.")


def _targets(pattern: str) -> List[str]:
    if os.path.isdir(pattern):
        names = sorted(os.path.join(pattern, n) for n in os.listdir(pattern))
    else:
        names = sorted(glob.glob(pattern, recursive=True))
    return [os.path.abspath(n) for n in names if os.path.isfile(n) and n.lower().endswith(RASTER_EXTENSIONS)]


def _path(value, base: str) -> Optional[str]:
    value = (value or "").strip() if isinstance(value, str) else None
    return os.path.abspath(os.path.join(base, value)) if value else None


def _reference(value, base: str) -> Optional[Reference]:
    """``value`` (text, or a reference already resolved) resolved, paths relative to ``base``; None when empty."""
    if isinstance(value, str):
        value = value.strip()
    return resolve_reference(value, base) if value else None


def _stem(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0] or "target"


def _unique(folder: str, used: set) -> str:
    candidate, n = folder, 2
    while candidate in used:
        candidate, n = f"{folder}-{n}", n + 1
    return candidate
