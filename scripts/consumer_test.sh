#!/usr/bin/env bash
# Installs a build of cellforge into a fresh prefix (cmake --install), then builds and
# runs tests/consumer/, a separate project that finds it with find_package(cellforge)
# and includes only <cellforge/cellforge.h>. Fails when any step does.
#   scripts/consumer_test.sh [BUILD_DIR]     (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
prefix=$build/consumer-install
out=$build/consumer
rm -rf "$prefix" "$out"
cmake --install "$build" --prefix "$prefix" > /dev/null
generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
cmake -S tests/consumer -B "$out" "${generator[@]}" -DCMAKE_PREFIX_PATH="$PWD/$prefix" > /dev/null
cmake --build "$out" -j "$(nproc 2>/dev/null || echo 2)"
"$out/consumer"
