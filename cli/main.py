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

from ..core.errors import HamtaError, MethodCrashed, Refused, RegistrationCanceled, UsageError
from ..core.text import terminal_safe
from .options import FLAGS, settings_from
from .parser import build_parser
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
            raise UsageError("--method grid georeferences a sheet by its own printed grid: give no --reference")
        method, params = "grid", dict(params, hints=args.gcps)
        if args.sheet_crs:
            params["sheet_crs"] = args.sheet_crs
    elif args.gcps is not None or args.sheet_crs is not None:
        raise UsageError("--gcps and --sheet-crs are for a sheet georeferenced by its own grid: leave out --reference")
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
        raise UsageError(f"--out '{out}' is inside Hamta's cache folder '{cache}'; choose a folder outside it")


def cmd_batch(args) -> int:
    from ..core.batch import read_jobs, run_batch
    from ..core.batch.table import write_results
    from ..core.batch.task import BatchSettings

    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be at least 1 (default: the CPU count), got {args.workers}")
    options, output = settings_from(args)
    _outside_the_cache(args.out)
    sheet_crs = args.sheet_crs or (output.crs if args.reference is None else None)  # as for one sheet: --crs
    jobs = read_jobs(args.source, args.out, args.reference, sheet_crs)
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
        raise UsageError(f"map-points takes X Y pairs of target pixels; got {len(args.coords)} numbers")
    try:
        values = [float(v) for v in args.coords]
    except ValueError:
        raise UsageError("map-points takes numbers (X Y pairs of target pixels), got "
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


COMMANDS = {"register": cmd_register, "batch": cmd_batch, "map-points": cmd_map_points, "methods": cmd_methods,
            "bench": cmd_bench, "train-pca-sift": cmd_train_pca_sift, "demo": cmd_demo}


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
        return COMMANDS[args.command](args)
    except KeyboardInterrupt:
        print("hamta: interrupted; no output was published", file=sys.stderr)
        return EXIT_CANCELED
    except RegistrationCanceled as exc:
        print(f"hamta: {exc}", file=sys.stderr)
        return EXIT_CANCELED
    except Refused as exc:  # found nothing to register: its report says what was read and tried
        print(f"hamta: error: {explain(exc)}", file=sys.stderr)
        for name, path in exc.written.items():
            print(f"{name:8s} {path}")
        return EXIT_ERROR
    except HamtaError as exc:
        print(f"hamta: error: {explain(exc)}", file=sys.stderr)
        return EXIT_ERROR
    except (UsageError, argparse.ArgumentTypeError) as exc:
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
