#!/usr/bin/env bash
# Records the answers of every checker setting on the shipped scenes, for refactors that must not
# change them: the trade study's checks (no planning) on fixed-seed uniform states, two
# resolutions, every rounding and path, FCL and FCL+OctoMap. Compare two snapshots with
# scripts/compare_answers.py (it ignores the timing columns).
#   scripts/answers_snapshot.sh OCTOMOTION_BINARY OUT_DIR [STATES]
# scan_table is left out: its point cloud has no exact FCL reference.
set -euo pipefail
bin=$1
out=$2
states=${3:-3000}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
for scene in bookshelf cage cluttered_table narrow_passage rooms; do
  "$bin" bench "$root/robots/scenes/$scene.yaml" --states "$states" --runs 0 \
    --resolutions 0.04,0.02 --seed 7 --out-dir "$out/$scene" >/dev/null 2>"$out/$scene.log"
done
echo "answers of $bin in $out" >&2
