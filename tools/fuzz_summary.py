"""Tally ``make fuzz`` logs (one JSON line per run) into a table of outcomes per method family.

Usage: python tools/fuzz_summary.py fuzz-output/*.jsonl
"""
import collections
import json
import os
import sys

OUTCOMES = {0: "exit 0", 1: "error (1)", 2: "usage (2)", 3: "unverified (3)"}


def main(paths):
    table = collections.defaultdict(collections.Counter)
    wrong, failed, slowest, total = [], [], {}, 0
    for path in paths:
        family = os.path.splitext(os.path.basename(path))[0]
        with open(path) as f:
            for line in f:
                row = json.loads(line)
                total += 1
                table[family][OUTCOMES.get(row["rc"], f"exit {row['rc']}")] += 1
                table[family]["runs"] += 1
                if row.get("error") is not None and row["error"] > 3.0:
                    wrong.append((family, row))
                if row.get("failures"):
                    failed.append((family, row))
                    table[family]["failed checks"] += 1
                slowest[family] = max(slowest.get(family, 0.0), row.get("time_s") or 0.0)
    columns = ["runs"] + list(OUTCOMES.values()) + ["failed checks"]
    print("| family | " + " | ".join(columns) + " | slowest run (s) |")
    print("|---" * (len(columns) + 2) + "|")
    for family in sorted(table):
        print(f"| {family} | " + " | ".join(str(table[family][c]) for c in columns) + f" | {slowest[family]:.1f} |")
    print(f"\n{total} runs; exit 0 while more than 3 px (RMS) off: {len(wrong)}; runs failing a check "
          f"(traceback, modified input, partial outputs, wrong exit): {len(failed)}")
    for family, row in failed:
        print(f"  {family}: {row}")
    return 1 if failed or wrong else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
