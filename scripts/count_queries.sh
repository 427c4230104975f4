#!/usr/bin/env bash
# Instructions per query of the 9 adjacency queries, cellforge against the radial
# edge structure, counted by valgrind's callgrind (deterministic: the same counts
# on every run and machine load). Prints a markdown table.
#   scripts/count_queries.sh [BUILD_DIR] [MODELS...]
# BUILD_DIR defaults to build-cmp (a Release build, docs/structure-comparison.md);
# MODELS to cube cube_with_hole sphere64 two_cubes_edge book. The counts include
# the calling loop of bench/count_structures.cpp (the same for both structures).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-cmp}
shift || true
models=("$@")
[ ${#models[@]} -gt 0 ] || models=(cube cube_with_hole sphere64 two_cubes_edge book)
bin=$build/bin/count_structures
[ -x "$bin" ] || { echo "count_queries.sh: $bin not built (cmake --build $build --target count_structures)" >&2; exit 1; }
command -v valgrind > /dev/null || { echo "count_queries.sh: valgrind not found (apt-get install valgrind)" >&2; exit 1; }
names=("V→V" "V→E" "V→F" "E→V" "E→E" "E→F" "F→V" "F→E" "F→F")

count() {  # model structure query -> "instructions queries"
  local log
  log=$(mktemp)
  local said
  said=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
           --toggle-collect='*measured_queries*' "$bin" "$1" "$2" "$3" 2>"$log")
  local ir
  ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$log")
  rm -f "$log"
  echo "$ir $(echo "$said" | awk '{print $2}')"
}

echo "| model | query | cellforge | radial edge | cellforge ÷ radial edge |"
echo "|---|---|---:|---:|---:|"
for model in "${models[@]}"; do
  for q in 0 1 2 3 4 5 6 7 8; do
    read -r ic nq < <(count "$model" cellforge "$q")
    read -r ir _ < <(count "$model" radial_edge "$q")
    awk -v m="$model" -v n="${names[$q]}" -v ic="$ic" -v ir="$ir" -v nq="$nq" \
      'BEGIN { printf "| %s | %s | %.1f | %.1f | %.2f |\n", m, n, ic / nq, ir / nq, ic / ir }'
  done
done
