"""The ``hamta`` command line: register, map-points, methods, demo (and bench)."""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import sys
import time
from typing import List, Optional

from ..core.errors import HamtaError, MethodCrashed, RegistrationCanceled
from ..core.text import terminal_safe
from .options import FLAGS, settings_from
from .progress import ProgressBar

# Exit codes (documented in the README).
EXIT_OK = 0  # registered, and the independent check verified the result
EXIT_ERROR = 1  # bad input or a registration that could not be done (the message says why)
EXIT_USAGE = 2  # bad command line or parameter
EXIT_UNVERIFIED = 3  # a model was found but not verified: no georeferenced output unless --accept-unverified
EXIT_CANCELED = 130  # interrupted (Ctrl-C); nothing was written


def _pairs(values: List[str]) -> dict:
    out = {}
    for item in values or []:
        if "=" not in item:
            raise argparse.ArgumentTypeError(f"--param expects key=value, got {item!r}")
        k, v = item.split("=", 1)
        out[k.strip().replace("-", "_")] = v.strip()
    return out


def cmd_register(args) -> int:
    from ..core import UnverifiedResult, run
    from ..core.outputs import OutputPaths

    options, output = settings_from(args)
    _outside_the_cache(args.out)
    method, params = args.method, _pairs(args.param)
    if args.reference is None or method == "grid":
        if args.reference is not None:
            raise ValueError("--method grid georeferences a sheet by its own printed grid: give no --reference")
        method, params = "grid", dict(params, hints=args.gcps)
    elif args.gcps is not None:
        raise ValueError("--gcps gives hints to a sheet georeferenced by its own grid: leave out --reference")
    paths = OutputPaths.in_folder(args.out, vrt=args.vrt, raster_format=output.format, overwrite=args.overwrite,
                                  only=None if args.outputs is None else args.outputs.split(","))
    if args.scheduler:
        from ..core.batch.runner import scheduler_map  # Dask's modules only for a run that uses a cluster

        cluster = scheduler_map(args.scheduler)
    else:
        cluster = contextlib.nullcontext()
    try:
        with cluster as map_chunks:
            result, written = run(args.target, args.reference, paths, method=method, params=params,
                                  options=options, output=output, accept_unverified=args.accept_unverified,
                                  progress=ProgressBar(not args.quiet), map_chunks=map_chunks)
    except UnverifiedResult as exc:
        print_result(exc.result, exc.written)
        print(f"hamta: {explain(exc)}", file=sys.stderr)
        print_advice(exc.result)
        return EXIT_UNVERIFIED
    print_result(result, written)
    if not result.verified:
        print_advice(result, written=True)
    return EXIT_OK if result.verified else EXIT_UNVERIFIED


def print_advice(result, written: bool = False) -> None:
    """What may help an unverified result, as flags of this command line (stderr)."""
    from ..core.advice import advice

    tips = [t for t in advice(result) if not (written and t.option == "accept_unverified")]
    if tips:
        print("hamta: options that may help:", file=sys.stderr)
    for tip in tips:
        flag = FLAGS.get(tip.option, "--" + tip.option.replace("_", "-"))
        print(f"  {flag}{'' if tip.value is True else f' {tip.value}'}: {tip.why}", file=sys.stderr)


def explain(exc: HamtaError) -> str:
    """The error's message, naming the option that lets the user go on as this command line spells it."""
    return f"{exc} ({FLAGS.get(exc.option, '--' + exc.option.replace('_', '-'))})." if exc.option else str(exc)


def print_result(result, written) -> None:
    """What the run found: the attempts of 'auto', the verdict first, then the self-reported fit."""
    from ..core.outcome import attempt_lines
    from ..core.outputs.tags import counts_text, pixel_mode_text, unknown_crs_text, verdict_text

    for line in attempt_lines(result.auto):
        print(line)
    print(f"result: {verdict_text(result)}")
    if result.pixel_mode:
        print(f"note: {pixel_mode_text()}")
    elif result.reference.crs is None:
        print(f"note: {unknown_crs_text(result)}")
    s = result.stats
    print(f"method {result.method}, model {result.model.kind}: {counts_text(s)}; "
          f"self-reported RMSE {s.rmse_px:.3f} px, RMS_LOO {_fmt(s.rms_loo_px)} px; {result.timings.wall:.2f} s")
    for name, path in written.items():
        print(f"{name:8s} {path}")


