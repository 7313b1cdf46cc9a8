#!/usr/bin/env bash
# Writes docs/benchmarks.md, the one page of measured figures, from the bench programs. Each
# section is stamped with the commit, the date and the machine it was measured on; sections not
# named on the command line keep what the page had (so a long study need not rerun for a quick
# one). Run from a configured Release build (scripts/run.sh demo builds one):
#   scripts/write_benchmarks.sh [--build DIR] [SECTION ...]     (no SECTION: all of them)
# Sections: differential motion octree builders translate primitive_contact planner_environment
#           planner_selfcollision planner_clearance pointoctree self_pair_tables check_breakdown
#           plan_split validity_checker broadphase world_updates refine motion_validator
#           tradeoff python_check_many bench_set_mbm bench_set_instructions bench_set_rigid
#           defaults hull_distance
# Environment: OCTOMOTION_DIFFERENTIAL_STATES (default 1000000).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
if [[ ${1:-} == --build ]]; then
  build=$(cd "$2" && pwd)
  shift 2
fi
out=$root/docs/benchmarks.md
all=(differential motion octree builders translate primitive_contact planner_environment
  planner_selfcollision planner_clearance pointoctree self_pair_tables check_breakdown plan_split
  validity_checker broadphase world_updates refine motion_validator tradeoff python_check_many
  bench_set_mbm bench_set_instructions bench_set_rigid defaults hull_distance)
