#!/usr/bin/env bash
# Builds the libFuzzer targets of io/ (tests/fuzz/fuzz_read.cpp, one binary per
# format) with clang, AddressSanitizer and UndefinedBehaviorSanitizer, and runs
# each for FUZZ_SECONDS (default 30) on a copy of the seed corpus in tests/data/.
# A crash, a sanitizer report, a leak or a timeout fails the script; the input
# that caused it is kept in $FUZZ_BUILD/crashes/<format>/.
#
#   FUZZ_SECONDS=30  seconds per target      FUZZ_FORMATS="stl obj off 3mf json"
#   FUZZ_BUILD=build-fuzz                    FUZZ_CXX=clang++
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
SECONDS_EACH=${FUZZ_SECONDS:-30}
OUT=${FUZZ_BUILD:-$ROOT/build-fuzz}
CXX=${FUZZ_CXX:-clang++}
FORMATS=${FUZZ_FORMATS:-stl obj off 3mf json}
JOBS=$(nproc 2>/dev/null || echo 2)

command -v "$CXX" > /dev/null || { echo "fuzz.sh: $CXX not found (apt-get install clang)"; exit 1; }

FLAGS=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined
       -fno-sanitize-recover=undefined -I"$ROOT/include" -I"$ROOT/src")
LIBS=()
if [ -f /usr/include/lib3mf/Model/COM/NMR_DLLInterfaces.h ]; then
  FLAGS+=(-DCELLFORGE_HAVE_LIB3MF -I/usr/include/lib3mf)
  LIBS+=(-l3MF)
else
  FORMATS=${FORMATS//3mf/}
  echo "fuzz.sh: lib3mf-dev not installed; skipping the 3mf target"
fi

# The layers io/ stands on (geom, topo, build; no database code: it needs no server
# libraries).
mkdir -p "$OUT/obj"
SOURCES=$(ls "$ROOT"/src/geom/*.cpp "$ROOT"/src/topo/*.cpp "$ROOT"/src/build/*.cpp \
  "$ROOT"/src/io/*.cpp 2>/dev/null)
compile() {  # src -> obj, when the object is missing or older than a source or header
  local src=$1 obj=$OUT/obj/$(echo "${1#$ROOT/}" | tr / _).o
  if [ ! -f "$obj" ] || [ -n "$(find "$src" "$ROOT/include" "$ROOT/src" -newer "$obj" -name '*.[ch]*' -print -quit)" ]; then
    "$CXX" "${FLAGS[@]}" -fsanitize=fuzzer-no-link -c "$src" -o "$obj"
  fi
  echo "$obj"
}
export -f compile; export OUT ROOT CXX
export FLAGS_STR="${FLAGS[*]}"
OBJECTS=()
while read -r o; do OBJECTS+=("$o"); done < <(
  echo "$SOURCES" | xargs -P "$JOBS" -I{} bash -c 'FLAGS=($FLAGS_STR); compile "$@"' _ {})

status=0
for fmt in $FORMATS; do
  case $fmt in
    stl) enum=kStl ;; obj) enum=kObj ;; off) enum=kOff ;; 3mf) enum=k3mf ;; json) enum=kJson ;;
    *) echo "fuzz.sh: unknown format $fmt"; exit 2 ;;
  esac
  bin=$OUT/fuzz_$fmt
  "$CXX" "${FLAGS[@]}" -fsanitize=fuzzer -DFUZZ_FORMAT=$enum "$ROOT/tests/fuzz/fuzz_read.cpp" \
    "${OBJECTS[@]}" "${LIBS[@]}" -o "$bin"
  corpus=$OUT/corpus/$fmt
  crashes=$OUT/crashes/$fmt
  mkdir -p "$corpus" "$crashes"
  cp "$ROOT"/tests/data/*."$fmt" "$corpus"/ 2>/dev/null || true
  echo "fuzz.sh: $fmt for ${SECONDS_EACH}s on $(ls "$corpus" | wc -l) inputs"
  # lib3mf keeps some allocations for the process lifetime: no leak check there.
  leaks=1; [ "$fmt" = 3mf ] && leaks=0
  if ! ASAN_OPTIONS=detect_leaks=$leaks:abort_on_error=1 \
       "$bin" -max_total_time="$SECONDS_EACH" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
       -artifact_prefix="$crashes/" -print_final_stats=1 "$corpus" > "$OUT/fuzz_$fmt.log" 2>&1; then
    echo "fuzz.sh: $fmt FAILED; see $OUT/fuzz_$fmt.log and $crashes/"
    tail -n 30 "$OUT/fuzz_$fmt.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$OUT/fuzz_$fmt.log" | tail -n 2 | sed "s/^/  $fmt: /"
  fi
done
exit $status
