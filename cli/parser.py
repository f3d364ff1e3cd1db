"""The ``hamta`` command line's parser: each command and its options (the commands themselves are in
:mod:`hamta.cli.main`)."""
from __future__ import annotations

import argparse
import os

from ..core.version import __version__
from .options import add_options


def build_parser() -> argparse.ArgumentParser:
    """The parser of every command; the command given is ``args.command``."""
    p = argparse.ArgumentParser(prog="hamta", description="Automatic georeferencing and co-registration of rasters.",
                                epilog="Exit codes: 0 success, 1 runtime error, 2 usage error, 3 unverified result, "
                                       "130 cancelled.")
    p.add_argument("--version", action="version", version=f"hamta {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    _add_register(sub)
    _add_batch(sub)

    m = sub.add_parser("map-points", help="map target pixels through the model stored in a report.json")
    m.add_argument("report", help="a report.json written by 'hamta register'")
    m.add_argument("coords", nargs="+", help="X Y pairs in target pixels (x = column, y = row, corner origin; put "
                                             "'--' before negative numbers)")
    m.add_argument("--json", action="store_true", help="print JSON instead of a table")

    ms = sub.add_parser("methods", help="the matching methods and when to use each")
    ms.add_argument("--verbose", action="store_true", help="also what each does, its source and its parameters")

    _add_bench(sub)

    t = sub.add_parser("train-pca-sift", help="learn the PCA-SIFT basis from images (maintainers)")
    t.add_argument("images", nargs="+", help="rasters to learn from (the shipped basis: the Landsat sample)")
    t.add_argument("--out", default=None, help="output .npz (default: the basis shipped with the package)")

    dm = sub.add_parser("demo", help="register the bundled sample and report the true error")
    dm.add_argument("--out", default="demo-output", help="folder for the sample and the result (default demo-output)")
    dm.add_argument("--method", default="sift", help="matching method (default sift)")
    _add_quiet(dm)
    return p


def _add_register(sub) -> None:
    r = sub.add_parser("register", help="register a target raster onto a reference raster, or a scanned sheet by its "
                                        "own printed grid",
                       description="Register TARGET onto REFERENCE (or, without one, by the sheet's own printed grid) "
                                   "and write the georeferenced outputs into OUT.")
    r.add_argument("--reference", default=None, help="georeferenced reference raster (its CRS is the map; one "
                                                      "without georeferencing needs --pixel-mode); or a map service: "
                                                      "a tile URL such as 'https://host/{z}/{x}/{y}.png', a QGIS XYZ "
                                                      "or WMS layer source, or a GDAL string (/vsicurl/..., WMTS:..., "
                                                      "WCS:..., a GDAL WMS XML file); see --extent. Without it, a "
                                                      "scanned sheet is georeferenced by its own printed grid: give "
                                                      "--sheet-crs, and --gcps where its labels cannot be read")
    r.add_argument("--gcps", default=None, metavar="HINTS.points",
                   help="without --reference: two or three crossings of the sheet's printed grid placed roughly with "
                        "their coordinates, as the QGIS Georeferencer saves them (mapX, mapY: the printed coordinates, "
                        "in degrees or in the grid's units; --param step=... where they do not tell the grid's step); "
                        "without it, the labels printed in the sheet's margins are read (OCR: Tesseract or RapidOCR)")
    _add_sheet_crs(r)
    r.add_argument("--target", required=True, help="raster to georeference")
    r.add_argument("--out", required=True, help="output folder (created if missing)")
    r.add_argument("--method", default="auto",
                   help="matching method (see 'hamta methods'); default auto: methods from fast to robust until one's "
                        "result verifies")
    r.add_argument("--param", action="append", default=[], metavar="KEY=VALUE",
                   help="method parameter, repeatable (see 'hamta methods --verbose')")
    r.add_argument("--vrt", action="store_true", help="also write gcps.vrt (target + GCPs, no resampling)")
    r.add_argument("--overwrite", action="store_true",
                   help="replace files in OUT that Hamta did not write there (refused otherwise)")
    r.add_argument("--outputs", default=None, metavar="NAME,...",
                   help="write only these outputs (what is not asked for is not computed): "
                        "raster, points, gpkg, report, html, vrt; default all but vrt")
    add_options(r)
    _add_run_options(r, "measure the local correction's windows on this Dask cluster (big scenes; its workers need "
                        "Hamta and the paths); tls:// takes its certificates from Dask's configuration "
                        "(distributed.comm.tls.*), tcp:// is unauthenticated; default: threads of this process")


def _add_sheet_crs(parser) -> None:
    parser.add_argument("--sheet-crs", default=None, metavar="CRS",
                        help="without --reference: what the coordinates printed on the sheet count in (EPSG:4326 or "
                             "EPSG:4269 for degrees of a graticule, whatever projection it is drawn in; the national "
                             "grid's CRS for its metres, feet or yards); the output is in --crs if given, else in it "
                             "(a projected one) or in the projection the graticule is found drawn in. Without it, "
                             "--crs stands for it")


def _add_batch(sub) -> None:
    bt = sub.add_parser("batch", help="register many targets, in parallel on Dask (a local cluster or a scheduler)",
                        description="Register every pair of SOURCE: a job list (.csv or .gpkg with columns target, "
                                    "reference, method, model, extent, crs, hints, output) or a folder/glob of targets "
                                    "registered onto --reference, or each by its own printed grid (scanned sheets: "
                                    "--sheet-crs, no --reference). Each pair writes into its own folder under --out "
                                    "(a row's "
                                    "output: a relative folder inside --out); a rerun skips "
                                    "pairs already done. Exit code: 0 all verified, 3 some not verified, 1 some "
                                    "failed.")
    bt.add_argument("source", help="job list (.csv/.gpkg), a folder of targets, or a glob pattern (quote it)")
    bt.add_argument("--out", required=True, help="output folder: one sub-folder per pair, batch.gpkg and batch.csv")
    bt.add_argument("--reference", default=None, help="the reference for targets from a folder or pattern (a raster, "
                                                      "a VRT mosaic or a map service, as for 'register')")
    bt.add_argument("--method", default="auto", help="matching method of every pair (a job's own overrides it)")
    _add_sheet_crs(bt)
    add_options(bt)
    bt.add_argument("--overwrite", action="store_true",
                    help="replace files in a pair's folder that Hamta did not write there (that pair fails otherwise)")
    _add_run_options(bt, "an existing Dask scheduler (workers need Hamta installed and access to the paths); "
                         "tls:// takes its certificates from Dask's configuration (distributed.comm.tls.ca-file, "
                         ".client.cert, .client.key), tcp:// is unauthenticated; default: a local cluster on "
                         "127.0.0.1 with TLS credentials of its own")
    bt.add_argument("--workers", type=int, default=None,
                    help="workers of the local cluster, at least 1 (default: CPU count)")


def _add_bench(sub) -> None:
    b = sub.add_parser("bench", help="measure methods and baselines on synthetic families and real pairs")
    b.add_argument("--quick", action="store_true",
                   help="a small subset at 512 px: product methods and generic baselines (a smoke test, ~1 min)")
    b.add_argument("--methods", help="comma-separated methods (default: all; the SIFT baseline always runs); "
                                     "variants as 'name[key=value,...]', separated by ';'")
    b.add_argument("--sweep", action="append", metavar="KEY=V1,V2,...",
                   help="run every method once per value of a parameter or registration option")
    b.add_argument("--families", help="comma-separated families (default: all but 'large', the 10980 px scene)")
    b.add_argument("--size", type=int, default=None, help="reference size in px (default 1024; 512 with --quick)")
    b.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="parallel cases (default: all CPUs)")
    b.add_argument("--out", default="bench-output", help="folder for bench.json, bench.md and the cases")
    b.add_argument("--data", default=None, help="development data folder (default ../shared/data)")
    b.add_argument("--no-reproductions", action="store_true",
                   help="skip the papers' own evaluations and the engineering goals")
    _add_quiet(b)


def _add_run_options(parser: argparse.ArgumentParser, scheduler_help: str) -> None:
    """The options ``register`` and ``batch`` share: --accept-unverified, --quiet and --scheduler (whose help
    says what the command does with the cluster)."""
    parser.add_argument("--accept-unverified", action="store_true",
                        help="write the outputs even when the result is not verified (the verdict is in every output)")
    _add_quiet(parser)
    parser.add_argument("--scheduler", default=None, metavar="tls://HOST:PORT", help=scheduler_help)


def _add_quiet(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
