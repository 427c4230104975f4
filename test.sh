#!/usr/bin/env bash
# Builds and runs every test: the normal build in build/, a separate project built
# against its `cmake --install`, then the same tests once more under
# AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/. Among the tests, the
# holdout check (tests/holdout/) reads, diagnoses, converts to every format and back,
# saves and loads every model of tests/data/, its volumes checked against a signed
# volume computed from the files' own polygons.
# The store tests run against a real PostgreSQL server started here (and stopped at
# exit); if it cannot start, this script fails. OpenSCAD files are built by cellforge
# and by Debian's openscad and compared (scripts/openscad_compare.sh). Then each file
# parser and the OpenSCAD language are fuzzed for FUZZ_SECONDS (default 20) seconds.
# Each stage's end is printed with the minutes since the start ("test.sh: ... at
# 12.3 min"), for CI's 40-minute budget. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")"
stage() { echo "test.sh: $1 at $(awk -v s="$SECONDS" 'BEGIN { printf "%.1f", s / 60 }') min"; }

# As run.sh builds it: -O2, no debug information (a quarter of the compile time).
scripts/setup.sh build -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
stage "set-up and build"

eval "$(scripts/pg_test_server.sh start)"  # exports CELLFORGE_PG_URL, CELLFORGE_PG_DIR
trap 'scripts/pg_test_server.sh stop' EXIT
export CI="${CI:-1}"  # without the server URL the PostgreSQL tests fail, never skip

# The tests' heaps on huge pages where the kernel gives them on request (geom/memory.h):
# the Boolean tests take a quarter less time so on a virtual machine.
(cd build && GLIBC_TUNABLES="${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1" \
   ctest --output-on-failure -j"$(nproc)")
stage "tests"

# Agreement with OpenSCAD itself: the corpus built by both and compared (about a
# minute); with CELLFORGE_COMPARE_ALL=1 also the openscad package's examples and MCAD
# (several minutes). docs/compatibility.md lists the known differences; a new one fails.
if [ "${CELLFORGE_COMPARE_ALL:-0}" = 1 ]; then
  COMPARE_TIMEOUT=${COMPARE_TIMEOUT:-30} scripts/openscad_compare.sh --all build
else
  scripts/openscad_compare.sh build
fi
# Then every file of the --all set (cellforge's examples, the openscad package's and
# MCAD) built by cellforge alone and checked against what openscad gave for it, kept
# in tests/openscad_recorded/ (`scripts/openscad_compare.sh --all --record
# tests/openscad_recorded build` records them again): seconds, where running openscad
# on them takes many minutes. A file that stopped building (example021.scad did for a
# day) fails here.
scripts/openscad_compare.sh --all --recorded tests/openscad_recorded build
stage "OpenSCAD comparisons"

# The installed library as another project sees it: find_package(cellforge) and
# <cellforge/cellforge.h> (tests/consumer/).
scripts/consumer_test.sh build
stage "consumer project"

# Built with clang, which compiles this Debug tree in about half of GCC's time, and
# with the fuzzers in it (scripts/fuzz.sh below): the library is compiled here once
# for both.
scripts/setup.sh build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++ \
  -DCELLFORGE_SANITIZE=ON -DCELLFORGE_BENCH=OFF
stage "ASan + UBSan build"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   LSAN_OPTIONS=suppressions=$PWD/../tests/lsan.supp ctest --output-on-failure -j"$(nproc)")
stage "ASan + UBSan tests"

# Every file parser under libFuzzer (clang, ASan + UBSan) for a bounded time each,
# built in build-asan.
FUZZ_BUILD=$PWD/build-asan FUZZ_SECONDS=${FUZZ_SECONDS:-20} scripts/fuzz.sh
stage "fuzzers"

echo "test.sh: all tests passed"
