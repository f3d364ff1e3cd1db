"""Calibrate the independent check's thresholds on half of the development cases and report on the other half.

Usage:
    python tools/calibrate_check.py collect EVIDENCE.pkl [--jobs 2] [--part pairs|study]
    python tools/calibrate_check.py fit EVIDENCE.pkl [EVIDENCE2.pkl ...]

``collect`` keeps the evidence the check judged from (each look's per-site peaks, offsets, lifts and margins)
with the true error of the model judged, for two kinds of case:

- ``pairs``: ``auto`` on every pair of the real multimodal set (``../shared/data/multimodal``, 600 pairs, the
  bench's 15 px tolerance), every attempt it made;
- ``study``: the calibration study's models (``tools/verify_calibration.py``: the synthetic families and the
  real development pairs, each case's true model made wrong by 0.5-6 px; tolerance 3 px). These are most of the
  wrong models that come close: what keeps a looser setting from verifying them.

``fit`` re-judges that evidence under each setting of a grid of thresholds, replays ``auto`` on the pairs (the
first verified attempt is the answer; two suspect attempts of different methods that agree within the tolerance
verify each other), chooses the setting on the calibration half (odd pair numbers, odd case numbers of each
study family): no confident wrong answer, no unknown, then the fewest right answers flagged, then the fewest
thresholds changed. It reports the defaults and the chosen setting on both halves, so that the held-out half
(even numbers) predicts unseen cases.

A setting under which ``auto`` would have gone on past the last attempt it made under the defaults cannot be
replayed from the evidence; such pairs are counted as 'unknown'.
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import dataclasses
import itertools
import multiprocessing
import os
import pickle
import sys

import numpy as np

import hamta.core.pipeline as pipeline
import hamta.core.verify as verify_module
from hamta.bench.families import build_case, default_data_dir, family_specs
from hamta.bench.multimodal_set import CATEGORIES, build
from hamta.core import RegisterOptions, run
from hamta.core.verify import VERDICT_RANK, VerifyParams, second_look_worth
from hamta.core.verify.verdict import judge

# The thresholds fitted. The chance levels of a verified result (max_chance, max_z_chance, max_rank_chance) are not:
# they guard a search that checks many wrong places (a basemap search; the check itself when a method tries many
# poses), of which this evidence holds few. With them in the grid, the calibration half chose levels 100 times
# looser (1e-3), under which a search's Bonferroni share would be 100 times looser too. ``--wide`` fits them anyway.
GRID = {"max_suspect_chance": (1e-3, 3e-3, 1e-2, 3e-2), "max_contradict": (0.3, 0.4, 0.5, 0.6),
        "min_coverage": (0.3, 0.4)}
WIDE = {"max_chance": (1e-6, 1e-5, 1e-4, 1e-3), "max_z_chance": (1e-7, 1e-6, 1e-5, 1e-4),
        "max_rank_chance": (1e-3, 1e-2), "max_suspect_chance": (1e-3, 1e-2), "max_contradict": (0.4, 0.6)}
DEFAULTS = {k: getattr(VerifyParams(), k) for k in {**GRID, **WIDE}}
EVIDENCE = ("sites", "offsets", "peaks", "zero_z", "margins", "turned", "extent")


class Recorder:
    """Stands in for the verdict rule while a case runs: judges as it does and keeps what it judged from."""

    def __init__(self):
        self.looks = []

    def __call__(self, sites, offsets, peaks, zero_z, margins, turned, extent, params, elapsed=0.0):
        self.looks.append(dict(sites=sites, offsets=offsets, peaks=peaks, zero_z=zero_z, margins=margins,
                               turned=turned, extent=extent, params=params))
        return judge(sites, offsets, peaks, zero_z, margins, turned, extent, params, elapsed)

    def take(self) -> list:
        looks, self.looks = self.looks, []
        return looks


def collect_pair(key):
    """Every attempt of ``auto`` on one case (a multimodal pair, or a should-fail case: nothing to find): method,
    true RMS error (infinite without truth), the model at the check points, and each look's evidence."""
    family, pair = key
    if family == "should-fail":
        spec = family_specs(family)[pair - 1]
        case = build_case(spec, os.path.join("calibration-cases", family), 1024, default_data_dir())
    else:
        case = build(family, pair, default_data_dir())
    recorder, attempts = Recorder(), []
    register_auto = pipeline.register_auto

    def recording_auto(attempt, options, monitor, chain):
        def wrapped(name, p, mon, refine):
            recorder.take()
            result = attempt(name, p, mon, refine)
            e = case.errors(result.model) if case.truth is not None else np.array([np.inf])
            grid = result.model.apply(case.check_points if case.truth is not None else target_grid(result.target))
            attempts.append(dict(method=name, error_px=float(np.sqrt(np.mean(e ** 2))), looks=recorder.take(),
                                 grid=grid, verdict=result.verification.verdict))
            return result
        return register_auto(wrapped, options, monitor, chain)

    verify_module.judge, pipeline.register_auto = recorder, recording_auto
    try:
        result, _ = run(case.target, case.reference, None, options=RegisterOptions(
            tolerance_px=case.tolerance_px, pixel_mode=True), accept_unverified=True)
        verdict = result.verification.verdict
    except Exception as exc:  # no model at all: nothing to re-judge
        verdict = f"no model: {type(exc).__name__}"
    finally:
        verify_module.judge, pipeline.register_auto = judge, register_auto
    return [dict(kind="pair", family=family, number=pair, tolerance_px=case.tolerance_px, verdict=verdict,
                 attempts=attempts, more=True)]


