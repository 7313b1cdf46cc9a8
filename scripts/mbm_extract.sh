# Sourced by the MotionBenchMaker bench scripts (bench_set_mbm.sh, bench_defaults_mbm.sh,
# bench_set_instructions.sh) after they set `root` and `name`: sets `data`
# (OCTOMOTION_BENCH_SET_DATA, default ../shared/data beside the repository) and `tmp` (a
# temporary folder, removed on exit) and extracts mbm_panda/problems.tar.bz2 into it, so the
# problems are at $tmp/problems.
data=${OCTOMOTION_BENCH_SET_DATA:-$root/../shared/data}
archive=$data/mbm_panda/problems.tar.bz2
[[ -f $archive ]] || { echo "$name: no $archive (see docs/benchmarking.md)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tar -xjf "$archive" -C "$tmp"
