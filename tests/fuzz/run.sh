#!/usr/bin/env bash
# Builds the interpreter fuzzer with clang (ASan + UBSan + libFuzzer) in its own build directory
# and runs it for SECONDS. Exit status 0 only when the run ended at the time limit without a
# crash, hang (-timeout), out-of-memory or sanitizer report; the input that failed is saved in
# BUILD_DIR/artifacts/ (copy it to tests/fuzz/crashes/ to keep it as a regression input).
#
#   tests/fuzz/run.sh SECONDS [BUILD_DIR]      BUILD_DIR defaults to build-fuzz/ in the repo
#   FUZZ_ARGS="-jobs=2" tests/fuzz/run.sh 600  extra libFuzzer flags (FUZZ_JOBS: build jobs,
#                                              FUZZ_CXX, FUZZ_CMAKE: the tools)
#   build-fuzz/interp_fuzzer FILE...           replays inputs (no fuzzing)
#
# The seeds of tests/fuzz/corpus/ are copied into BUILD_DIR/corpus/, which keeps what earlier runs
# found; the repository's corpus is never written. Every file of tests/fuzz/crashes/ is run
# when the fuzzer starts, so a saved reproducer fails the run until its bug is fixed.
set -euo pipefail

if [[ $# -lt 1 || ! $1 =~ ^[0-9]+$ ]]; then
  echo "usage: $0 SECONDS [BUILD_DIR]" >&2
  exit 2
fi
seconds=$1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${2:-$root/build-fuzz}
mkdir -p "$build"
build=$(cd "$build" && pwd)

cc=${FUZZ_CC:-clang}
cxx=${FUZZ_CXX:-clang++}
cmake=${FUZZ_CMAKE:-cmake}
if ! command -v "$cxx" >/dev/null; then
  echo "$0: $cxx not found (the fuzzer needs clang with libFuzzer)" >&2
  exit 2
fi

generator=()
if [[ ! -f $build/CMakeCache.txt ]] && command -v ninja >/dev/null; then
  generator=(-G Ninja)
fi
start=$SECONDS
CC=$cc CXX=$cxx "$cmake" -S "$here" -B "$build" "${generator[@]}" >/dev/null
"$cmake" --build "$build" -j"${FUZZ_JOBS:-$(nproc)}"
echo "fuzz: built in $((SECONDS - start)) s"

# Seeds: the repository's corpus (copied), then the saved reproducers (read-only, run first).
mkdir -p "$build/corpus" "$build/artifacts" "$build/regressions"
cp -R "$here/corpus/." "$build/corpus/"
rm -f "$build/regressions/"*
find "$here/crashes" -maxdepth 1 -type f ! -name 'README*' ! -name '.*' \
  -exec cp {} "$build/regressions/" \; 2>/dev/null || true
rm -f "$build/artifacts/"*

# Every sanitizer report is fatal; the stack is symbolized. Options from the environment come
# last, so they win.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1:symbolize=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:abort_on_error=1:print_stacktrace=1:symbolize=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
if [[ -z ${ASAN_SYMBOLIZER_PATH:-} ]]; then
  for s in llvm-symbolizer llvm-symbolizer-14 /usr/lib/llvm-14/bin/llvm-symbolizer; do
    if command -v "$s" >/dev/null; then
      ASAN_SYMBOLIZER_PATH=$(command -v "$s")
      export ASAN_SYMBOLIZER_PATH
      break
    fi
  done
fi

# The fuzzer's progress goes to BUILD_DIR/fuzz.log; the report is printed when the run fails.
log=$build/fuzz.log
status=0
# shellcheck disable=SC2086
"$build/interp_fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
  -dict="$here/interp.dict" -print_final_stats=1 -artifact_prefix="$build/artifacts/" ${FUZZ_ARGS:-} \
  "$build/corpus" "$build/regressions" >"$log" 2>&1 || status=$?

found=$(find "$build/artifacts" -maxdepth 1 -type f | sort)
if [[ $status -ne 0 || -n $found ]]; then
  # The report without the recommended-dictionary listing.
  grep -v '^"' "$log" | grep -v -E '^#[0-9]+[[:space:]]+(NEW|REDUCE|pulse|RELOAD)' | tail -n 150 >&2
  echo "fuzz: FAILED (exit status $status; log $log); inputs saved:" >&2
  for f in $found; do
    echo "  $f" >&2
    echo "  replay: $build/interp_fuzzer $f" >&2
  done
  exit 1
fi
# The kept corpus grows with every run (a 60 s run adds 1000-3000 inputs): past 5000 files it is
# minimized to the inputs that keep its coverage (about 3000, some 15 s).
if (($(find "$build/corpus" -maxdepth 1 -type f | wc -l) > 5000)); then
  rm -rf "$build/corpus.min"
  mkdir "$build/corpus.min"
  if "$build/interp_fuzzer" -merge=1 -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
      "$build/corpus.min" "$build/corpus" >"$build/merge.log" 2>&1; then
    rm -rf "$build/corpus"
    mv "$build/corpus.min" "$build/corpus"
    echo "fuzz: corpus minimized to $(find "$build/corpus" -maxdepth 1 -type f | wc -l) inputs"
  fi
fi
grep -E '^(Done|stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb))' "$log" || true
echo "fuzz: no crash, hang or sanitizer report in $seconds s (total $((SECONDS - start)) s)"