selected=("$@")
((${#selected[@]})) || selected=("${all[@]}")

gbench="--benchmark_repetitions=5 --benchmark_report_aggregates_only=true"
states=${OCTOMOTION_DIFFERENTIAL_STATES:-1000000}
# section -> title | bench target | arguments (relative to the repository root)
declare -A title target args
add() { title[$1]=$2; target[$1]=$3; args[$1]=$(printf "%s" "$4" | tr -s " \n" " "); }
add differential "Randomised differential validation against FCL (docs/validation.md §6)" \
  validation_differential_bench "--states $states --per-case 4000 --seed 1"
add motion "Moving trees and the fused query (motion_bench)" motion_bench "$gbench"
add octree "Octree queries and file I/O (octree_bench)" octree_bench "$gbench"
add builders "Builders (builders_bench)" builders_bench "$gbench"
add translate "Translations and quarter turns (translate_bench)" translate_bench "$gbench"
add primitive_contact "Exact primitives against the voxel query (primitive_contact_bench)" \
  primitive_contact_bench "$gbench"
add planner_environment "Many environment objects (planner_environment_bench)" \
  planner_environment_bench "$gbench"
add planner_selfcollision "Self-collision broad phase (planner_selfcollision_bench)" \
  planner_selfcollision_bench "$gbench"
add planner_clearance "Clearance (planner_clearance_bench)" planner_clearance_bench "$gbench"
add pointoctree "Point octree against nanoflann (pointoctree_bench)" pointoctree_bench "$gbench"
add self_pair_tables "Self-pair tables, bookshelf at 5 mm (planner_self_pair_tables_bench)" \
  planner_self_pair_tables_bench "robots/scenes/bookshelf.yaml 0.005 20000"
add check_breakdown "Where a check's time goes, cage at 5 mm (planner_check_breakdown_bench)" \
  planner_check_breakdown_bench "robots/scenes/cage.yaml 0.005"
add plan_split "Where a plan's time goes, bookshelf at 1 cm (planner_plan_split_bench)" \
  planner_plan_split_bench "robots/scenes/bookshelf.yaml 0.01"
add validity_checker "The OMPL validity checker per scene and checker (planner_validity_checker_bench)" \
  planner_validity_checker_bench "$gbench"
add broadphase "N-objects octree broad phase (broadphase_bench)" broadphase_bench ""
add world_updates "A world that changes between plans, the Panda at 1 cm (planner_world_updates_bench)" \
  planner_world_updates_bench "$gbench"
add refine "Exact refine mode, the Panda in MotionBenchMaker scenes and the arm scenes at 1 cm (planner_refine_bench)" \
  planner_refine_bench "5000 4 0.01 0123 0 robots/scenes/bookshelf.yaml robots/scenes/cage.yaml
  robots/scenes/cluttered_table.yaml"
add hull_distance "Hull distance bounds against FCL's distance, Panda self pairs (planner_hull_distance_bench)" \
  planner_hull_distance_bench "$gbench"
add motion_validator "Motion validators on the Panda MotionBenchMaker problems (planner_motion_validator_bench)" \
  planner_motion_validator_bench "--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
# The arm scenes, with exact refine as its own rows; the section is the study's results.md.
add tradeoff "Speed/accuracy trade study, the arm scenes (tradeoff_bench; docs/trade-off.md)" \
  tradeoff_bench "--only bookshelf,cage,cluttered_table --states 5000 --move-tree-states 200
  --resolutions 0.02,0.01,0.005 --refine-exact --no-fcl-octomap --runs 10 --planners RRTConnect:1
  --out-dir $build/tradeoff-results"
add bench_set_mbm "Planning on the MotionBenchMaker Panda problems (octomotion bench-set)" \
  octomotion ""
add bench_set_instructions "Instructions per plan on the MotionBenchMaker Panda problems (callgrind)" \
  octomotion ""
add bench_set_rigid "Planning rigid bodies, a generated building included (octomotion bench-set)" \
  octomotion ""
add defaults "The defaults against the voxels alone, MotionBenchMaker Panda problems (docs/trade-off.md)" \
  octomotion ""

# A Python bench: its target is the extension, its program a script run by the module's interpreter.
add python_check_many "Python check_many against the C++ per-state time (python_check_many_bench.py)" \
  _octomotion "--states 1000,10000 --cli $build/planner/octomotion"
python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null || true)

commit=$(git -C "$root" rev-parse --short HEAD)
git -C "$root" diff --quiet HEAD -- octree planner bench tests || commit="$commit+changes"
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//' || echo unknown)
stamp="Measured at commit $commit on $(date -u +%Y-%m-%d), $(nproc) cores of $cpu."

# The text between a section's markers in the page as it is.
old_section() {
  [[ -f $out ]] || return 0
  awk -v name="$1" '$0 == "<!-- section " name " -->" {on = 1} on {print}
    $0 == "<!-- end " name " -->" {on = 0}' "$out"
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for s in "${selected[@]}"; do
  [[ -n ${title[$s]:-} ]] || { echo "unknown section $s (one of: ${all[*]})" >&2; exit 2; }
  if [[ $s == bench_set_* ]]; then  # a command over a problem set, not a bench program
    echo "write_benchmarks: $s" >&2
    "$root/scripts/$s.sh" "$build" "$tmp/$s.body"
    printf '<!-- section %s -->\n## %s\n\n%s\n\n' "$s" "${title[$s]}" "$stamp" >"$tmp/$s.md"
    cat "$tmp/$s.body" >>"$tmp/$s.md"
    echo "<!-- end $s -->" >>"$tmp/$s.md"
    continue
  fi
  if [[ $s == defaults ]]; then  # two bench-set runs and a bench program
    echo "write_benchmarks: $s" >&2
    "$root/scripts/bench_defaults_mbm.sh" "$build" "$tmp/$s.body"
    printf '<!-- section %s -->\n## %s\n\n%s\n\n' "$s" "${title[$s]}" "$stamp" >"$tmp/$s.md"
    cat "$tmp/$s.body" >>"$tmp/$s.md"
    echo "<!-- end $s -->" >>"$tmp/$s.md"
    continue
  fi
  cmake --build "$build" --target "${target[$s]}" >/dev/null
  echo "write_benchmarks: $s" >&2
  program=("$build/bench/${target[$s]}")
  shown="build/bench/${target[$s]}"
  if [[ ${target[$s]} == _octomotion ]]; then
    program=(env "PYTHONPATH=$build/python" "${python:-python3}" "bench/$s""_bench.py")
    shown="PYTHONPATH=build/python ${python:-python3} bench/$s""_bench.py"
  fi
  # shellcheck disable=SC2086
  if ! result=$(cd "$root" && "${program[@]}" ${args[$s]} 2>&1); then
    echo "$result" >&2
    echo "write_benchmarks: $s failed; docs/benchmarks.md not written" >&2
    exit 1
  fi
  {
    echo "<!-- section $s -->"
    echo "## ${title[$s]}"
    echo
    echo "$stamp Command: \`$shown ${args[$s]//$build/build}\`"
    echo
    if [[ $s == tradeoff ]]; then  # its tables are in the results file, its output is progress
      sed 's/^### /### Scene: /' "$build/tradeoff-results/results.md"
    elif [[ $s == differential ]]; then
      echo "Per checker path: FCL's contacts; the octree's missed contacts (none allowed with"
      echo "conservative rounding); the free states it rejects, their FCL distance as a fraction of"
      echo "the path's margin (none allowed above 1), and those where one solid lies inside another."
      echo
      echo "$result" | grep -v '^took \|^differential validation:'
    else
      echo '```text'
      # OMPL's note that its sampler was seeded before (each benchmark loads a scene) is noise.
      echo "$result" | grep -v '^\*\*\*WARNING\|^$\|^Error: *Random number generation already started\|^ *at line [0-9]* in .*RandomNumbers.cpp'
      echo '```'
    fi
    echo "<!-- end $s -->"
  } >"$tmp/$s.md"
done

{
  echo "# Measured figures"
  echo
  echo "Generated by \`scripts/write_benchmarks.sh\` from the bench programs; do not edit. Each"
  echo "section says the commit and the machine it was measured on; rerun one with"
  echo "\`scripts/write_benchmarks.sh SECTION\`. Medians are over repetitions (Google Benchmark:"
  echo "\`_median\` rows) or over the states of a run, as each program says."
  for s in "${all[@]}"; do
    echo
    if [[ -f $tmp/$s.md ]]; then
      cat "$tmp/$s.md"
    elif [[ -n $(old_section "$s") ]]; then
      old_section "$s"
    else
      printf '<!-- section %s -->\n## %s\n\nNot measured yet: `scripts/write_benchmarks.sh %s`.\n<!-- end %s -->\n' \
        "$s" "${title[$s]}" "$s" "$s"
    fi
  done
} >"$tmp/page.md"
mv "$tmp/page.md" "$out"
echo "wrote $out" >&2
