#!/usr/bin/env bash
# The sanitizer and fuzzing stage of the test suite (docs/testing.md), run by `./sward.sh test` after ctest.
#
# One extra build (clang, ASan + UBSan, libraries instrumented for libFuzzer) serves both halves:
#   1. the Vulkan-free CPU suites and a GPU smoke subset on lavapipe with validation on, under ASan/UBSan/LSan;
#   2. every fuzz target for FUZZ_SECONDS (default 10) from its seed corpus and saved regressions, two at a time.
# Any sanitizer report, crash, leak, timeout or test failure fails the script. Nothing is skipped: a missing clang
# or libFuzzer is an error (tools/setup-deps.sh installs them).
#
# Environment: SANITIZE_BUILD_DIR (default build-sanitize), FUZZ_SECONDS (per target), FUZZ_RUNS (executions per
# target instead of a time: the long run of docs/testing.md), FUZZ_TARGETS (names, default all), JOBS (parallel
# build jobs and fuzz targets at a time, default nproc).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${SANITIZE_BUILD_DIR:-build-sanitize}
fuzz_seconds=${FUZZ_SECONDS:-10}
fuzz_budget=(-max_total_time="$fuzz_seconds")
[ -n "${FUZZ_RUNS:-}" ] && fuzz_budget=(-runs="$FUZZ_RUNS")
jobs=${JOBS:-$(nproc)}
all_targets="scene grass_map atlas gltf glb state_file pfm kitti_png flow exr calib raster"
targets=${FUZZ_TARGETS:-$all_targets}
# Longest first under the sanitizers (the order they start in); scene runs as two shards (below).
cpu_suites="scene vegetation common eval interaction range io world dataset export"
# A GPU smoke subset: engine basics, the validation self-test, one renderer of each kind (ruts: in sward-render and
# in a Session), the GPU simulation, a range-sensor dataset (sward-render with a LiDAR, the ruts, the GPU state) and a
# dataset with motion ground truth (the flow truth pass, the kept plant states, the flow files).
gpu_filter="RangeAllocator.*:Validation.*:GpuTest.ComputeRoundTrip*:GpuTest.BuffersAreSubAllocated*"
gpu_filter+=":GpuTest.ExpansionMatchesTheCpuReference:GpuTest.RecoveryMatchesTheCpuReference"
gpu_filter+=":ObjectRenderTest.RoverIsDrawnWithExactDepthAndItsLabel:RenderTest.TwoRendersAreBitwiseIdentical"
gpu_filter+=":GpuTest.WheelsPressRuts*:GpuTest.RutsAreTheSameBits*:RangeSensorDatasets.LidarPoints*"
gpu_filter+=":FlowTruth.StillSceneFlowIsTheDepthReprojectedWithBothPoses"

fail() { echo "sanitize-and-fuzz: $*" >&2; exit 1; }
seconds_since() { echo $(( $(date +%s) - $1 )); }

# --- toolchain: clang with the ASan, UBSan and libFuzzer runtimes ---------------------------------------------
command -v clang++ >/dev/null && command -v clang >/dev/null || fail "clang is not installed (run tools/setup-deps.sh)"
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' > "$probe/probe.cpp"
clang++ -fsanitize=fuzzer,address,undefined "$probe/probe.cpp" -o "$probe/probe" 2> "$probe/log" \
  || { cat "$probe/log" >&2; fail "clang cannot link libFuzzer + ASan + UBSan (libclang-rt-14-dev missing? run tools/setup-deps.sh)"; }
command -v llvm-symbolizer >/dev/null || fail "llvm-symbolizer is missing: sanitizer reports would have no source lines (package llvm)"

# --- build -----------------------------------------------------------------------------------------------------
start=$(date +%s)
launcher=()
if command -v ccache >/dev/null; then # as sward.sh: paths hashed relative to the checkout, so other checkouts hit
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1 CCACHE_SLOPPINESS=pch_defines,time_macros
fi
# -O1 keeps ASan fast enough for lavapipe-driven tests; Debug keeps assertions on; line tables give reports lines.
# Warnings are errors in the GCC build (sward.sh); clang's own extra warnings are not made fatal here.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -gline-tables-only" "-DCMAKE_C_FLAGS_DEBUG=-O1 -gline-tables-only" \
  -DSWARD_SANITIZE=ON -DSWARD_FUZZ=ON -DSWARD_WERROR=OFF "${launcher[@]}" > "$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; fail "configuring $build failed"; }
build_targets=(sward_fuzz_all sward_gpu_smoke_tests sward-render)
for suite in $cpu_suites; do build_targets+=("sward_${suite}_tests"); done
cmake --build "$build" -j "$jobs" --target "${build_targets[@]}" || fail "building $build failed"
echo "sanitize-and-fuzz: build took $(seconds_since "$start") s"

