#!/usr/bin/env bash
# Builds the libFuzzer harnesses of Testing/Fuzz with clang (ASan + UBSan) in build-fuzz/ and
# runs each for a bounded time from its seed corpus (Testing/Fuzz/corpus/<harness>, kept in the
# repo; the inputs found during the run go to build-fuzz/corpus/<harness>: merge the useful ones
# into the repo's corpus by hand). Usage: bash scripts/fuzz.sh [seconds per harness]
# Exit status: 0 clean, 77 when clang is missing (CTest: skipped), other: a crash was found
# (the reproducer is left in build-fuzz/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-20}"
build="$root/build-fuzz"
if ! command -v clang++ >/dev/null 2>&1; then
  echo "clang++ not found: fuzzing skipped"
  exit 77
fi
cmake -S "$root/Testing/Fuzz" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2 >/dev/null
status=0
for harness in FuzzMeshGeodesics FuzzSilhouetteTables; do
  seeds="$root/Testing/Fuzz/corpus/$harness"
  corpus="$build/corpus/$harness"
  mkdir -p "$corpus"
  echo "== $harness: ${seconds} s, $(ls "$seeds" | wc -l) seed inputs"
  (cd "$build" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "./$harness" -max_total_time="$seconds" -max_len=512 -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 "$corpus" "$seeds") 2>&1 | grep -E "^(#[0-9]+ *DONE|stat::number_of_executed_units|==|SUMMARY|ERROR|artifact)" || true
  if ls "$build"/crash-* "$build"/leak-* "$build"/timeout-* >/dev/null 2>&1; then
    echo "$harness: failure, reproducer(s): $(ls "$build"/crash-* "$build"/leak-* "$build"/timeout-* 2>/dev/null)"
    status=1
  fi
done
exit $status
