"""A GeoPackage point layer of GCPs, written with the standard library's sqlite3.

No allowed dependency writes vectors (rasterio is raster-only; Fiona would bring a second GDAL),
and a point layer needs only the core of the OGC GeoPackage 1.2 encoding (OGC 12-128r15):
the three metadata tables and standard GeoPackage geometry blobs (header + little-endian WKB).
"""
from __future__ import annotations

import shutil
import sqlite3
import struct
from typing import Optional

import numpy as np

from .gcp_style import write_default_style
from .points import destination_coordinates
from .tags import verdict_text

TABLE = "gcps"
_APPLICATION_ID = 0x47504B47  # "GPKG"
_USER_VERSION = 10200
_FIELDS = [("gcp_id", "INTEGER"), ("enabled", "BOOLEAN"), ("target_x", "REAL"), ("target_y", "REAL"),
           ("reference_x", "REAL"), ("reference_y", "REAL"), ("map_x", "REAL"), ("map_y", "REAL"),
           ("residual_px", "REAL"), ("residual_x_px", "REAL"), ("residual_y_px", "REAL"), ("score", "REAL")]


def _srs(result):
    """(srs_id, name, organization, code, definition) for the layer's CRS."""
    crs = None if result.pixel_mode else result.reference.crs
    return srs_entry(None if crs is None else crs.to_wkt())


def srs_entry(crs_wkt):
    """(srs_id, name, organization, code, definition) of a ``gpkg_spatial_ref_sys`` row for a CRS (WKT or None)."""
    if crs_wkt is None:
        return -1, "Undefined cartesian SRS", "NONE", -1, "undefined"
    from pyproj import CRS

    pcrs = CRS.from_user_input(crs_wkt)
    definition = pcrs.to_wkt(version="WKT1_GDAL") or pcrs.to_wkt()
    epsg = pcrs.to_epsg()
    if epsg:
        return epsg, pcrs.name, "EPSG", epsg, definition
    return 100000, pcrs.name, "NONE", 100000, definition


def _gp_header(srs_id: int) -> bytes:
    return b"GP" + struct.pack("<BBi", 0, 1, srs_id)  # version 0, little endian, no envelope


def _point_blob(x: float, y: float, srs_id: int) -> bytes:
    return _gp_header(srs_id) + struct.pack("<BIdd", 1, 1, x, y)


def _line_blob(xy: np.ndarray, srs_id: int) -> bytes:
    return _gp_header(srs_id) + struct.pack("<BII", 1, 2, len(xy)) + np.asarray(xy, "<f8").tobytes()


def polygon_blob(ring: np.ndarray, srs_id: int) -> Optional[bytes]:
    """A one-ring polygon (closed here), or None for fewer than 3 or non-finite vertices."""
    ring = np.asarray(ring, float)
    if len(ring) < 3 or not np.isfinite(ring).all():
        return None
    ring = np.vstack([ring, ring[:1]])
    return _gp_header(srs_id) + struct.pack("<BIII", 1, 3, 1, len(ring)) + ring.astype("<f8").tobytes()


def add_srs(con, srs) -> None:
    """Register ``srs`` (a :func:`srs_entry` tuple) unless the GeoPackage predefines it."""
    srs_id, name, org, code, definition = srs
    if srs_id not in (-1, 0, 4326):
        con.execute("INSERT OR IGNORE INTO gpkg_spatial_ref_sys VALUES (?,?,?,?,?,?)",
                    (name, srs_id, org, code, definition, ""))


def add_feature_layer(con, layer: str, geom_type: str, fields, rows, xy, description: str, srs_id: int) -> None:
    """Create feature table ``layer`` with ``fields`` ((name, SQL type)), insert ``rows`` (geometry blob
    first, then the fields) and register it; ``xy`` (N, 2) gives its bounds (None or empty: none)."""
    cols = ", ".join(f'"{n}" {t}' for n, t in fields)
    con.execute(f'CREATE TABLE "{layer}" (fid INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, geom {geom_type}, {cols})')
    names = ",".join(["geom"] + [f'"{n}"' for n, _ in fields])
    con.executemany(f'INSERT INTO "{layer}" ({names}) VALUES ({",".join("?" * (len(fields) + 1))})', rows)
    bounds = [None] * 4 if xy is None or not len(xy) else xy.min(axis=0).tolist() + xy.max(axis=0).tolist()
    con.execute("INSERT INTO gpkg_contents (table_name, data_type, identifier, description, min_x, min_y, max_x, "
                "max_y, srs_id) VALUES (?,?,?,?,?,?,?,?,?)", (layer, "features", layer, description, *bounds, srs_id))
    con.execute("INSERT INTO gpkg_geometry_columns VALUES (?,?,?,?,?,?)", (layer, "geom", geom_type, srs_id, 0, 0))


