#!/usr/bin/env python3
"""The rigid-body benchmark's table (scripts/bench_set_rigid.sh): one row per problem, for each
set-up (a folder of RESULTS holding results.csv, bench-set's per-run rows) the runs solved, the
median planning time (an unsolved run at the limit), the mean motion checks (checkMotion calls)
per plan and the path states FCL finds in collision. State checks are left out: the discrete
validator's go through isValid, the certified validator's do not, so they do not compare."""
import csv
import statistics
import sys
from pathlib import Path

SETUPS = [("octree", "octree, certified"), ("fcl", "FCL, certified"),
          ("ompl_default", "OMPL defaults + FCL")]


def main():
    results = Path(sys.argv[1])
    rows = {}  # problem -> set-up -> runs
    for name, _ in SETUPS:
        with open(results / name / "results.csv", newline="") as f:
            for r in csv.DictReader(f):
                rows.setdefault(r["problem"], {}).setdefault(name, []).append(r)
    head = "| problem |" + "".join(f" {label}: solved, median, motions, FCL collisions |"
                                   for _, label in SETUPS)
    print(head)
    print("|---|" + "---|" * len(SETUPS))
    for problem in sorted(rows):
        cells = []
        for name, _ in SETUPS:
            runs = rows[problem].get(name, [])
            solved = sum(r["solved"] == "1" for r in runs)
            times = [float(r["time"]) for r in runs]
            checks = [float(r["motion_checks"] or 0) for r in runs]
            bad = sum(int(r["fcl_recheck_colliding"] or 0) for r in runs)
            median = statistics.median(times) if times else float("nan")
            shown = f"{median * 1000:.0f} ms" if median < 1 else f"{median:.2f} s"
            mean_checks = statistics.mean(checks) if checks else 0
            cells.append(f" {solved}/{len(runs)}, {shown}, {mean_checks:.0f}, {bad} |")
        print(f"| {problem} |" + "".join(cells))


if __name__ == "__main__":
    main()
