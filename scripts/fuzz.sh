#!/usr/bin/env bash
# Fuzzes every loader (and the fused collision query against its oracle) with libFuzzer:
# configures build-fuzz with clang, ASan + UBSan and -DOCTOMOTION_FUZZ=ON, builds the targets in
# fuzz/, then runs them (as many at a time as there are cores) for a bounded time each, seeded
# with a scratch copy of fuzz/corpus/<name>/ (so the repository is never modified) and the
# format's dictionary fuzz/dict/<name>.dict.
#   usage: scripts/fuzz.sh [seconds per target, default 60] [target names...]
# Exits non-zero when any target reports a finding (crash, sanitizer report, leak, timeout
# over 10 s, more than 2 GB, an exception other than octomotion::Error, or a failed oracle); the
# reproducer is kept in <build>/fuzz-findings/<name>/ and the log printed.
# Environment: OCTOMOTION_FUZZ_BUILD_DIR (default build-fuzz), OCTOMOTION_CMAKE_ARGS (extra cmake
# args, e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache), OCTOMOTION_FUZZ_SEED (libFuzzer's -seed; CI
# fixes it so a run can be replayed; unset, every run explores differently).
set -euo pipefail

seconds=${1:-60}
shift || true
if ! [[ $seconds =~ ^[0-9]+$ ]] || ((seconds == 0)); then
  echo "usage: $0 [seconds per target] [target...]" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=${OCTOMOTION_FUZZ_BUILD_DIR:-$root/build-fuzz}

targets=("$@")
if ((${#targets[@]} == 0)); then
  for dir in "$root"/fuzz/corpus/*/; do
    targets+=("$(basename "$dir")")
  done
fi

# shellcheck disable=SC2086
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DOCTOMOTION_WERROR=ON -DOCTOMOTION_FUZZ=ON -DOCTOMOTION_SANITIZE=address,undefined \
  -DOCTOMOTION_BUILD_TESTS=OFF -DOCTOMOTION_BUILD_BENCH=OFF ${OCTOMOTION_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/%/_fuzz}"

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
findings_root=$build/fuzz-findings

# One target: its own scratch corpus and log; the outcome goes to $work/status.
fuzz_one() {
  local t=$1 work=$scratch/$1 findings=$findings_root/$1
  mkdir -p "$work/corpus" "$findings"
  cp -R "$root/fuzz/corpus/$t/." "$work/corpus/"
  local args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
    -artifact_prefix="$findings/")
  [[ -f $root/fuzz/dict/$t.dict ]] && args+=(-dict="$root/fuzz/dict/$t.dict")
  [[ -n ${OCTOMOTION_FUZZ_SEED:-} ]] && args+=(-seed="$OCTOMOTION_FUZZ_SEED")
  # The harnesses write their temporary input files to TMPDIR.
  if TMPDIR=$work ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp" \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/fuzz/${t}_fuzz" "${args[@]}" "$work/corpus" >"$work/log" 2>&1; then
    echo ok >"$work/status"
  else
    echo failed >"$work/status"
  fi
}

# As many targets at a time as there are cores (each is one process); reports in target order.
slots=$(nproc)
echo "== fuzz: ${#targets[@]} targets, ${seconds} s each, ${slots} at a time"
for t in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= slots)); do wait -n || true; done
  fuzz_one "$t" &
done
wait
failed=()
for t in "${targets[@]}"; do
  echo "== fuzz $t (${seconds} s)"
  if [[ $(cat "$scratch/$t/status" 2>/dev/null) == ok ]]; then
    grep -E "^(#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|stat::new_units_added)" \
      "$scratch/$t/log" || true
  else
    failed+=("$t")
    tail -n 60 "$scratch/$t/log" 2>/dev/null || true
    echo "!! $t: finding kept in $findings_root/$t/" >&2
  fi
done

if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, no findings"