def _fmt(v) -> str:
    return "n/a" if v is None else f"{v:.3f}"


def _outside_the_cache(out: str) -> None:
    """Refuse an output folder inside Hamta's cache (a cache entry could replace an output, or the reverse)."""
    from ..core.basemap.cache import default_cache

    out, cache = os.path.realpath(out), os.path.realpath(default_cache())
    if out == cache or out.startswith(cache + os.sep):
        raise ValueError(f"--out '{out}' is inside Hamta's cache folder '{cache}'; choose a folder outside it")


def cmd_batch(args) -> int:
    from ..core.batch import read_jobs, run_batch
    from ..core.batch.table import write_results
    from ..core.batch.task import BatchSettings

    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be at least 1 (default: the CPU count), got {args.workers}")
    options, output = settings_from(args)
    _outside_the_cache(args.out)
    jobs = read_jobs(args.source, args.out, args.reference)
    settings = BatchSettings(method=args.method, options=options, output=output,
                             accept_unverified=args.accept_unverified, overwrite=args.overwrite)
    result = run_batch(jobs, settings, scheduler=args.scheduler, workers=args.workers,
                       progress=ProgressBar(not args.quiet))
    tables = write_results(args.out, result.records)
    for r in result.records:
        if r["status"] != "verified":
            print(f"{r['status']:10s} {r['name']}: {r['message']}")
    for note in result.notes:
        print(f"note: {note}")
    print(result.summary())
    print(f"results  {tables['gpkg']}\n         {tables['csv']}")
    counts = result.counts()
    return EXIT_ERROR if counts["failed"] else (EXIT_UNVERIFIED if counts["unverified"] else EXIT_OK)


def cmd_map_points(args) -> int:
    from ..core.mapping import map_points_from_report

    if len(args.coords) % 2:
        raise ValueError(f"map-points takes X Y pairs of target pixels; got {len(args.coords)} numbers")
    try:
        values = [float(v) for v in args.coords]
    except ValueError:
        raise ValueError("map-points takes numbers (X Y pairs of target pixels), got "
                         f"{' '.join(args.coords)}") from None
    xy = [(values[i], values[i + 1]) for i in range(0, len(values), 2)]
    rows = map_points_from_report(args.report, xy)
    if args.json:
        print(json.dumps(rows, indent=1))
    else:
        print("target_x target_y -> reference_x reference_y -> map_x map_y")
        for r in rows:
            print(" ".join(f"{v:.6f}" for v in r["target_px"] + r["reference_px"] + r["map"]))
    return 0


def cmd_methods(args) -> int:
    import dataclasses

    from ..core.methods import all_methods

    methods = list(all_methods().values())
    if not args.verbose:
        rows = [("auto", "default", "any pair: tries methods from fast to robust until one's result verifies")]
        rows += [(m.name, m.kind, m.advice) for m in methods]
        width = max(len(r[0]) for r in rows)
        print(f"{'method':{width}}  {'kind':8}  when to use")
        for name, kind, advice in rows:
            print(f"{name:{width}}  {kind:8}  {advice}")
        print("\n'hamta methods --verbose' shows what each does, its source and its parameters (--param KEY=VALUE).")
        return 0
    for m in methods:
        print(f"{m.name}  [{m.kind}]  {m.title}")
        print(f"    when to use: {m.advice}")
        print(f"    {m.summary}")
        print(f"    source: {m.citation}; default model: {m.default_model}")
        for f in dataclasses.fields(m.params_type):
            print(f"    --param {f.name}={f.default!r}  {f.metadata.get('help', '')}")
    return 0


