#!/usr/bin/env bash
# The planning benchmark on the 700 MotionBenchMaker Panda problems (docs/benchmarking.md):
# extracts ../shared/data/mbm_panda/problems.tar.bz2 to a temporary folder, runs `octomotion
# bench-set` on it with the real Panda (RRTConnect, 1 s, the defaults, octree-fused and fcl) and
# writes the section's markdown (the command, then the summary table) to OUT.
#   scripts/bench_set_mbm.sh BUILD OUT
# scripts/write_benchmarks.sh bench_set_mbm calls it and stamps the section. Environment:
# OCTOMOTION_BENCH_SET_LIMIT=N plans only the first N problems of each set (default: all);
# OCTOMOTION_BENCH_SET_CHECKERS=LIST the checkers (default: octree-fused,fcl);
# OCTOMOTION_BENCH_SET_DATA=DIR the data folder (default: ../shared/data beside the repository).
# The CSV and the OMPL logs stay in BUILD/bench-set-mbm.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$1
out=$2
name=bench_set_mbm
# shellcheck source=scripts/mbm_extract.sh
source "$root/scripts/mbm_extract.sh"
limit=()
[[ -n ${OCTOMOTION_BENCH_SET_LIMIT:-} ]] && limit=(--limit "$OCTOMOTION_BENCH_SET_LIMIT")
results=$build/bench-set-mbm
args=(--checkers "${OCTOMOTION_BENCH_SET_CHECKERS:-octree-fused,fcl}" --planner RRTConnect --time 1 --seed 1 "${limit[@]}"
  --robot "$data/panda/panda.urdf" --srdf "$data/panda/panda.srdf")
cmake --build "$build" --target octomotion >/dev/null
"$build/planner/octomotion" bench-set "$tmp/problems" "${args[@]}" --out-dir "$results" \
  >"$tmp/summary.md" 2>"$tmp/stderr" || { cat "$tmp/stderr" >&2; exit 1; }
{
  shown="${args[*]}"
  echo "Command: \`octomotion bench-set problems ${shown//$data/../shared/data}\` on"
  echo "\`mbm_panda/problems.tar.bz2\` extracted (\`problems/<set>/\`). Times: the planner's solve"
  echo "time, an unsolved problem counted at the limit; checks: isValid and checkMotion calls per"
  echo "plan; the FCL re-check: every solved path's simplified states, each segment cut into 100x"
  echo "the pieces of the motion step."
  echo
  cat "$tmp/summary.md"
  echo
  tail -n 1 "$tmp/stderr" | sed "s|$build|build|g; s|^octomotion: ||"
} >"$out"
