#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/fuzz_read.cpp, one binary per file format
# of io/; tests/fuzz/fuzz_scad.cpp for the OpenSCAD language of csg/) with clang,
# AddressSanitizer and UndefinedBehaviorSanitizer, and runs each for FUZZ_SECONDS
# (default 30) on a copy of its seed corpus (tests/data/*.FORMAT; tests/scad/ for scad;
# and tests/fuzz/found/*.FORMAT, the inputs that made a fuzzer fail once, so that every
# run tries them first).
# A crash, a sanitizer report, a leak or a timeout fails the script; the input
# that caused it is kept in $FUZZ_BUILD/crashes/<format>/.
#
#   FUZZ_SECONDS=30  seconds per target      FUZZ_FORMATS="stl obj off 3mf json scad"
#   FUZZ_BUILD=build-fuzz                    FUZZ_CXX=clang++
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
SECONDS_EACH=${FUZZ_SECONDS:-30}
OUT=${FUZZ_BUILD:-$ROOT/build-fuzz}
CXX=${FUZZ_CXX:-clang++}
FORMATS=${FUZZ_FORMATS:-stl obj off 3mf json scad}
JOBS=$(nproc 2>/dev/null || echo 2)

command -v "$CXX" > /dev/null || { echo "fuzz.sh: $CXX not found (apt-get install clang)"; exit 1; }

# The fuzzers link the io layer target (and so the layers io/ stands on: geom, topo,
# shape) or the csg layer (and boolean below it); no database code, which needs
# server libraries. Built with clang, -O1 and the sanitizers by the CELLFORGE_FUZZ
# configuration of CMakeLists.txt, which builds those layers only. A clang sanitizer
# tree (-DCELLFORGE_SANITIZE=ON, as test.sh's build-asan) has the fuzzers too:
# FUZZ_BUILD=build-asan uses it as it is configured (at -O0 there, so a fuzzer runs
# fewer inputs a second than in its own -O1 tree).
generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
if [ -f "$OUT/CMakeCache.txt" ] && grep -q "CELLFORGE_SANITIZE:BOOL=ON" "$OUT/CMakeCache.txt"; then
  grep -q "CMAKE_CXX_COMPILER:.*clang" "$OUT/CMakeCache.txt" ||
    { echo "fuzz.sh: $OUT is a sanitizer tree built with another compiler than clang: no fuzzers"; exit 2; }
elif [ ! -f "$OUT/CMakeCache.txt" ] || ! grep -q "CELLFORGE_FUZZ:BOOL=ON" "$OUT/CMakeCache.txt"; then
  cmake -S "$ROOT" -B "$OUT" "${generator[@]}" -DCMAKE_CXX_COMPILER="$CXX" \
    -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_CXX_FLAGS_FUZZ="-O1 -g" -DCELLFORGE_FUZZ=ON > /dev/null
fi
targets=()
for fmt in $FORMATS; do
  case $fmt in
    stl | obj | off | 3mf | json | scad) targets+=("fuzz_$fmt") ;;
    *) echo "fuzz.sh: unknown format $fmt"; exit 2 ;;
  esac
done
cmake --build "$OUT" -j "$JOBS" --target "${targets[@]}"

# One fuzzer per core at a time (each is one process); reports in the order of FORMATS.
run_one() {
  local fmt=$1 bin=$OUT/bin/fuzz_$1 corpus=$OUT/corpus/$1 crashes=$OUT/crashes/$1 rc=0
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
    "$bin" -max_total_time="$SECONDS_EACH" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$crashes/" -print_final_stats=1 "$corpus" > "$OUT/fuzz_$fmt.log" 2>&1 || rc=$?
  echo $rc > "$OUT/fuzz_$fmt.rc"
}
running=0
for fmt in $FORMATS; do
  corpus=$OUT/corpus/$fmt
  mkdir -p "$corpus" "$OUT/crashes/$fmt"
  rm -f "$OUT/fuzz_$fmt.rc"
  cp "$ROOT"/tests/data/*."$fmt" "$corpus"/ 2>/dev/null || true
  cp "$ROOT"/tests/fuzz/found/*."$fmt" "$corpus"/ 2>/dev/null || true
  [ "$fmt" = scad ] && cp "$ROOT"/tests/scad/*.scad "$ROOT"/tests/scad/lib/*.scad "$corpus"/
  echo "fuzz.sh: $fmt for ${SECONDS_EACH}s on $(ls "$corpus" | wc -l) inputs"
  run_one "$fmt" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true

status=0
for fmt in $FORMATS; do
  if [ "$(cat "$OUT/fuzz_$fmt.rc" 2>/dev/null || echo missing)" != 0 ]; then
    echo "fuzz.sh: $fmt FAILED; see $OUT/fuzz_$fmt.log and $OUT/crashes/$fmt/"
    tail -n 30 "$OUT/fuzz_$fmt.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$OUT/fuzz_$fmt.log" | tail -n 2 | sed "s/^/  $fmt: /"
  fi
done
exit $status
