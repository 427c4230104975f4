#!/usr/bin/env bash
# Builds OpenSCAD files with both `cellforge build` and Debian's `openscad -o` and
# compares them: volume (relative 1e-5: OpenSCAD's STL has 6 digits), bounding box,
# validity of cellforge's result, and the echo output, line for line.
#
#   scripts/openscad_compare.sh [--all] [--record DIR | --recorded DIR] [BUILD_DIR]
#
# --record DIR keeps what openscad gave for each file in DIR (its exit code, its
# echo, error and warning lines, and its result's volume and box: one small file a
# file compared); --recorded DIR reads that instead of running openscad, so that
# the --all set beyond the corpus can be checked in well under a minute of
# cellforge's time, where openscad takes many (./test.sh does it;
# tests/openscad_recorded/ was recorded with Debian's openscad 2021.01, timeout 60 s).
#
# Compares every file of tests/scad/ (those marked `// expect no-openscad: WHY` are
# skipped with the reason); with --all also cellforge's examples/, every example the
# openscad package ships (/usr/share/openscad/examples) and every MCAD file. A file whose results differ must be listed, with the reason, in
# docs/compatibility.md (as `label`); a difference that is not listed fails the
# script. The per-file results and both programs' times go to
# BUILD_DIR/openscad-compare.txt.
#   COMPARE_TIMEOUT=120  seconds each program may take on one file
set -uo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
ALL=0 RECORD="" RECORDED=""
while [ $# -gt 0 ]; do
  case $1 in
    --all) ALL=1 ;;
    --record) RECORD=$(mkdir -p "$2" && cd "$2" && pwd); shift ;;
    --recorded) RECORDED=$(cd "$2" && pwd); shift ;;
    *) break ;;
  esac
  shift
done
BUILD=$(cd "${1:-$ROOT/build}" && pwd)
CF=$BUILD/bin/cellforge
T=${COMPARE_TIMEOUT:-120}
KNOWN=$ROOT/docs/compatibility.md
OUT=$BUILD/openscad-compare.txt
[ -n "$RECORDED" ] && OUT=$BUILD/openscad-recorded.txt
[ -n "$RECORDED" ] || command -v openscad > /dev/null ||
  { echo "openscad_compare: openscad not installed (apt-get install openscad)"; exit 1; }
