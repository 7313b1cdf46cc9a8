#!/usr/bin/env python3
"""Compares the answer columns of two scripts/answers_snapshot.sh runs.

usage: scripts/compare_answers.py BEFORE_DIR AFTER_DIR
Exit status 0 when every checker setting of every scene classified the same states the same way
(counts of free and colliding states, false positives and negatives against FCL, tree memory).
"""
import csv
import glob
import os
import sys

COLUMNS = ["scene", "checker", "resolution_m", "rounding", "states", "free_states",
           "colliding_states", "false_positives", "false_negatives", "memory_bytes"]


def rows(path):
    with open(path, newline="") as f:
        return [[r.get(c) for c in COLUMNS] for r in csv.DictReader(f)]


def main(before, after):
    files = sorted(glob.glob(os.path.join(before, "*", "*_checks.csv")))
    if not files:
        print(f"no *_checks.csv under {before}")
        return 2
    differing = compared = 0
    for f in files:
        rel = os.path.relpath(f, before)
        g = os.path.join(after, rel)
        if not os.path.exists(g):
            print(f"missing in {after}: {rel}")
            differing += 1
            continue
        a, b = rows(f), rows(g)
        compared += len(a)
        if a != b:
            differing += 1
            print(f"differs: {rel}")
            for x, y in zip(a, b):
                if x != y:
                    print(f"  before {x}\n  after  {y}")
            if len(a) != len(b):
                print(f"  {len(a)} rows before, {len(b)} after")
    print(f"{compared} settings compared, {differing} file(s) differ")
    return 1 if differing else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
