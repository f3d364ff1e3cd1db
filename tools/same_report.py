"""Whether two bench runs gave every case the same report: ``python tools/same_report.py A/bench.json B/bench.json``.

Compares, case by case, what a run decided (outcome, verdict, method, zoom, places and notes, requests, the
error to 3 decimals) and prints every difference; exits 1 when there is one. Times and memory are left out:
they are what a loaded machine changes. Used to check that a quiet and a loaded machine, or the wheels and
Debian's packages, give the same verdicts (issue 63)."""
import json
import sys

FIELDS = ("outcome", "verdict", "verified", "method_used", "method", "zoom", "zooms_read", "notes", "requests",
          "rms_px", "error_px", "rmse_px")


def _rows(path):
    out = json.load(open(path))["meta"]["config"]["out_dir"]
    report = json.loads(open(path).read().replace(out, "OUT"))  # the run's own folder, named in notes
    rows = {}
    for study, these in report.get("study_rows", {}).items():
        for r in these:
            rows[(study, str(r.get("unit") or r.get("case")), str(r.get("method")))] = r
    for r in report.get("cases", []):
        rows[("cases", r["case"], str(r.get("method")))] = r
    return rows


def _decided(row):
    out = {}
    for key in FIELDS:
        if key in row:
            value = row[key]
            out[key] = round(value, 3) if isinstance(value, float) else value
    return out


def main(a, b) -> int:
    first, second = _rows(a), _rows(b)
    differ = 0
    for key in sorted(set(first) ^ set(second)):
        print(" / ".join(key), "only in", a if key in first else b)
    for key in sorted(set(first) & set(second)):
        x, y = (_decided(rows[key]) for rows in (first, second))
        if x != y:
            differ += 1
            print(" / ".join(key))
            for field in sorted(set(x or {}) | set(y or {})):
                if (x or {}).get(field) != (y or {}).get(field):
                    print(f"  {field}: {(x or {}).get(field)!r} -> {(y or {}).get(field)!r}")
    print(f"{len(first)} and {len(second)} cases, {len(set(first) & set(second))} in both; {differ} of those differ")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