def cmd_demo(args) -> int:
    from ..bench.sample import TARGET_SHAPE, check_point_error, make_demo_pair
    from ..core import RegisterOptions, run
    from ..core.outputs import OutputPaths

    root = os.path.abspath(args.out)
    sample = make_demo_pair(os.path.join(root, "sample"))
    t0 = time.perf_counter()
    result, written = run(sample["target"], sample["reference"],
                          OutputPaths.in_folder(os.path.join(root, "result"), vrt=True), method=args.method,
                          options=RegisterOptions(model="affine"), progress=ProgressBar(not args.quiet))
    elapsed = time.perf_counter() - t0
    with open(sample["truth"]) as f:
        truth = json.load(f)
    import numpy as np

    rmse, worst = check_point_error(result.model, np.array(truth["target_px_to_reference_px"]), TARGET_SHAPE,
                                    (1000, 1000))
    s = result.stats
    print(f"Sample pair:   {sample['target']}  ->  {sample['reference']}")
    print(f"Method {result.method}, model {result.model.kind}: {s.n_gcps} GCPs, self-reported RMSE "
          f"{s.rmse_px:.3f} px, RMS_LOO {_fmt(s.rms_loo_px)} px")
    print(f"TRUE check-point error against the known transform: RMSE {rmse:.3f} px, max {worst:.3f} px "
          f"(reference pixels)")
    print(f"Time {elapsed:.2f} s, peak memory {s.peak_rss_mb:.0f} MB")
    print("Outputs:")
    for name, path in written.items():
        print(f"  {name:8s} {path}")
    return 0


def cmd_bench(args) -> int:
    from ..bench.families import DEFAULT_FAMILIES
    from ..bench.runner import BenchConfig, expand_sweep, run_bench
    from ..bench.tables import text_tables
    from ..core.methods import all_methods

    def split(text, sep=","):
        return tuple(x.strip() for x in text.split(sep) if x.strip())

    families = split(args.families) if args.families else DEFAULT_FAMILIES
    methods = split(args.methods or "", ";" if "[" in (args.methods or "") else ",")
    if args.sweep:
        methods = tuple(expand_sweep(methods or tuple(all_methods()), args.sweep))
    config = BenchConfig(methods=methods, families=families,
                         size=args.size or (512 if args.quick else 1024), quick=args.quick, jobs=args.jobs,
                         out_dir=args.out, data_dir=args.data or "", reproductions=not args.no_reproductions)
    report = run_bench(config, progress=ProgressBar(not args.quiet))
    print(text_tables(report))
    print(f"\nwritten: {os.path.join(os.path.abspath(args.out), 'bench.json')} and bench.md")
    return 0