SHIFT_LAYER_SUFFIX = "_local_shifts"
SHIFT_EXAGGERATION = 20.0
_SHIFT_FIELDS = [("window_id", "INTEGER"), ("kept", "BOOLEAN"), ("reference_x", "REAL"), ("reference_y", "REAL"),
                 ("shift_x_px", "REAL"), ("shift_y_px", "REAL"), ("shift_px", "REAL"), ("used_x_px", "REAL"),
                 ("used_y_px", "REAL"), ("score", "REAL")]


def write_gcp_layer(path: str, result, layer: str = TABLE, base: Optional[str] = None) -> None:
    """Write the GCPs of ``result`` as ``layer`` (geometry: destination map coordinates; pixel mode
    uses (column, -row) of the reference like the ``.points`` file). With ``base``, an existing
    GeoPackage, its other layers are kept: it is copied to ``path`` first and only ``layer`` is replaced."""
    gcps = result.gcps
    ref = np.array([g.reference_px for g in gcps], float).reshape(-1, 2)
    mp = np.array([g.map_xy for g in gcps], float).reshape(-1, 2)
    dst = destination_coordinates(result, ref, mp)
    srs = _srs(result)
    srs_id = srs[0]
    if base is not None:
        shutil.copyfile(base, path)
    con = connect_staged(path)
    try:
        create_metadata(con)
        _drop_layer(con, layer)
        add_srs(con, srs)
        rows = [(_point_blob(dst[i, 0], dst[i, 1], srs_id), i + 1, int(g.enabled), g.target_px[0], g.target_px[1],
                 g.reference_px[0], g.reference_px[1], g.map_xy[0], g.map_xy[1], g.residual_px, g.residual_xy[0],
                 g.residual_xy[1], g.score) for i, g in enumerate(gcps)]
        description = f"Hamta ground control points (run {result.run_id}); {verdict_text(result)}"
        add_feature_layer(con, layer, "POINT", _FIELDS, rows, dst, description, srs_id)
        write_default_style(con, layer)
        _drop_layer(con, layer + SHIFT_LAYER_SUFFIX)
        if result.local is not None:
            _write_shifts(con, result, layer + SHIFT_LAYER_SUFFIX, srs_id)
        con.commit()
    finally:
        con.close()


def _write_shifts(con, result, layer: str, srs_id: int) -> None:
    """The local correction's windows as lines from each window's centre along its measured shift
    (exaggerated :data:`SHIFT_EXAGGERATION` times), in the GCP layer's coordinates."""
    grid = result.local
    start = grid.reference_px
    ends = start + SHIFT_EXAGGERATION * grid.shift_xy
    a = destination_coordinates(result, start, result.reference_to_map(start))
    b = destination_coordinates(result, ends, result.reference_to_map(ends))
    rows = [(_line_blob(np.array([a[i], b[i]]), srs_id), i + 1, int(grid.kept[i]), float(start[i, 0]),
             float(start[i, 1]), float(grid.shift_xy[i, 0]), float(grid.shift_xy[i, 1]),
             float(np.hypot(*grid.shift_xy[i])), float(grid.smoothed_xy[i, 0]), float(grid.smoothed_xy[i, 1]),
             float(grid.score[i])) for i in range(len(start))]
    description = (f"Hamta local shifts (run {result.run_id}): window centre to centre + {SHIFT_EXAGGERATION:g} x "
                   "the shift (global model minus the window's position, reference px); kept = used for the fit")
    add_feature_layer(con, layer, "LINESTRING", _SHIFT_FIELDS, rows, np.vstack([a, b]), description, srs_id)