[ -x "$CF" ] || { echo "openscad_compare: $CF not built"; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
: > "$OUT"
ok=0 known=0 new=0 skipped=0

# The six numbers of a bounding box in a JSON text, space-separated.
bbox_of() { grep -o '"bbox": [^}]*\]\]\?' "$1" | head -n 1 | grep -oE -- '-?[0-9.]+(e[-+]?[0-9]+)?' | tr '\n' ' '; }
field() { grep -o "\"$2\": [^,}]*" "$1" | head -n 1 | sed 's/.*: //'; }

# OpenSCAD's volume and box from its ASCII STL directly: the signed volume of every
# triangle (a cavity's inward shell counts negative), independent of cellforge's reader.
oc_json() {
  awk 'BEGIN { n = 0 }
       $1 == "vertex" { x[n] = $2; y[n] = $3; z[n] = $4; n++;
         if (!init) { lx = hx = $2; ly = hy = $3; lz = hz = $4; init = 1 }
         if ($2 < lx) lx = $2; if ($2 > hx) hx = $2; if ($3 < ly) ly = $3; if ($3 > hy) hy = $3;
         if ($4 < lz) lz = $4; if ($4 > hz) hz = $4;
         if (n == 3) { v += x[0] * (y[1] * z[2] - z[1] * y[2]) / 6; v -= y[0] * (x[1] * z[2] - z[1] * x[2]) / 6
                       v += z[0] * (x[1] * y[2] - y[1] * x[2]) / 6; n = 0 } }
       END { printf "{\"volume\": %.17g, \"bbox\": [[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]]}\n", v, lx, ly, lz, hx, hy, hz }' \
    "$tmp/oc.stl" > "$tmp/oc.json"
}

# compare LABEL FILE: appends one line to $OUT; sets $result.
compare() {
  local label=$1 file=$2 defines=()
  local d
  d=$(grep -o '// expect define: .*' "$file" | sed 's|// expect define: ||')
  [ -n "$d" ] && defines=(-D "$d")
  rm -f "$tmp"/oc.stl "$tmp"/cf.stl "$tmp"/oc.json
  local t0=$EPOCHREALTIME
  local kept oc_rc
  kept=${label//\//__}.txt
  if [ -n "$RECORDED" ]; then
    # Line 1 the exit code, line 2 the volume and box (or nothing), then the lines of
    # openscad's output that are read below.
    [ -f "$RECORDED/$kept" ] || { result="FAIL: nothing recorded for it in $RECORDED"; times=""; return; }
    oc_rc=$(sed -n 1p "$RECORDED/$kept")
    if [ -n "$(sed -n 2p "$RECORDED/$kept")" ]; then
      sed -n 2p "$RECORDED/$kept" > "$tmp/oc.json"
      echo recorded > "$tmp/oc.stl"
    fi
    sed -n '3,$p' "$RECORDED/$kept" > "$tmp/oc.out"
  else
    (cd "$(dirname "$file")" && timeout "$T" openscad "${defines[@]}" -o "$tmp/oc.stl" "$(basename "$file")") > "$tmp/oc.out" 2>&1
    oc_rc=$?
  fi
  oc_rc_kept=$oc_rc
  local t1=$EPOCHREALTIME
  (cd "$(dirname "$file")" && timeout "$T" "$CF" build --no-cache "$(basename "$file")" "${defines[@]}" -o "$tmp/cf.stl" --report json) \
    > "$tmp/cf.out" 2> "$tmp/cf.err"
  local cf_rc=$?
  local t2=$EPOCHREALTIME
  times=$(awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN { printf "openscad %.3f s, cellforge %.3f s", b - a, c - b }')
  # OpenSCAD may print other text without a newline before an echo line
  # (examples/Old/example023.scad: "\\\\\\ECHO: ..."), so the echo is taken from where
  # "ECHO: " starts.
  grep -o 'ECHO: .*' "$tmp/oc.out" > "$tmp/oc.echo"
  grep '^ECHO:' "$tmp/cf.out" > "$tmp/cf.echo"
  grep '^{' "$tmp/cf.out" | tail -n 1 > "$tmp/cf.json"
  local oc_empty=0
  grep -q "Current top level object is empty" "$tmp/oc.out" && oc_empty=1
  if [ $oc_rc -eq 124 ]; then result="skip: openscad took more than ${T}s"; return; fi
  if [ $cf_rc -ne 0 ] && [ $cf_rc -ne 124 ] && grep -q '^ERROR:' "$tmp/oc.out"; then
    result=ok  # both refuse the file
    return
  fi
  if [ $oc_rc -ne 0 ] && [ $oc_empty -eq 0 ] && [ ! -s "$tmp/oc.echo" ]; then
    if grep -q "not a 3D object\|not a 3D" "$tmp/oc.out"; then
      result="skip: a 2D result (OpenSCAD exports it as DXF/SVG only)"
    else
      result="skip: openscad fails ($(grep -m1 -E 'ERROR|WARNING' "$tmp/oc.out" | cut -c1-100))"
    fi
    return
  fi
  if [ $cf_rc -eq 124 ]; then result="FAIL: cellforge took more than ${T}s"; return; fi
  if [ $cf_rc -ne 0 ]; then
    result="FAIL: cellforge: $(grep -v '^ ' "$tmp/cf.err" | grep -v ': warning: ' | head -n 1 | cut -c1-160)"
    return
  fi
  if ! diff -q "$tmp/oc.echo" "$tmp/cf.echo" > /dev/null; then
    result="FAIL: echo differs: $(diff "$tmp/oc.echo" "$tmp/cf.echo" | grep '^[<>]' | head -n 2 | tr '\n' ' ' | cut -c1-200)"
    return
  fi
  [ "$(field "$tmp/cf.json" valid)" = "true" ] || { result="FAIL: cellforge's result is invalid"; return; }
  local cv
  cv=$(field "$tmp/cf.json" volume)
  if [ $oc_empty -eq 1 ] || [ ! -s "$tmp/oc.stl" ]; then
    if [ $oc_empty -eq 1 ] && awk -v v="$cv" 'BEGIN { exit !(v == 0) }'; then result=ok; return; fi
    if [ $oc_empty -eq 1 ]; then result="FAIL: openscad's result is empty, cellforge's volume is $cv"; return; fi
    result=ok  # no geometry from openscad, the echo agreed
    return
  fi
  [ -s "$tmp/oc.json" ] || oc_json
  local ov
  ov=$(field "$tmp/oc.json" volume)
  if ! awk -v a="$ov" -v b="$cv" 'BEGIN { d = a - b; if (d < 0) d = -d; m = (a < 0 ? -a : a); if ((b < 0 ? -b : b) > m) m = (b < 0 ? -b : b); exit !(d <= 1e-5 * m + 1e-9) }'; then
    result="FAIL: volume $cv, openscad $ov"
    return
  fi
  local ob cb
  ob=$(bbox_of "$tmp/oc.json")
  cb=$(bbox_of "$tmp/cf.json")
  if ! awk -v a="$ob" -v b="$cb" 'BEGIN { n = split(a, x, " "); split(b, y, " "); if (n != 6) exit 1;
         s = 1; for (i = 1; i <= 3; i++) { e = x[i + 3] - x[i]; if (e > s) s = e }
         for (i = 1; i <= 6; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > 1e-5 * s) exit 1 } }'; then
    result="FAIL: bounding box $cb, openscad $ob"
    return
  fi
  result=ok
}

record() {  # LABEL FILE
  local label=$1 file=$2 why
  times=""
  why=$(grep -o '// expect no-openscad: .*' "$file" 2> /dev/null | sed 's|// expect no-openscad: ||')
  if [ -n "$why" ]; then
    result="skip: $why"
  else
    compare "$label" "$file"
    if [ -n "$RECORD" ] && [ "${label#tests/scad/}" = "$label" ]; then
      [ -s "$tmp/oc.json" ] || [ ! -s "$tmp/oc.stl" ] || oc_json
      { echo "${oc_rc_kept:-}"; cat "$tmp/oc.json" 2> /dev/null || echo; grep -E 'ECHO: |Current top level object is empty|ERROR|WARNING|not a 3D' "$tmp/oc.out"; } \
        > "$RECORD/${label//\//__}.txt"
    fi
  fi
  case $result in
    ok) ok=$((ok + 1)) ;;
    skip*) skipped=$((skipped + 1)) ;;
    FAIL*)
      if grep -qF "\`$label\`" "$KNOWN" 2> /dev/null; then
        known=$((known + 1))
        result="known ${result#FAIL: }"
      else
        new=$((new + 1))
        echo "openscad_compare: $label: $result"
      fi
      ;;
  esac
  printf '%s\t%s\t%s\n' "$label" "$result" "$times" >> "$OUT"
}

# (With --recorded the corpus is left to the comparison with openscad itself, which
# ./test.sh runs first.)
if [ -z "$RECORDED" ]; then
  for f in "$ROOT"/tests/scad/*.scad; do
    record "tests/scad/$(basename "$f")" "$f"
  done
fi
if [ $ALL -eq 1 ]; then
  for f in "$ROOT"/examples/*.scad; do
    record "cellforge-examples/$(basename "$f")" "$f"
  done
  for f in $(find /usr/share/openscad/examples -name '*.scad' | sort); do
    record "examples/${f#/usr/share/openscad/examples/}" "$f"
  done
  for f in /usr/share/openscad/libraries/MCAD/*.scad; do
    record "MCAD/$(basename "$f")" "$f"
  done
fi
echo "openscad_compare: $ok agree, $known known differences (docs/compatibility.md), $new new, $skipped skipped; details in $OUT"
[ $new -eq 0 ]
