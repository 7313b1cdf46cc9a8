#!/usr/bin/env bash
# The candidate defaults on the MotionBenchMaker Panda problems (docs/trade-off.md, "Why these
# defaults"): `octomotion bench-set` on the first problems of each set, once with the voxels
# alone (--refine none, the previous default, and FCL in the same run) and once with the
# library's defaults (exact refine), then planner_refine_bench's false positives, check times
# and build times. Writes the section's markdown to OUT.
#   scripts/bench_defaults_mbm.sh BUILD OUT
# scripts/write_benchmarks.sh defaults calls it and stamps the section. Environment:
# OCTOMOTION_DEFAULTS_LIMIT=N problems per set (default 5); OCTOMOTION_BENCH_SET_DATA=DIR the
# data folder (default: ../shared/data beside the repository).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$1
out=$2
name=bench_defaults_mbm
# shellcheck source=scripts/mbm_extract.sh
source "$root/scripts/mbm_extract.sh"
limit=${OCTOMOTION_DEFAULTS_LIMIT:-5}
common=(--planner RRTConnect --time 1 --seed 1 --limit "$limit"
  --robot "$data/panda/panda.urdf" --srdf "$data/panda/panda.srdf")
cmake --build "$build" --target octomotion planner_refine_bench >/dev/null
run() {  # NAME ARGS...: one bench-set run, its summary to $tmp/NAME.md
  local name=$1
  shift
  "$build/planner/octomotion" bench-set "$tmp/problems" "$@" "${common[@]}" \
    --out-dir "$build/bench-defaults-$name" >"$tmp/$name.md" 2>"$tmp/$name.err" ||
    { cat "$tmp/$name.err" >&2; exit 1; }
}
run voxels --checkers octree-fused,fcl --refine none
run defaults --checkers octree-fused
{
  shown="${common[*]}"
  shown=${shown//$data/../shared/data}
  echo "Planning: \`octomotion bench-set problems $shown\` on \`mbm_panda/problems.tar.bz2\`"
  echo "extracted, as in the bench_set_mbm section; \"not loaded\" counts problems whose start or"
  echo "goal the checker rejects."
  echo
  echo "The voxels alone (\`--checkers octree-fused,fcl --refine none\`, the previous default):"
  echo
  cat "$tmp/voxels.md"
  echo
  echo "The defaults (\`--checkers octree-fused\`: exact refine):"
  echo
  cat "$tmp/defaults.md"
  echo
  echo "Checks: \`build/bench/planner_refine_bench 5000 4 0.01\` (uniform states; false positives"
  echo "of the states FCL finds free; build: the model's, FCL geometry and tables included):"
  echo
  echo '```text'
  (cd "$root" && "$build/bench/planner_refine_bench" 5000 4 0.01)
  echo '```'
} >"$out"
