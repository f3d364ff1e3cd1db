"""``hamta bench``: every method and baseline on the synthetic families and the real pairs.

Each case is generated once, then every selected method registers it through the public
``register`` entry point (the one the CLI and Processing call) in the same worker process, one
after the other, so per-case time ratios to the SIFT baseline compare like with like. The
returned mapping is judged against ground truth (:mod:`hamta.core.evaluation.metrics`).
"""
from __future__ import annotations

import concurrent.futures as cf
import dataclasses
import datetime
import json
import multiprocessing
import os
import platform
import sys
import time
from dataclasses import asdict, dataclass
from typing import Callable, List, Optional, Sequence

from ..core import RegisterOptions, run
from ..core.auto import AUTO
from ..core.methods import all_methods
from ..core.outputs import OutputPaths
from ..core.outputs.report import clean
from ..core.result import versions
from .families import (
    DEFAULT_FAMILIES,
    FAMILIES,
    GROUPS,
    CaseSpec,
    available,
    build_case,
    default_data_dir,
    family_specs,
)
from .io_floor import io_floor
from .memory import PeakRss
from .metrics import judge
from .tables import BASELINE, markdown, summarise


@dataclass(frozen=True)
class BenchConfig:
    """What to run. ``size`` is the reference's longest side in pixels for synthetic cases."""

    methods: Sequence[str] = ()
    families: Sequence[str] = DEFAULT_FAMILIES
    size: int = 1024
    quick: bool = False
    jobs: int = 1
    out_dir: str = "bench-output"
    data_dir: str = ""
    reproductions: bool = True

    def resolved(self) -> "BenchConfig":
        methods = [m for m in (self.methods or default_methods(self.quick)) if m != BASELINE]
        methods.insert(0, BASELINE)  # the baseline always runs, first, so ratios have a reference
        families = [g for f in self.families for g in GROUPS.get(f, (f,))]
        unknown = [f for f in families if f not in FAMILIES]
        if unknown:
            raise ValueError(f"unknown famil{'y' if len(unknown) == 1 else 'ies'} {', '.join(unknown)}; "
                             f"choose from {', '.join(FAMILIES + tuple(GROUPS))}")
        for m in methods:
            parse_variant(m)  # raises on unknown methods, parameters or options
        return BenchConfig(tuple(methods), tuple(families), self.size, self.quick, max(1, self.jobs),
                           os.path.abspath(self.out_dir), self.data_dir or default_data_dir(), self.reproductions)


QUICK_BASELINES = ("sift", "orb", "phasecorr")


def default_methods(quick: bool) -> list:
    """'auto' and every method; for a quick run the product methods and the generic baselines only
    (the faithful versions and the papers' own baselines belong to full runs)."""
    return [AUTO] + [name for name, m in all_methods().items()
                     if not quick or m.kind == "method" or name in QUICK_BASELINES]


def parse_variant(text: str):
    """``name`` or ``name[key=value,...]`` -> (method name, method params, RegisterOptions fields).

    Keys are the method's parameters or, failing that, fields of RegisterOptions (e.g.
    ``ransac_threshold_px``); a variant is benchmarked as its own row.
    """
    name, _, rest = text.partition("[")
    if name not in all_methods() and name != AUTO:
        raise ValueError(f"unknown method {name!r}; available: {AUTO}, {', '.join(all_methods())}")
    params, options = {}, {}
    option_fields = {f.name for f in dataclasses.fields(RegisterOptions)}
    method_fields = set() if name == AUTO else {f.name for f in dataclasses.fields(all_methods()[name].params_type)}
    for item in filter(None, rest.rstrip("]").split(",")):
        key, _, value = item.partition("=")
        key = key.strip()
        if key in method_fields:
            params[key] = value.strip()
        elif key in option_fields:
            options[key] = _number_or_text(value.strip())
        else:
            raise ValueError(f"{key!r} is neither a parameter of {name!r} nor a registration option")
    if name != AUTO:
        all_methods()[name].make_params(params)
    return name, params, options


def _number_or_text(text: str):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def expand_sweep(methods: Sequence[str], sweeps: Sequence[str]) -> List[str]:
    """Every non-baseline method crossed with every ``key=v1,v2,...`` sweep value."""
    variants = [m for m in methods if m != BASELINE]
    for sweep in sweeps:
        key, _, values = sweep.partition("=")
        variants = [f"{m[:-1] + ',' if m.endswith(']') else m + '['}{key}={v}]"
                    for m in variants for v in values.split(",")]
    return [BASELINE] + variants


