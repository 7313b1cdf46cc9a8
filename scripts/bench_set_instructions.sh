#!/usr/bin/env bash
# Instructions per plan on MotionBenchMaker Panda problems (docs/benchmarking.md): runs
# `octomotion bench-set` under callgrind on the first N problems of each set (the defaults,
# RRTConnect, seed 1, the octree-fused checker), counts the instructions inside each
# RRTConnect::solve and writes the section's markdown (the command, then a table per set) to OUT.
# A count does not move with the machine's speed or load, so two builds' counts compare their
# plans' work where their wall-clock times would compare the hours they ran in.
#   scripts/bench_set_instructions.sh BUILD OUT
# scripts/write_benchmarks.sh bench_set_instructions calls it and stamps the section.
# Environment: OCTOMOTION_BENCH_INSTRUCTIONS_LIMIT=N problems per set (default 10);
# OCTOMOTION_BENCH_SET_DATA=DIR the data folder (default: ../shared/data beside the repository).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$1
out=$2
name=bench_set_instructions
command -v valgrind >/dev/null || { echo "$name: valgrind is not installed" >&2; exit 1; }
# shellcheck source=scripts/mbm_extract.sh
source "$root/scripts/mbm_extract.sh"
limit=${OCTOMOTION_BENCH_INSTRUCTIONS_LIMIT:-10}
results=$build/bench-set-instructions
# A time limit no plan reaches under callgrind: the plans are those of a 1 s limit without it,
# since every problem solves within 1 s there (bench_set_mbm) and the limit draws no samples.
args=(--checkers octree-fused --planner RRTConnect --time 1000 --seed 1 --limit "$limit"
  --robot "$data/panda/panda.urdf" --srdf "$data/panda/panda.srdf" --recheck-density 1)
cmake --build "$build" --target octomotion >/dev/null
mkdir -p "$tmp/cg"
# Counted inside RRTConnect::solve only; a profile is dumped as each SimpleSetup::solve begins,
# so dump k + 1 holds plan k and the final profile the last plan.
valgrind --tool=callgrind --toggle-collect='ompl::geometric::RRTConnect::solve*' \
  --dump-before='ompl::geometric::SimpleSetup::solve*' --callgrind-out-file="$tmp/cg/cg.out" \
  "$build/planner/octomotion" bench-set "$tmp/problems" "${args[@]}" --out-dir "$results" \
  >/dev/null 2>"$tmp/stderr" || { tail -n 20 "$tmp/stderr" >&2; exit 1; }
{
  shown="${args[*]}"
  echo "Command: \`valgrind --tool=callgrind --toggle-collect='ompl::geometric::RRTConnect::solve*'"
  echo "--dump-before='ompl::geometric::SimpleSetup::solve*' octomotion bench-set problems"
  echo "${shown//$data/../shared/data}\` on \`mbm_panda/problems.tar.bz2\` extracted. Instructions:"
  echo "those callgrind counts inside each plan's RRTConnect::solve (millions); the plans are the"
  echo "ones \`bench_set_mbm\` times (the same seed per problem, every one solved within 1 s)."
  echo
  python3 - "$tmp/cg" "$results/results.csv" <<'EOF'
import csv, glob, math, os, re, sys

folder, table = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(table)))
def totals(path):
    for line in open(path):
        if line.startswith('summary:') or line.startswith('totals:'):
            return int(line.split()[1])
    raise SystemExit(f'bench_set_instructions: no total in {path}')
dumps = sorted(glob.glob(os.path.join(folder, 'cg.out.*')),
               key=lambda p: int(re.search(r'\.(\d+)$', p).group(1)))
counts = [totals(p) for p in dumps[1:]] + [totals(os.path.join(folder, 'cg.out'))]
if len(counts) != len(rows):
    raise SystemExit(f'bench_set_instructions: {len(counts)} profiles for {len(rows)} plans')
sets = {}
for row, count in zip(rows, counts):
    sets.setdefault(row['set'], []).append((count, row))
def quantile(values, p):
    # Nearest rank, as bench-set's own summary takes its medians and 90th percentiles.
    rank = math.ceil(p * len(values))
    return values[min(len(values) - 1, max(rank, 1) - 1)]
def line(name, items):
    values = sorted(c / 1e6 for c, _ in items)
    solved = sum(int(r['solved']) for _, r in items)
    print(f'| {name} | {len(items)} | {solved}/{len(items)} | {quantile(values, 0.5):.2f} | '
          f'{quantile(values, 0.9):.2f} | {sum(values):.1f} |')
print('| set | problems | solved | median instructions / plan (M) | p90 (M) | total (M) |')
print('|---|---|---|---|---|---|')
for name in sorted(sets):
    line(name, sets[name])
line('all', [item for name in sorted(sets) for item in sets[name]])
EOF
} >"$out"
