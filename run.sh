#!/usr/bin/env bash
# The main job on the bundled examples: build, combine by Boolean operations,
# build OpenSCAD files, validate, query, store, export.
set -euo pipefail
cd "$(dirname "$0")"

# -O2 without debug information, as test.sh builds it (one build folder for both): the
# debug information took a quarter of the compile time (CI's budget, test.sh).
scripts/setup.sh build -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
bin=build/bin/cellforge
db=build/cellforge.db
out=build/out
mkdir -p "$out"

# Models built with the Euler operators: validated, counted, queried.
"$bin" demo

# Stored in the SQLite model database (a new version on every run), then exported
# from it for 3D printing (binary STL, 3MF) and losslessly (native JSON).
for example in box box_with_hole nonmanifold; do
  "$bin" db save "example:$example" --name "$example" --db "$db"
  for ext in stl 3mf json; do
    "$bin" db load "$example" -o "$out/$example.$ext" --db "$db"
  done
done
"$bin" db list --db "$db"
"$bin" db sql "SELECT face, edge, direction, point, x, y, z, start_end FROM face_edge_points WHERE volume = 'box' AND version = (SELECT max(version) FROM face_edge_points WHERE volume = 'box') ORDER BY face, use_ord, start_end LIMIT 8" --db "$db"

# OpenSCAD-style primitives and sweeps, written for printing and stored.
"$bin" make sphere r=10 fn=32 -o "$out/sphere.stl"
"$bin" make cylinder h=5 r1=3 r2=1 fn=17 -o "$out/cone.stl"
"$bin" make torus R=5 r=1 fn=24 -o "$out/torus.stl"
"$bin" make linear_extrude shape=ngon n=6 r=2 height=10 twist=90 slices=5 -o "$out/twist.stl"
for part in sphere cone torus twist; do
  "$bin" db save "$out/$part.stl" --name "$part" --db "$db"
done

# Parts combined by exact Boolean operations: a plate with a hole exactly through it
# (caps coplanar with its faces), a sphere minus an offset sphere, and two cubes
# that share only an edge (a valid non-manifold union), each validated and stored.
"$bin" make cube size=40,30,8 center=true -o "$out/plate.stl"
"$bin" make cylinder h=8 r=6 fn=48 center=true -o "$out/peg.stl"
"$bin" make sphere r=10 fn=48 -o "$out/ball.stl"
"$bin" make cube size=10,10,10 -o "$out/cube.stl"
"$bin" bool difference "$out/plate.stl" "$out/peg.stl" -o "$out/plate_with_hole.stl"
"$bin" bool difference "$out/ball.stl" "$out/cube.stl" -o "$out/ball_minus_cube.stl" --report json
"$bin" bool union "$out/cube.stl" examples/cube_at_10_10.off -o "$out/cubes_sharing_an_edge.json"
for part in plate_with_hole ball_minus_cube cubes_sharing_an_edge; do
  ext=stl; [ "$part" = cubes_sharing_an_edge ] && ext=json
  "$bin" db save "$out/$part.$ext" --name "$part" --db "$db"
done

# Parts written in the OpenSCAD language (examples/*.scad), built exactly by
# `cellforge build` (one n-ary Boolean per run of set operations), written for
# printing, stored with their scripts, and listed: model, faces, valid, volume, time.
printf '\n%-18s %7s %6s %14s %9s\n' model faces valid volume "build s"
for scad in examples/*.scad; do
  name=$(basename "$scad" .scad)
  report=$("$bin" build "$scad" -o "$out/$name.stl" -o "$out/$name.3mf" --save "$name" --db "$db" \
             --no-cache --report json)
  python3 -c 'import json, sys
r = json.loads(sys.argv[2]); s = r["seconds"]
print("%-18s %7d %6s %14.6g %9.3f" % (sys.argv[1], r["faces"], "yes" if r["valid"] else "NO",
      r["volume"], s["evaluate"] + s["build"] + s["write"]))' "$name" "$report"
done
echo

# What a slicer will see: exported meshes read back and diagnosed.
"$bin" info "$out/box_with_hole.stl"
"$bin" info "$out/torus.stl"
"$bin" info "$out/plate_with_hole.stl"
echo "run.sh: exported to $out/"