def run_case(spec: CaseSpec, config: BenchConfig) -> List[dict]:
    """Build one case and register it with every method; one result row per method."""
    folder = os.path.join(config.out_dir, "cases", spec.family)
    case = build_case(spec, folder, config.size, config.data_dir)
    # Large scenes are timed with their outputs written, against the IO floor measured here first.
    floor = io_floor(case, folder) if spec.family in WRITE_OUTPUTS else None
    rows = []
    for method in config.methods:
        name, params, overrides = parse_variant(method)
        # Benchmark pairs are judged in reference pixels, so a reference without georeferencing is fine.
        options = RegisterOptions(**dict({"model": spec.model, "tolerance_px": case.tolerance_px, "pixel_mode": True},
                                         **overrides))
        paths = OutputPaths.in_folder(os.path.join(folder, f"out-{_safe(method)}")) if floor else None
        result, error = None, None
        with PeakRss() as mem:
            t0 = time.perf_counter()
            try:
                result, _ = run(case.target, case.reference, paths, method=name, params=params, options=options,
                                accept_unverified=True)
            except Exception as exc:  # a HamtaError is a failure; anything else (MethodCrashed) a crash, see judge
                error = exc
        wall = time.perf_counter() - t0
        row = {"family": spec.family, "case": spec.name, "method": method, "model": spec.model,
               "tolerance_px": case.tolerance_px, "n_check_points": int(len(case.check_points)),
               "time_s": wall,
               "timings_s": result.timings.to_dict() if result is not None else {"total": wall},
               "peak_rss_mb": round(mem.peak, 1),
               "diagnostics": result.diagnostics if result is not None else {}}
        if floor:
            row.update(io_floor=floor, outputs_written=True)
        row.update(judge(case, result, error))
        rows.append(row)
    return rows


WRITE_OUTPUTS = ("large",)


def _safe(text: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in text)


def run_bench(config: BenchConfig, progress: Optional[Callable[[float, str], None]] = None) -> dict:
    """Run the benchmark; write ``bench.json`` and ``bench.md`` into ``config.out_dir``; return the report."""
    config = config.resolved()
    os.makedirs(config.out_dir, exist_ok=True)
    notes, specs = [], []
    for fam in config.families:
        if not available(fam, config.data_dir):
            notes.append(f"family '{fam}' skipped: no development data at {config.data_dir}")
            continue
        specs.extend(family_specs(fam, config.quick))
    t0 = time.perf_counter()
    rows: List[dict] = []
    done = 0
    for batch in _execute(specs, config):
        rows.extend(batch)
        done += 1
        if progress:
            progress(done / max(len(specs), 1), f"{done}/{len(specs)} cases")
    rows.sort(key=lambda r: (FAMILIES.index(r["family"]), r["case"], list(config.methods).index(r["method"])))
    reproductions, study_rows = run_reproductions(config, rows, progress) if config.reproductions else ([], {})
    report = {
        "meta": {"date": datetime.datetime.now().isoformat(timespec="seconds"), "duration_s": round(
            time.perf_counter() - t0, 1), "config": {k: list(v) if isinstance(v, tuple) else v
                                                    for k, v in asdict(config).items()},
                 "machine": {"cpus": os.cpu_count(), "platform": platform.platform()}, "versions": versions(),
                 "notes": notes},
        "summary": summarise(rows, config.methods),
        "reproductions": reproductions,
        "cases": rows,
        "study_rows": study_rows,
    }
    with open(os.path.join(config.out_dir, "bench.json"), "w") as f:
        json.dump(clean(report), f, indent=1, allow_nan=False)
    with open(os.path.join(config.out_dir, "bench.md"), "w") as f:
        f.write(markdown(report))
    return report


def run_reproductions(config: BenchConfig, bench_rows: List[dict], progress=None) -> tuple:
    """Each paper's own evaluation whose method is benchmarked and whose families are selected: (its tables,
    {study: its rows} of the studies with units of their own, to compare runs). A reproduction without units of
    its own is computed from the benchmark's rows."""
    from .studies import all_studies

    tables, study_rows = [], {}
    names = {parse_variant(m)[0] for m in config.methods}
    for rep in all_studies():
        if not set(rep.methods) & names or not set(rep.families) & set(config.families):
            continue
        if rep.units is None:
            rows = [r for r in bench_rows if r["family"] in rep.families]
            if rows:
                tables.extend(rep.tables(rows))
            continue
        units = rep.units(config)
        rows = []
        for i, unit_rows in enumerate(_map(_run_unit, [(rep.name, u, config) for u in units], config)):
            rows.extend(unit_rows)
            if progress:
                progress((i + 1) / len(units), f"reproducing {rep.name}: {i + 1}/{len(units)}")
        if rows:
            tables.extend(rep.tables(rows))
            study_rows[rep.name] = rows
    return tables, study_rows


def _run_unit(args):
    from .studies import all_studies

    name, unit, config = args
    return next(r for r in all_studies() if r.name == name).run_unit(unit, config)


def _pool(jobs: int):
    """Workers forked (fast) where the platform can, spawned where it cannot or where this process has run
    torch (the learned extra): a forked child deadlocks on the thread pools torch left in its parent."""
    fork = "fork" in multiprocessing.get_all_start_methods() and "torch" not in sys.modules
    method = "fork" if fork else "spawn"
    return cf.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context(method))


def _map(fn, items, config):
    """``fn`` over ``items`` in the order given, in the worker pool when ``config.jobs`` > 1."""
    if config.jobs <= 1 or len(items) <= 1:
        yield from map(fn, items)
        return
    with _pool(config.jobs) as pool:
        yield from pool.map(fn, items)


def _execute(specs, config):
    if config.jobs <= 1 or len(specs) <= 1:
        for spec in specs:
            yield run_case(spec, config)
        return
    with _pool(config.jobs) as pool:
        futures = [pool.submit(run_case, spec, config) for spec in specs]
        for fut in cf.as_completed(futures):
            yield fut.result()


