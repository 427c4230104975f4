#!/usr/bin/env bash
# Shared set-up for ./run.sh and ./test.sh: installs the Debian packages listed in
# deps/apt-*.txt that are missing (only those), then configures and builds.
#   scripts/setup.sh BUILD_DIR [extra cmake arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."

missing=()
for pkg in $(cat deps/apt-*.txt | sed 's/#.*//' | sort -u); do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

build_dir=$1
shift
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# Configure when the folder is new or when the flags differ from the ones it was
# configured with (kept in $build_dir/setup-flags), so that changing a flag here or in
# the caller takes effect without deleting the folder.
flags="${generator[*]} ${launcher[*]} $*"
if [ ! -f "$build_dir/CMakeCache.txt" ] || [ "$(cat "$build_dir/setup-flags" 2>/dev/null)" != "$flags" ]; then
  cmake -S . -B "$build_dir" "${generator[@]}" "${launcher[@]}" "$@"
  echo "$flags" > "$build_dir/setup-flags"
fi
cmake --build "$build_dir" -j "$(nproc 2>/dev/null || echo 2)"
