#!/usr/bin/env bash
# Builds and runs every test: the normal build in build/, then the same tests once
# more under AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/.
# Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")"

scripts/setup.sh build -DCMAKE_BUILD_TYPE=RelWithDebInfo
(cd build && ctest --output-on-failure -j2)

scripts/setup.sh build-asan -DCMAKE_BUILD_TYPE=Debug -DCELLFORGE_SANITIZE=ON -DCELLFORGE_BENCH=OFF
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j2)

echo "test.sh: all tests passed"
