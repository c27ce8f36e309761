#!/usr/bin/env bash
# The one test command: installs what is missing, builds, runs every test.
#   1. release build: unit, element and pipeline tests (meson test)
#   2. AddressSanitizer + UBSan build: unit and element tests
#   3. clang libFuzzer build: every parser fuzzed for a bounded time
# Environment: GESTURECAM_FUZZ_RUNS / _SECONDS / _SEED (see below), GESTURECAM_SKIP_ASAN=1,
# GESTURECAM_SKIP_FUZZ=1 to skip a stage locally.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
. tests/deps.sh
gesturecam_install_deps

jobs=$(nproc)
passed=0
failed=0
failures=()

# Adds one stage's counts from meson's test log.
count_meson() { count_meson_log "$1/meson-logs/testlog.json" "$2"; }
count_meson_log() {
  local log=$1 stage=$2
  [ -f "$log" ] || { failed=$((failed + 1)); failures+=("$stage: no test log"); return; }
  local p f
  p=$(python3 -c 'import json,sys; r=[json.loads(l) for l in open(sys.argv[1])]; print(sum(x["result"] in ("OK","EXPECTEDFAIL") for x in r))' "$log")
  f=$(python3 -c 'import json,sys; r=[json.loads(l) for l in open(sys.argv[1])]; print(sum(x["result"] in ("FAIL","TIMEOUT","ERROR","UNEXPECTEDPASS") for x in r))' "$log")
  passed=$((passed + p))
  failed=$((failed + f))
  [ "$f" -eq 0 ] || failures+=("$stage: $f failed")
}

echo "== release build =="
gesturecam_setup build -Dbuildtype=release
meson compile -C build -j "$jobs"
meson test -C build --print-errorlogs --num-processes "$jobs" || true
count_meson build release

if [ "${GESTURECAM_SKIP_ASAN:-0}" != 1 ]; then
  echo "== AddressSanitizer + UBSan build =="
  gesturecam_setup build-asan -Dbuildtype=debugoptimized -Db_sanitize=address,undefined -Db_lundef=false
  meson compile -C build-asan -j "$jobs"
  # Plain C++ tests: LeakSanitizer on; the tools they start read video through GStreamer,
  # whose one-time GLib allocations tests/lsan-glib.supp leaves out. Element tests: GLib keeps
  # one-time type and plugin registrations alive on purpose, so leaks there are judged by
  # GStreamer's own leaks tracer (a leaked buffer, caps or element fails the test) instead of LSan.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS="suppressions=$PWD/tests/lsan-glib.supp" \
    meson test -C build-asan --suite unit --print-errorlogs --num-processes "$jobs" \
      --timeout-multiplier 4 --logbase unit || true
  count_meson_log build-asan/meson-logs/unit.json asan-unit
  if [ -d build-asan/gst-plugin ]; then
    # Programs the tests start (gst-plugin-scanner, gst-inspect-1.0) load the instrumented
    # plugin too: they need the sanitizer runtimes preloaded. A registry cached by an earlier
    # run may list the plugin as broken, so each run scans afresh.
    rm -f build-asan/tests/gst/registry-*.bin
    asan_runtime="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)"
    LD_PRELOAD="$asan_runtime" GST_REGISTRY_FORK=no \
    ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      GST_TRACERS=leaks GST_LEAKS_TRACER_STACK_TRACE=0 \
      meson test -C build-asan --suite gst --print-errorlogs --num-processes "$jobs" \
        --timeout-multiplier 4 --logbase gst || true
    count_meson_log build-asan/meson-logs/gst.json asan-gst
  fi
fi

if [ "${GESTURECAM_SKIP_FUZZ:-0}" != 1 ]; then
  echo "== libFuzzer build =="
  CC=clang CXX=clang++ gesturecam_setup build-fuzz -Dbuildtype=debugoptimized -Dfuzz=true \
    -Dplugin=false -Dtests=enabled -Db_lundef=false
  meson compile -C build-fuzz -j "$jobs"
  # A fixed seed and run count make the stage reproducible: CI runs exactly the inputs that
  # were run before the change was submitted. The time cap only bounds a slow machine.
  # Longer exploration: GESTURECAM_FUZZ_RUNS=-1 GESTURECAM_FUZZ_SECONDS=600 GESTURECAM_FUZZ_SEED=0.
  seconds=${GESTURECAM_FUZZ_SECONDS:-90}
  runs=${GESTURECAM_FUZZ_RUNS:-100000}
  seed=${GESTURECAM_FUZZ_SEED:-1}
  for target in build-fuzz/tests/fuzz/fuzz_*; do
    [ -f "$target" ] && [ -x "$target" ] || continue
    name=$(basename "$target")
    corpus="tests/fuzz/corpus/${name#fuzz_}"
    work=$(mktemp -d)
    [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/
    echo "-- $name: $runs runs, seed $seed, at most ${seconds}s"
    if timeout --kill-after=10 $((seconds + 120)) "$target" -seed="$seed" -runs="$runs" \
        -max_total_time="$seconds" -timeout=20 -max_len=4096 -print_final_stats=1 \
        -artifact_prefix="build-fuzz/$name-" "$work" \
        > "build-fuzz/$name.log" 2>&1; then
      passed=$((passed + 1))
    else
      failed=$((failed + 1))
      failures+=("fuzz: $name (see build-fuzz/$name.log)")
      tail -40 "build-fuzz/$name.log"
    fi
    rm -rf "$work"
  done
fi

echo
for f in "${failures[@]+"${failures[@]}"}"; do echo "FAILED: $f"; done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
