#!/usr/bin/env bash
# The main job on the bundled examples: build, validate, query.
set -euo pipefail
cd "$(dirname "$0")"

scripts/setup.sh build -DCMAKE_BUILD_TYPE=RelWithDebInfo
bin=build/bin/cellforge

# Models built with the Euler operators: validated, counted, queried.
"$bin" demo