def target_grid(target, n: int = 20) -> np.ndarray:
    gx, gy = np.meshgrid((np.arange(n) + 0.5) * target.width / n, (np.arange(n) + 0.5) * target.height / n)
    return np.column_stack([gx.ravel(), gy.ravel()])


def collect_study(key):
    """The calibration study's models of one case (``key``: family, case name, number), each with its evidence."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import verify_calibration as study

    family, name, number = key
    recorder, looks = Recorder(), []

    def recording_verify(*args, **kwargs):
        recorder.take()
        v = verify_module.verify(*args, **kwargs)
        looks.append(recorder.take())
        return v

    verify_module.judge, study.verify = recorder, recording_verify
    try:
        rows = study.study((family, name, 3.0, "calibration-cases"))
    finally:
        verify_module.judge = judge
    return [dict(kind="study", family=family, number=number, tolerance_px=3.0, verdict=r["verdict"], more=False,
                 attempts=[dict(method="model", error_px=r["true_error_px"], looks=lk, verdict=r["verdict"])])
            for r, lk in zip(rows, looks)]


def rejudge(attempt, overrides: dict):
    """The verdict of a recorded attempt with the thresholds ``overrides`` replacing those it was judged with;
    None where the evidence the replay needs was not recorded (a second look that the defaults did not take)."""
    looks = attempt["looks"]
    base = dataclasses.replace(looks[0]["params"], **overrides)
    first = judge(**{k: looks[0][k] for k in EVIDENCE}, params=base)
    if first.verdict == "verified" or not second_look_worth(first):
        return first.verdict
    if len(looks) < 2:
        return None
    second = judge(**{k: looks[1][k] for k in EVIDENCE}, params=base.second_look())
    return second.verdict if VERDICT_RANK[second.verdict] > VERDICT_RANK[first.verdict] else first.verdict


def replay(record, overrides: dict) -> str:
    """'right verified', 'wrong verified', 'right flagged', 'wrong flagged', 'none' or 'unknown' for one case."""
    tol = record["tolerance_px"]
    seen, best = [], None
    for a in record["attempts"]:
        verdict = rejudge(a, overrides)
        if verdict is None:
            return "unknown"
        if verdict == "suspect" and any(b["verdict"] == "suspect" and b["method"] != a["method"]
                                        and distance(a, b) <= tol for b in seen):
            verdict = "verified"
        current = dict(a, verdict=verdict)
        seen.append(current)
        if verdict == "verified":
            return ("right" if a["error_px"] <= tol else "wrong") + " verified"
        if best is None or VERDICT_RANK[verdict] > VERDICT_RANK[best["verdict"]]:
            best = current
    if record["more"] and record["verdict"] == "verified":
        return "unknown"  # auto stopped at a verified attempt that these settings refuse: later steps unseen
    if best is None:
        return "none"
    return ("right" if best["error_px"] <= tol else "wrong") + " flagged"


def distance(a, b) -> float:
    return float(np.sqrt(np.mean(np.sum((a["grid"] - b["grid"]) ** 2, axis=1))))


def settings(grid: dict):
    for values in itertools.product(*grid.values()):
        yield dict(zip(grid, values))


def describe(overrides: dict) -> str:
    return ", ".join(f"{k}={v:g}" for k, v in overrides.items())


def row(name, counts, n) -> str:
    flagged, wrong = counts.get("right flagged", 0), counts.get("wrong verified", 0)
    share = 100 * flagged / max(n, 1)
    return (f"| {name} | {n} | {counts.get('right verified', 0)} | {wrong} | {flagged} ({share:.1f} %) | "
            f"{counts.get('unknown', 0)} |")


def groups(records, members):
    """(label, indexes) for the table: the pairs by category, the should-fail cases, the study's models by true
    error; of the records at ``members``."""
    def where(test):
        return [i for i in members if test(records[i])]

    out = [("multimodal pairs", where(lambda r: r["family"] in CATEGORIES))]
    out += [(f"&nbsp;&nbsp;{f}", where(lambda r, f=f: r["family"] == f)) for f in CATEGORIES]
    out.append(("should-fail cases (every verified answer wrong)", where(lambda r: r["family"] == "should-fail")))
    study = [(label, where(lambda r, lo=lo, hi=hi: r["kind"] == "study" and lo < r["attempts"][0]["error_px"] <= hi))
             for label, lo, hi in (("study models ≤ 2 px", -1.0, 2.0), ("study models 2–3 px", 2.0, 3.0),
                                   ("study models > 3 px", 3.0, np.inf))]
    return [(label, sub) for label, sub in out + study if sub]


_RECORDS: list = []  # the records a fit's worker processes replay (inherited when they fork)


def _outcomes(overrides: dict) -> list:
    return [replay(r, overrides) for r in _RECORDS]


def count(outcomes, chosen) -> dict:
    counts = {}
    for i in chosen:
        counts[outcomes[i]] = counts.get(outcomes[i], 0) + 1
    return counts


def fit(records, jobs: int, grid: dict) -> str:
    global _RECORDS
    _RECORDS = records
    halves = {"calibration (odd)": [i for i, r in enumerate(records) if r["number"] % 2],
              "held out (even)": [i for i, r in enumerate(records) if not r["number"] % 2]}
    calibration, held_out = halves.values()
    pairs = [i for i in calibration if records[i]["family"] in CATEGORIES]
    defaults = {k: DEFAULTS[k] for k in grid}
    grid = list(settings(grid))
    with cf.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("fork")) as pool:
        results = dict(zip(map(describe, grid), pool.map(_outcomes, grid, chunksize=4)))
    scored = []
    for overrides in grid:
        outcomes = results[describe(overrides)]
        c = count(outcomes, calibration)
        if c.get("wrong verified", 0) or c.get("unknown", 0):
            continue
        changed = sum(overrides[k] != defaults[k] for k in overrides)
        flagged = count(outcomes, pairs).get("right flagged", 0)
        scored.append((flagged, -c.get("right verified", 0), changed, describe(overrides), overrides))
    scored.sort(key=lambda s: s[:4])
    chosen = scored[0][4] if scored else defaults
    lines = [f"chosen on the calibration half: {describe(chosen)}", f"defaults: {describe(defaults)}", "",
             "| setting, half, cases | cases | right verified | wrong verified | right flagged | unknown |",
             "|---|---|---|---|---|---|"]
    for label, overrides in (("defaults", defaults), ("chosen", chosen)):
        outcomes = results[describe(overrides)]
        for half, members in halves.items():
            for name, sub in groups(records, members):
                lines.append(row(f"{label}, {half}: {name}", count(outcomes, sub), len(sub)))
    lines += ["", "the best settings without wrong or unknown on the calibration half (its multimodal pairs right "
              "but flagged; the held-out half's figures):"]
    for s in scored[:15]:
        lines.append(f"- {s[3]}: {s[0]}; held out {count(results[s[3]], held_out)}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("step", choices=("collect", "fit"))
    parser.add_argument("evidence", nargs="+")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--part", choices=("pairs", "study", "should-fail"), default="pairs")
    parser.add_argument("--wide", action="store_true", help="fit the chance levels too (see GRID)")
    args = parser.parse_args(argv)
    if args.step == "collect":
        if args.part == "pairs":
            work, keys = collect_pair, [(f, p) for f in CATEGORIES for p in range(1, 101)]
        elif args.part == "should-fail":
            work, keys = collect_pair, [("should-fail", i) for i in range(1, len(family_specs("should-fail")) + 1)]
        else:
            sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
            from verify_calibration import FAMILIES

            work = collect_study
            keys = [(f, s.name, i) for f in FAMILIES for i, s in enumerate(family_specs(f), 1)]
        with cf.ProcessPoolExecutor(args.jobs) as pool:
            records = [r for batch in pool.map(work, keys) for r in batch]
        with open(args.evidence[0], "wb") as fh:
            pickle.dump(records, fh)
        print(f"{len(records)} cases, {sum(len(r['attempts']) for r in records)} attempts -> {args.evidence[0]}")
    else:
        records = []
        for path in args.evidence:
            with open(path, "rb") as fh:
                records += pickle.load(fh)
        print(fit(records, args.jobs, WIDE if args.wide else GRID))
    return 0


if __name__ == "__main__":
    sys.exit(main())
