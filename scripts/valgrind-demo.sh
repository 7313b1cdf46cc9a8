#!/usr/bin/env bash
# Runs the main demo (demos/plan_arm: octo7 plans into the bookshelf, FCL re-check, 20,000 timed
# checks) under valgrind's memcheck, built in Release with debug info (RelWithDebInfo) in
# build-valgrind. Fails on any memory error (invalid read/write, use of uninitialised values,
# bad free) and on definite leaks. Suppressions, for third-party libraries only, are in
# scripts/valgrind.supp, each with a comment saying why. About 1-2 minutes on a 2-core machine.
# Environment: OCTOMOTION_VALGRIND_BUILD_DIR (default build-valgrind), OCTOMOTION_CMAKE_ARGS;
# OCTOMOTION_VALGRIND_PREBUILT=DIR runs DIR/demos/plan_arm as it is (CI: the Release build the
# test step made), without configuring or building.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${OCTOMOTION_VALGRIND_BUILD_DIR:-$root/build-valgrind}

if [[ -n ${OCTOMOTION_VALGRIND_PREBUILT:-} ]]; then
  build=$OCTOMOTION_VALGRIND_PREBUILT
else
  # shellcheck disable=SC2086
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOCTOMOTION_WERROR=ON \
    -DOCTOMOTION_BUILD_TESTS=OFF -DOCTOMOTION_BUILD_BENCH=OFF ${OCTOMOTION_CMAKE_ARGS:-} >/dev/null
  cmake --build "$build" -j "$(nproc)" --target plan_arm
fi

cd "$root"
exec valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite \
  --show-leak-kinds=definite --track-origins=yes \
  --suppressions="$root/scripts/valgrind.supp" "$build/demos/plan_arm"
