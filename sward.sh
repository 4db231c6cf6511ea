#!/usr/bin/env bash
# One entry point for a new user:
#   ./sward.sh render [ARGS]  set up, build, render examples/meadow.json into out/ (ARGS go to sward-render)
#   ./sward.sh test           set up, build, run the whole test suite
#   ./sward.sh build          set up and build only
# BUILD_TYPE=Debug|Release (default Release), SANITIZE=1 (ASan + UBSan), BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")"

command=${1:-render}
[ $# -gt 0 ] && shift

build_type=${BUILD_TYPE:-Release}
build_dir=${BUILD_DIR:-build}
sanitize=OFF
[ "${SANITIZE:-0}" = "1" ] && sanitize=ON

tools/setup-deps.sh
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" -DSWARD_SANITIZE="$sanitize" > "$build_dir.configure.log" 2>&1 \
  || { cat "$build_dir.configure.log"; exit 1; }
cmake --build "$build_dir" -j "$(nproc)"

case "$command" in
  build) ;;
  render)
    "$build_dir/bin/sward-render" examples/meadow.json --out out "$@"
    ;;
  test)
    ctest --test-dir "$build_dir" -j "$(nproc)" --output-on-failure --timeout 600 "$@"
    tools/sanitize-and-fuzz.sh # ASan + UBSan suites, GPU smoke on lavapipe, every fuzz target (docs/testing.md)
    ;;
  *)
    echo "usage: ./sward.sh render|test|build [ARGS]" >&2
    exit 2
    ;;
esac
