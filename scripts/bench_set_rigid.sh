#!/usr/bin/env bash
# The rigid-body planning benchmark (docs/scenes.md, "Large rigid scenes"): the shipped rigid
# scenes (robots/scenes/rooms.yaml, narrow_passage.yaml) and a generated building
# (`octomotion make-building`), planned by `octomotion bench-set` with RRTConnect over several
# seeds in three set-ups: the octree checker with the certified motion validator (the defaults),
# FCL with the certified validator, and OMPL's defaults with FCL (`--motion-validator
# ompl-default`: OMPL's discrete validator at 1 % of the space's extent, as OMPL.app plans).
# Writes the section's markdown (the commands, then one summary table per set-up) to OUT.
#   scripts/bench_set_rigid.sh BUILD OUT
# scripts/write_benchmarks.sh bench_set_rigid calls it and stamps the section. Environment:
# OCTOMOTION_BENCH_RIGID_SEEDS=N plans each problem with seeds 1..N (default 5);
# OCTOMOTION_BENCH_RIGID_TIME=S the time limit (default 30). The CSVs and the OMPL logs stay in
# BUILD/bench-set-rigid/<set-up>.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$1
out=$2
seeds=${OCTOMOTION_BENCH_RIGID_SEEDS:-5}
time_limit=${OCTOMOTION_BENCH_RIGID_TIME:-30}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --build "$build" --target octomotion >/dev/null
cli=$build/planner/octomotion
# One set per folder; the shipped scenes are copied with their mesh paths made absolute.
mkdir -p "$tmp/problems/shipped"
for scene in rooms narrow_passage; do
  sed "s|\.\./meshes/|$root/robots/meshes/|" "$root/robots/scenes/$scene.yaml" \
    >"$tmp/problems/shipped/$scene.yaml"
done
"$cli" make-building "$tmp/problems/building" >/dev/null
results=$build/bench-set-rigid
# Each seed is a run of its own (bench-set's --runs repeats one seed).
run_setup() {  # name, then bench-set options
  local name=$1
  shift
  for ((seed = 1; seed <= seeds; ++seed)); do
    "$cli" bench-set "$tmp/problems" --planner RRTConnect --time "$time_limit" --seed "$seed" \
      "$@" --out-dir "$results/$name/seed$seed" >/dev/null 2>"$tmp/stderr" ||
      { cat "$tmp/stderr" >&2; exit 1; }
  done
  # The per-seed CSVs as one (the header once).
  awk 'FNR > 1 || NR == 1' "$results/$name"/seed*/results.csv >"$results/$name/results.csv"
}
run_setup octree --checkers octree-fused
run_setup fcl --checkers fcl
run_setup ompl_default --checkers fcl --motion-validator ompl-default
python3 "$root/scripts/bench_set_rigid_table.py" "$results" >"$tmp/table.md"
{
  echo "Commands: \`octomotion make-building problems/building\`, the shipped \`rooms.yaml\` and"
  echo "\`narrow_passage.yaml\` in \`problems/shipped\`, then for seeds 1 to $seeds:"
  echo "\`octomotion bench-set problems --planner RRTConnect --time $time_limit --seed N\` with"
  echo "\`--checkers octree-fused\` (the defaults: certified motion validator), \`--checkers fcl\`"
  echo "(FCL's distance in the certified validator) and \`--checkers fcl --motion-validator"
  echo "ompl-default\` (OMPL's defaults with FCL, as OMPL.app plans). Times: the planner's solve"
  echo "time, an unsolved run counted at the limit; motions: checkMotion calls per plan; FCL"
  echo "re-check: the simplified paths' states, each segment cut into 100x the pieces of the motion"
  echo "step, in collision under exact FCL."
  echo
  cat "$tmp/table.md"
} >"$out"
