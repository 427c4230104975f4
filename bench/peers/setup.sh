#!/usr/bin/env bash
# What the peers of bench/bench_boolean need, installed on request only (the default
# set-up never runs this): the Debian packages in bench/peers/apt.txt that are missing,
# and the npm package manifold-3d (version pinned in bench/peers/package.json) into
# BUILD_DIR/peers, outside the source tree. The build itself downloads nothing.
#   bench/peers/setup.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build_dir=$(realpath -m "${1:?usage: bench/peers/setup.sh BUILD_DIR}")

missing=()
for pkg in $(sed 's/#.*//' "$here/apt.txt"); do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
  echo "peers: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

mkdir -p "$build_dir/peers"
cp "$here/package.json" "$build_dir/peers/package.json"
(cd "$build_dir/peers" && npm install --no-audit --no-fund --omit=dev)