def connect_staged(path: str) -> sqlite3.Connection:
    """A connection to a GeoPackage being written in an output set's staging folder. SQLite's own syncs
    are turned off (a dozen fsyncs: milliseconds on a quiet disk, a tenth of a second on a busy one): the
    file is published whole or dropped with its staging folder, so a crash mid-write leaves nothing to recover."""
    con = sqlite3.connect(path)
    con.execute("PRAGMA synchronous = OFF")
    con.execute("PRAGMA journal_mode = MEMORY")
    return con


def is_geopackage(path: str) -> bool:
    """True for an existing SQLite file that declares itself a GeoPackage."""
    try:
        with open(path, "rb") as f:
            head = f.read(72)
    except OSError:
        return False
    return head[:16] == b"SQLite format 3\x00" and head[68:72] == struct.pack(">I", _APPLICATION_ID)


def _drop_layer(con, layer: str) -> None:
    """Remove ``layer`` and what refers to it (spatial index, registrations), if present."""
    names = {r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    for table in [n for n in names if n.startswith(f"rtree_{layer}_")] + [layer]:
        if table in names:
            con.execute(f'DROP TABLE "{table}"')
    for registry in ("gpkg_contents", "gpkg_geometry_columns", "gpkg_extensions", "gpkg_ogr_contents"):
        if registry in names:
            con.execute(f'DELETE FROM "{registry}" WHERE lower(table_name) = lower(?)', (layer,))


def create_metadata(con) -> None:
    con.execute(f"PRAGMA application_id = {_APPLICATION_ID}")
    con.execute(f"PRAGMA user_version = {_USER_VERSION}")
    if con.execute("SELECT 1 FROM sqlite_master WHERE name='gpkg_spatial_ref_sys'").fetchone():
        return  # an existing GeoPackage keeps its metadata tables
    con.execute("CREATE TABLE gpkg_spatial_ref_sys (srs_name TEXT NOT NULL, srs_id INTEGER NOT NULL PRIMARY KEY, "
                "organization TEXT NOT NULL, organization_coordsys_id INTEGER NOT NULL, definition TEXT NOT NULL, "
                "description TEXT)")
    con.executemany("INSERT INTO gpkg_spatial_ref_sys VALUES (?,?,?,?,?,?)", [
        ("Undefined cartesian SRS", -1, "NONE", -1, "undefined", "undefined cartesian coordinate reference system"),
        ("Undefined geographic SRS", 0, "NONE", 0, "undefined", "undefined geographic coordinate reference system"),
        ("WGS 84 geodetic", 4326, "EPSG", 4326,
         'GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],'
         'AUTHORITY["EPSG","6326"]],PRIMEM["Greenwich",0,AUTHORITY["EPSG","8901"]],UNIT["degree",0.0174532925199433,'
         'AUTHORITY["EPSG","9122"]],AXIS["Latitude",NORTH],AXIS["Longitude",EAST],AUTHORITY["EPSG","4326"]]',
         "longitude/latitude coordinates in decimal degrees on the WGS 84 spheroid"),
    ])
    con.execute("CREATE TABLE gpkg_contents (table_name TEXT NOT NULL PRIMARY KEY, data_type TEXT NOT NULL, "
                "identifier TEXT UNIQUE, description TEXT DEFAULT '', last_change DATETIME NOT NULL DEFAULT "
                "(strftime('%Y-%m-%dT%H:%M:%fZ','now')), min_x DOUBLE, min_y DOUBLE, max_x DOUBLE, max_y DOUBLE, "
                "srs_id INTEGER, CONSTRAINT fk_gc_r_srs_id FOREIGN KEY (srs_id) "
                "REFERENCES gpkg_spatial_ref_sys(srs_id))")
    con.execute("CREATE TABLE gpkg_geometry_columns (table_name TEXT NOT NULL, column_name TEXT NOT NULL, "
                "geometry_type_name TEXT NOT NULL, srs_id INTEGER NOT NULL, z TINYINT NOT NULL, m TINYINT NOT NULL, "
                "CONSTRAINT pk_geom_cols PRIMARY KEY (table_name, column_name), "
                "CONSTRAINT fk_gc_tn FOREIGN KEY (table_name) REFERENCES gpkg_contents(table_name), "
                "CONSTRAINT fk_gc_srs FOREIGN KEY (srs_id) REFERENCES gpkg_spatial_ref_sys (srs_id))")
