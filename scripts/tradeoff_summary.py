#!/usr/bin/env python3
"""Per-scene summary of a trade study, as markdown tables.

Reads the study's checks.csv and planning.csv (runTradeStudy's output, kCheckCsvColumns) and
prints, for every scene: FCL's reference line, one row per resolution comparing the fused
conservative octree with FCL and FCL+OctoMap (and the fused centre-rounding octree), and the
planning results. Numbers are printed as measured (3 significant digits), the ratios too: FCL /
octree is the study's paired ratio (speedup_vs_fcl, FCL timed right before each pass), FCL+OctoMap
env / octree env its env_speedup_vs_fcl_octomap.

usage: scripts/tradeoff_summary.py STUDY_DIR [IMAGE_PREFIX]   (IMAGE_PREFIX default: trade-off/)

STUDY_DIR is a --out-dir of bench/tradeoff_bench or `octomotion bench` (docs/trade-off.md,
"Commands"); IMAGE_PREFIX is where the tables link the plots that scripts/plot_tradeoff.sh
draws. Study directories are not kept in git: the study's commands regenerate them.
"""
import csv
import sys


def g(x):
    return f"{float(x):.3g}"


def pct(x):
    return g(100 * float(x))


def label(res_m):
    r = float(res_m)
    return f"{g(r * 100)} cm" if r >= 0.01 - 1e-12 else f"{g(r * 1000)} mm"


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    study, images = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "trade-off/")
    with open(f"{study}/checks.csv") as f:
        checks = list(csv.DictReader(f))
    try:
        with open(f"{study}/planning.csv") as f:
            planning = list(csv.DictReader(f))
    except FileNotFoundError:
        planning = []
    scenes = list(dict.fromkeys(r["scene"] for r in checks))
    for scene in scenes:
        rows = [r for r in checks if r["scene"] == scene]
        fcl = next(r for r in rows if r["checker"] == "fcl")
        print(f"### {scene}\n")
        print(f"![{scene}: check time vs false positives]({images}{scene}_tradeoff.png)\n")
        print(f"{fcl['states']} states, {fcl['colliding_states']} colliding per FCL. FCL: mean "
              f"{g(fcl['mean_us'])} µs (environment only {g(fcl['env_mean_us'])} µs), median free "
              f"{g(fcl['median_free_us'])} µs, median colliding {g(fcl['median_colliding_us'])} µs.\n")
        print("| resolution | octree-fused conservative: mean µs (env-only) | FP % (env FP %) | "
              "FCL / octree | FCL+OctoMap mean µs (env-only) | OctoMap FP % | "
              "FCL+OctoMap env / octree env | octree-fused center: mean µs | "
              "center FP % / FN % | memory KiB octree / OctoMap |")
        print("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
        resolutions = sorted({float(r["resolution_m"]) for r in rows if r["checker"] != "fcl"},
                             reverse=True)
        for res in resolutions:
            def find(checker, rounding=""):
                for r in rows:
                    if (r["checker"] == checker and abs(float(r["resolution_m"]) - res) < 1e-12
                            and r["rounding"] == rounding):
                        return r
                return None
            oc = find("octree-fused", "conservative")
            om = find("fcl-octomap")
            ce = find("octree-fused", "center")
            if oc is None:
                continue
            cells = [label(res),
                     f"{g(oc['mean_us'])} ({g(oc['env_mean_us'])})",
                     f"{pct(oc['fp_rate'])} ({pct(oc['env_fp_rate'])})",
                     g(oc["speedup_vs_fcl"])]
            if om:
                cells += [f"{g(om['mean_us'])} ({g(om['env_mean_us'])})", pct(om["fp_rate"]),
                          g(oc["env_speedup_vs_fcl_octomap"])]
            else:
                cells += ["–", "–", "–"]
            cells += [g(ce["mean_us"]), f"{pct(ce['fp_rate'])} / {pct(ce['fn_rate'])}"] if ce \
                else ["–", "–"]
            mem_om = g(float(om["memory_bytes"]) / 1024) if om else "–"
            cells.append(f"{g(float(oc['memory_bytes']) / 1024)} / {mem_om}")
            print("| " + " | ".join(cells) + " |")
        plans = [p for p in planning if p["scene"] == scene]
        if plans:
            print(f"\n![{scene}: planning time vs resolution]({images}{scene}_planning.png)\n")
            # median solve s: the planner's own solve, without what Benchmark adds to every run
            # (planning.csv from before that column has none: "–")
            print("| planner | checker | solved | median time s | median solve s "
                  "| median first solution s | median length |")
            print("|---|---|--:|--:|--:|--:|--:|")
            for p in plans:
                checker = p["checker"]
                if float(p["resolution_m"]) > 0:
                    checker += " " + label(p["resolution_m"])
                if p["rounding"]:
                    checker += " " + p["rounding"]
                first = g(p["median_first_solution_s"]) if float(p["median_first_solution_s"]) >= 0 \
                    else "–"
                length = g(p["median_length"]) if float(p["median_length"]) >= 0 else "–"
                solve = g(p["median_solve_time_s"]) if p.get("median_solve_time_s") else "–"
                print(f"| {p['planner']} ({g(p['time_limit_s'])} s) | {checker} | "
                      f"{p['solved']}/{p['runs']} | {g(p['median_time_s'])} | {solve} | {first} "
                      f"| {length} |")
        print()


if __name__ == "__main__":
    main()
