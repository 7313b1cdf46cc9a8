#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine: installs the Debian packages octomotion needs
# (those missing only), configures a Release build with warnings as errors, builds, then
#   demo  runs the main demo planning problem (demos/plan_arm: octo7 reaches into a bookshelf),
#   test  runs the whole test suite through ctest.
# Environment: OCTOMOTION_BUILD_DIR (default build), OCTOMOTION_CMAKE_ARGS (extra cmake args),
#              OCTOMOTION_CTEST_ARGS (extra ctest args, e.g. "-L motion").
set -euo pipefail

mode=${1:-}
if [[ $mode != demo && $mode != test ]]; then
  echo "usage: $0 demo|test" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=${OCTOMOTION_BUILD_DIR:-$root/build}

packages=(build-essential cmake ninja-build pkg-config clang-format
  libeigen3-dev libompl-dev libfcl-dev liburdfdom-dev libtinyxml-dev libassimp-dev liboctomap-dev
  libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  libyaml-cpp-dev libnanoflann-dev libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox python3
  pybind11-dev python3-pybind11 python3-numpy python3-matplotlib)
# The test suite also drives the web viewer (viewer/) in headless Chromium through Node.js.
if [[ $mode == test ]]; then
  packages+=(chromium)
  command -v npm >/dev/null || packages+=(nodejs npm)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "octomotion: installing ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

# The viewer's three.js and playwright-core, pinned by viewer/package-lock.json.
if [[ $mode == test && ! -d $root/viewer/node_modules ]]; then
  npm ci --prefix "$root/viewer" --no-audit --no-fund
fi

# The Python module is built for Debian's interpreter (python3-numpy's), not another python3
# earlier on the PATH.
python_args=()
[[ -x /usr/bin/python3 ]] && python_args=(-DPython3_EXECUTABLE=/usr/bin/python3)
# shellcheck disable=SC2086
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DOCTOMOTION_WERROR=ON \
  "${python_args[@]}" ${OCTOMOTION_CMAKE_ARGS:-}
cmake --build "$build" -j "$(nproc)"

if [[ $mode == demo ]]; then
  cd "$root" && exec "$build/demos/plan_arm"
else
  # shellcheck disable=SC2086
  cd "$build" && exec ctest --output-on-failure -j "$(nproc)" ${OCTOMOTION_CTEST_ARGS:-}
fi