def cmd_train_pca_sift(args) -> int:
    from ..core.descriptors.pca_sift import BASIS_PATH, save_basis, train_basis

    mean, components, n = train_basis(args.images)
    out = args.out or BASIS_PATH
    save_basis(out, mean, components, n, args.images)
    print(f"PCA-SIFT basis ({components.shape[0]} components from {n} patches) written to {out}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    from ..core.version import __version__
    from .options import add_options

    p = argparse.ArgumentParser(prog="hamta", description="Automatic georeferencing and co-registration of rasters.",
                                epilog="Exit codes: 0 success, 1 runtime error, 2 usage error, 3 unverified result, "
                                       "130 cancelled.")
    p.add_argument("--version", action="version", version=f"hamta {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

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
                                                      "--crs (the sheet's), and --gcps where its labels cannot be "
                                                      "read")
    r.add_argument("--gcps", default=None, metavar="HINTS.points",
                   help="without --reference: two or three crossings of the sheet's printed grid placed roughly with "
                        "their coordinates, as the QGIS Georeferencer saves them (mapX, mapY: the printed coordinates, "
                        "in degrees or in the grid's metres; --param step=... and --param grid_crs=... where they do "
                        "not tell the grid); without it, the labels printed in the sheet's margins are read "
                        "(Tesseract)")
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
    r.add_argument("--accept-unverified", action="store_true",
                    help="write the outputs even when the result is not verified (the verdict is in every output)")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    r.add_argument("--scheduler", default=None, metavar="tls://HOST:PORT",
                   help="measure the local correction's windows on this Dask cluster (big scenes; its workers need "
                        "Hamta and the paths); tls:// takes its certificates from Dask's configuration "
                        "(distributed.comm.tls.*), tcp:// is unauthenticated; default: threads of this process")
    r.set_defaults(func=cmd_register)

    bt = sub.add_parser("batch", help="register many targets, in parallel on Dask (a local cluster or a scheduler)",
                        description="Register every pair of SOURCE: a job list (.csv or .gpkg with columns target, "
                                    "reference, method, model, extent, output) or a folder/glob of targets registered "
                                    "onto --reference. Each pair writes into its own folder under --out (a row's "
                                    "output: a relative folder inside --out); a rerun skips "
                                    "pairs already done. Exit code: 0 all verified, 3 some not verified, 1 some "
                                    "failed.")
    bt.add_argument("source", help="job list (.csv/.gpkg), a folder of targets, or a glob pattern (quote it)")
    bt.add_argument("--out", required=True, help="output folder: one sub-folder per pair, batch.gpkg and batch.csv")
    bt.add_argument("--reference", default=None, help="the reference for targets from a folder or pattern (a raster, "
                                                      "a VRT mosaic or a map service, as for 'register')")
    bt.add_argument("--method", default="auto", help="matching method of every pair (a job's own overrides it)")
    add_options(bt)
    bt.add_argument("--overwrite", action="store_true",
                    help="replace files in a pair's folder that Hamta did not write there (that pair fails otherwise)")
    bt.add_argument("--accept-unverified", action="store_true",
                    help="write the outputs even when the result is not verified (the verdict is in every output)")
    bt.add_argument("--quiet", action="store_true", help="no progress bar")
    bt.add_argument("--scheduler", default=None, metavar="tls://HOST:PORT",
                    help="an existing Dask scheduler (workers need Hamta installed and access to the paths); "
                         "tls:// takes its certificates from Dask's configuration (distributed.comm.tls.ca-file, "
                         ".client.cert, .client.key), tcp:// is unauthenticated; default: a local cluster on "
                         "127.0.0.1 with TLS credentials of its own")
    bt.add_argument("--workers", type=int, default=None,
                    help="workers of the local cluster, at least 1 (default: CPU count)")
    bt.set_defaults(func=cmd_batch)

    m = sub.add_parser("map-points", help="map target pixels through the model stored in a report.json")
    m.add_argument("report", help="a report.json written by 'hamta register'")
    m.add_argument("coords", nargs="+", help="X Y pairs in target pixels (x = column, y = row, corner origin; put "
                                             "'--' before negative numbers)")
    m.add_argument("--json", action="store_true", help="print JSON instead of a table")
    m.set_defaults(func=cmd_map_points)

    ms = sub.add_parser("methods", help="the matching methods and when to use each")
    ms.add_argument("--verbose", action="store_true", help="also what each does, its source and its parameters")
    ms.set_defaults(func=cmd_methods)

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
    b.add_argument("--quiet", action="store_true", help="no progress bar")
    b.set_defaults(func=cmd_bench)

    t = sub.add_parser("train-pca-sift", help="learn the PCA-SIFT basis from images (maintainers)")
    t.add_argument("images", nargs="+", help="rasters to learn from (the shipped basis: the Landsat sample)")
    t.add_argument("--out", default=None, help="output .npz (default: the basis shipped with the package)")
    t.set_defaults(func=cmd_train_pca_sift)

    dm = sub.add_parser("demo", help="register the bundled sample and report the true error")
    dm.add_argument("--out", default="demo-output", help="folder for the sample and the result (default demo-output)")
    dm.add_argument("--method", default="sift", help="matching method (default sift)")
    dm.add_argument("--quiet", action="store_true", help="no progress bar")
    dm.set_defaults(func=cmd_demo)
    return p


def _joined_values(argv: List[str]) -> List[str]:
    """``--extent -8.9,...`` as ``--extent=-8.9,...``: argparse takes a value starting with '-' for a flag."""
    out = []
    for item in argv:
        if out and out[-1] == "--extent" and item[:1] == "-" and item[1:2].isdigit():
            out[-1] = f"{out[-1]}={item}"
        else:
            out.append(item)
    return out


def main(argv: Optional[List[str]] = None) -> int:
    """Run one ``hamta`` command; returns its exit code (see ``EXIT_*``); never shows a traceback
    unless ``HAMTA_DEBUG`` is set. Closed, full or abandoned standard streams change nothing but what
    is shown (see :class:`Tolerant`)."""
    streams = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = Tolerant(streams[0]), Tolerant(streams[1])
    try:
        return _main(argv)
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        sys.stdout, sys.stderr = streams


def _main(argv) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(_joined_values(sys.argv[1:] if argv is None else list(argv)))
    except SystemExit as exc:  # --help, --version, or a usage error argparse has already explained
        return exc.code if isinstance(exc.code, int) else EXIT_USAGE
    previous = _terminate_as_interrupt()
    try:
        return args.func(args)
    except KeyboardInterrupt:
        print("hamta: interrupted; no output was published", file=sys.stderr)
        return EXIT_CANCELED
    except RegistrationCanceled as exc:
        print(f"hamta: {exc}", file=sys.stderr)
        return EXIT_CANCELED
    except HamtaError as exc:
        print(f"hamta: error: {explain(exc)}", file=sys.stderr)
        return EXIT_ERROR
    except (ValueError, argparse.ArgumentTypeError) as exc:
        print(f"hamta: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # a bug: say so plainly, without a traceback
        if os.environ.get("HAMTA_DEBUG"):
            raise
        what = exc if isinstance(exc, MethodCrashed) else f"internal error ({type(exc).__name__}: {exc})"
        print(f"hamta: {what}. No output was published. Please report it; HAMTA_DEBUG=1 shows the details.",
              file=sys.stderr)
        return EXIT_ERROR
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


class Tolerant:
    """A standard stream that cannot end the run, nor be turned against the terminal: control characters
    other than newline, tab and carriage return are escaped (a message may quote a server). Once the
    reader has gone (``| head``), the stream is closed (``>&-``) or its disk is full (``>/dev/full``),
    what is written is dropped, so the exit code still says what the command did (its outputs are
    published whatever the terminal does)."""

    def __init__(self, stream):
        self.stream = stream
        self.broken = stream is None

    def write(self, text: str) -> int:
        if not self.broken:
            try:
                self.stream.write(terminal_safe(text))
            except (OSError, ValueError):
                self._drop()
        return len(text)

    def flush(self) -> None:
        if not self.broken:
            try:
                self.stream.flush()
            except (OSError, ValueError):
                self._drop()

    def isatty(self) -> bool:
        try:
            return not self.broken and self.stream.isatty()
        except (OSError, ValueError):
            return False

    def _drop(self) -> None:
        """Stop writing; the file descriptor points at /dev/null, so the interpreter's last flush is quiet."""
        self.broken = True
        with contextlib.suppress(OSError, ValueError, AttributeError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, self.stream.fileno())
            os.close(devnull)

    def __getattr__(self, name):
        return getattr(self.stream, name)


def _terminate_as_interrupt():
    """Make SIGTERM stop a run like Ctrl-C (staged outputs are removed); returns the old handler."""
    def interrupt(signum, frame):
        raise KeyboardInterrupt

    try:
        return signal.signal(signal.SIGTERM, interrupt)
    except ValueError:  # not the main thread
        return None


if __name__ == "__main__":
    sys.exit(main())
