#!/usr/bin/env bash
# One entry point for a new user; see usage() below. Exit status: 0 success, 1 failure, 2 usage error (as every
# sward tool, tools/tool_main.h).
set -euo pipefail
cd "$(dirname "$0")"

usage() {
  cat <<'USAGE'
usage: ./sward.sh [render|test|build|package|help] [ARGS]
  render [ARGS]  set up, build, then run sward-render ARGS; the scene defaults to examples/meadow.json and --out
                 to out/ when ARGS name none (e.g. ./sward.sh render my.json --out my-data --frames 0:10)
  test [ARGS]    set up, build, run the whole test suite (ARGS go to ctest)
  build          set up and build only
  package [--lean]  set up, build, then write the relocatable release archive
                 BUILD_DIR/package/sward-<version>-linux-x86_64.tar.gz (docs/release.md; check it with
                 tools/release-check.sh ARCHIVE); --lean leaves out GDAL, Embree and OpenCV (SWARD_WITH_GDAL,
                 SWARD_WITH_EMBREE, SWARD_WITH_OPENCV OFF: no GeoTIFF rasters, range sensors or sward-eval) and
                 builds in build-lean unless BUILD_DIR is set
  help           this text (also -h, --help); sets up and builds nothing
Environment: BUILD_TYPE=Debug|Release (default Release), SANITIZE=1 (ASan + UBSan), BUILD_DIR (default build).
USAGE
}

command=${1:-render}
[ $# -gt 0 ] && shift

# Answer the cheap questions before the setup and the build (minutes on a fresh machine).
case "$command" in
  help|-h|--help) usage; exit 0 ;;
  render|test|build|package) ;;
  *) echo "sward.sh: error: unknown command '$command' (see ./sward.sh --help)" >&2; exit 2 ;;
esac
# package's one option, the lean build (docs/release.md, "A lean build"): the optional components OFF.
with_optional=ON
if [ "$command" = package ]; then
  case "${1:-}" in
    --lean) with_optional=OFF; shift ;;
  esac
  if [ $# -gt 0 ]; then
    echo "sward.sh: error: package takes only --lean, not '$1' (see ./sward.sh --help)" >&2; exit 2
  fi
fi

# sward-render's arguments: the user's, plus the default scene and --out only where the user gave none. Options
# that take no value are listed; every other option is taken to be followed by its value (unless --opt=value).
render_args() {
  local has_scene=0 has_out=0 expect_value=0 arg
  for arg in "$@"; do
    if [ $expect_value = 1 ]; then expect_value=0; continue; fi
    case "$arg" in
      --out|-o|--out=*|-o=*) has_out=1; [[ "$arg" == *=* ]] || expect_value=1 ;;
      -q|--quiet|--no-vegetation|--validation|-h|--help|--version|--*=*) ;;
      -*) expect_value=1 ;;
      *) has_scene=1 ;;
    esac
  done
  [ $has_scene = 1 ] || printf '%s\0' examples/meadow.json
  [ $has_out = 1 ] || printf '%s\0' --out out
  [ $# = 0 ] || printf '%s\0' "$@"
}

build_type=${BUILD_TYPE:-Release}
build_dir=${BUILD_DIR:-build}
[ $with_optional = OFF ] && build_dir=${BUILD_DIR:-build-lean}
sanitize=OFF
[ "${SANITIZE:-0}" = "1" ] && sanitize=ON

tools/setup-deps.sh
# ccache (installed by setup-deps): a build of sources compiled before, in this checkout or another one (a CI clone),
# takes the objects from the cache. Paths are hashed relative to the checkout (CCACHE_BASEDIR), so a checkout in
# another folder hits too; the cache only ever returns what the compiler would have made of the same input.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # The test suites build with a precompiled header, which ccache caches only with this sloppiness.
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1 CCACHE_SLOPPINESS=pch_defines,time_macros
fi
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" -DSWARD_SANITIZE="$sanitize" \
  -DSWARD_WITH_GDAL=$with_optional -DSWARD_WITH_EMBREE=$with_optional -DSWARD_WITH_OPENCV=$with_optional \
  "${launcher[@]}" > "$build_dir.configure.log" 2>&1 \
  || { cat "$build_dir.configure.log"; exit 1; }
cmake --build "$build_dir" -j "$(nproc)"

case "$command" in
  build) ;;
  package)
    # CPack in the build folder (cmake/Package.cmake): the Runtime component, the Python module and the shared
    # libraries they load (cmake/BundleRuntime.cmake).
    (cd "$build_dir" && cpack)
    ls -l "$build_dir"/package/sward-*-linux-*.tar.gz
    ;;
  render)
    mapfile -d '' args < <(render_args "$@")
    exec "$build_dir/bin/sward-render" "${args[@]}"
    ;;
  test)
    ctest --test-dir "$build_dir" -j "$(nproc)" --output-on-failure --timeout 600 "$@"
    tools/sanitize-and-fuzz.sh # ASan + UBSan suites, GPU smoke on lavapipe, every fuzz target (docs/testing.md)
    ;;
esac
