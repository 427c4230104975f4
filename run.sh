#!/usr/bin/env bash
# The main job on the bundled examples: build, validate, query, store.
set -euo pipefail
cd "$(dirname "$0")"

scripts/setup.sh build -DCMAKE_BUILD_TYPE=RelWithDebInfo
bin=build/bin/cellforge
db=build/cellforge.db

# Models built with the Euler operators: validated, counted, queried.
"$bin" demo

# Stored in the SQLite model database (a new version on every run).
for example in box box_with_hole nonmanifold; do
  "$bin" db save "example:$example" --name "$example" --db "$db"
done
"$bin" db list --db "$db"
"$bin" db sql "SELECT face, edge, direction, point, x, y, z, start_end FROM face_edge_points WHERE volume = 'box' ORDER BY face, use_ord, start_end LIMIT 8" --db "$db"