# --- sanitizer runs --------------------------------------------------------------------------------------------
# LSan: only the Vulkan driver stack's own leaks are suppressed (tests/sanitize/lsan.supp says why, per library).
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$root/tests/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export SWARD_VALIDATION=1 OPENCV_IO_ENABLE_OPENEXR=1
start=$(date +%s)
# The driver stack stays loaded to exit so that its leaks can be attributed to it (tests/sanitize/keep_loaded.c).
clang -shared -fPIC -O1 tests/sanitize/keep_loaded.c -o "$build/libkeep_loaded.so" || fail "cannot build keep_loaded.so"
# One suite: its binary under the sanitizers, its log in the build folder; prints one line and returns non-zero on
# failure. GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS in the environment run a share of the suite (gtest's sharding).
sanitize_one() {
  local name=$1 log="$build/sanitize-${1/\//-}.log"
  shift
  if "$@" --gtest_brief=1 > "$log" 2>&1; then
    echo "sanitize-and-fuzz: $name passed ($(grep -o '[0-9]* tests\? from [0-9]* test suites\? ran' "$log"))"
  else
    tail -n 60 "$log"
    echo "sanitize-and-fuzz: $name FAILED under ASan/UBSan ($log)"
    return 1
  fi
}
# The suites are independent processes, run $jobs at a time, longest first, each started as soon as any slot frees
# (wait -n): the GPU smoke subset (about 130 s) and the scene suite (about 200 s: its streamed-world tests) set the
# length, so the scene suite runs as two gtest shards. A fixed order waiting on the oldest left a slot idle for
# minutes: 456 s for these runs against 266-289 s now.
suites=(gpu)
for suite in $cpu_suites; do
  if [ "$suite" = scene ]; then suites+=(scene/0 scene/1); else suites+=("$suite"); fi
done
declare -A running=()
failed=()
wait_any() {
  local pid
  wait -n -p pid "${!running[@]}" || failed+=("${running[$pid]}")
  unset "running[$pid]"
}
for suite in "${suites[@]}"; do
  [ ${#running[@]} -ge "$jobs" ] && wait_any
  case $suite in
    gpu) LD_PRELOAD="$root/$build/libkeep_loaded.so" sanitize_one gpu "$build/bin/sward_gpu_smoke_tests" \
           --gtest_filter="$gpu_filter" & ;;
    */*) GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=${suite#*/} \
           sanitize_one "$suite" "$build/bin/sward_${suite%/*}_tests" & ;;
    *) sanitize_one "$suite" "$build/bin/sward_${suite}_tests" & ;;
  esac
  running[$!]=$suite
done
while [ ${#running[@]} -gt 0 ]; do wait_any; done
[ ${#failed[@]} -eq 0 ] || fail "suites that failed under ASan/UBSan: ${failed[*]}"
render_out="$build/sanitize-render"
rm -rf "$render_out"
LD_PRELOAD="$root/$build/libkeep_loaded.so" "$build/bin/sward-render" examples/meadow.json --resolution 160x120 --samples 1 --out "$render_out" \
  > "$build/sanitize-render.log" 2>&1 \
  || { tail -n 60 "$build/sanitize-render.log"; fail "sward-render failed under ASan/UBSan ($build/sanitize-render.log)"; }
echo "sanitize-and-fuzz: sward-render meadow.json passed; sanitizer tests took $(seconds_since "$start") s"

# --- fuzzing ---------------------------------------------------------------------------------------------------
# New inputs go to a work corpus in the build folder (the committed seeds stay as they are); saved regressions are
# replayed first. Crashes, leaks, timeouts (> 10 s per input) and out-of-memory (> 2 GiB) all fail.
start=$(date +%s)
work="$build/fuzz-run"
rm -rf "$work"
mkdir -p "$work"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1"
fuzz_one() {
  local name=$1 dict=()
  case $name in
    scene|atlas) dict=(-dict="$root/fuzz/dict/json.dict") ;;
    gltf|glb) dict=(-dict="$root/fuzz/dict/gltf.dict") ;;
    exr|grass_map|kitti_png) dict=(-dict="$root/fuzz/dict/exr.dict") ;;
    calib|pfm) dict=(-dict="$root/fuzz/dict/calib.dict") ;;
  esac
  mkdir -p "$work/$name/corpus" "$work/$name/artifacts" "$root/fuzz/regressions/$name"
  # TMPDIR: fuzz_input.cpp writes each input to a file there; memory-backed keeps the fuzzer fast.
  if TMPDIR=/dev/shm "$build/bin/fuzz_$name" "${fuzz_budget[@]}" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 "${dict[@]}" -artifact_prefix="$work/$name/artifacts/" \
      "$work/$name/corpus" "$root/fuzz/corpus/$name" "$root/fuzz/regressions/$name" > "$work/$name.log" 2>&1; then
    echo "sanitize-and-fuzz: fuzz_$name: $(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/$name.log" | grep -o '[0-9]*$') executions in $(seconds_since "$2") s, 0 crashes"
  else
    tail -n 60 "$work/$name.log"
    echo "sanitize-and-fuzz: fuzz_$name FAILED; reproducer: $(ls "$work/$name/artifacts/"* 2>/dev/null | head -n 1)" \
         "(save it in fuzz/regressions/$name/)"
    return 1
  fi
}
pids=() names=() failed=()
for name in $targets; do
  [ -x "$build/bin/fuzz_$name" ] || fail "fuzz target fuzz_$name was not built"
  if [ ${#pids[@]} -ge "$jobs" ]; then
    wait "${pids[0]}" || failed+=("${names[0]}")
    pids=("${pids[@]:1}") names=("${names[@]:1}")
  fi
  fuzz_one "$name" "$(date +%s)" & pids+=($!) names+=("$name")
done
for i in "${!pids[@]}"; do wait "${pids[$i]}" || failed+=("${names[$i]}"); done
echo "sanitize-and-fuzz: fuzzing took $(seconds_since "$start") s"
[ ${#failed[@]} -eq 0 ] || fail "fuzz targets with findings: ${failed[*]}"
echo "sanitize-and-fuzz: all passed"
