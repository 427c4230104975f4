#!/usr/bin/env bash
# A throwaway PostgreSQL server (the newest installed) for the store tests.
#
#   eval "$(scripts/pg_test_server.sh start)"   # prints export CELLFORGE_PG_URL=... CELLFORGE_PG_DIR=...
#   ... ctest ...
#   scripts/pg_test_server.sh stop              # uses $CELLFORGE_PG_DIR (or pass the dir)
#
# initdb into a fresh temporary directory as an unprivileged user (the `postgres`
# user, or `nobody`, when run as root; the caller otherwise), trust authentication,
# no TCP: the server listens only on a Unix socket inside that directory, so runs
# never collide on a port. The superuser is `cellforge_admin`; the tests connect as
# `cellforge`, which is not a superuser: it owns the database `cellforge` and may
# create roles (the store creates `cellforge_reader`, under which user SQL runs).
# Exits non-zero (and says why on stderr) when the server cannot start.
set -euo pipefail

find_bin() {
  local name=$1 dir
  # Debian keeps each major version's programs in /usr/lib/postgresql/N/bin: the
  # highest N that has the program.
  for dir in $(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -t/ -k5,5nr); do
    [[ -x $dir/$name ]] && { echo "$dir/$name"; return; }
  done
  command -v "$name" || { echo "pg_test_server: $name not found (apt-get install postgresql)" >&2; exit 1; }
}

as_user() {
  if [[ $(id -u) -eq 0 ]]; then
    runuser -u "$PG_USER" -- "$@"
  else
    "$@"
  fi
}

pick_user() {
  if [[ $(id -u) -ne 0 ]]; then PG_USER=$(id -un); return; fi
  for u in postgres nobody; do
    if id "$u" >/dev/null 2>&1; then PG_USER=$u; return; fi
  done
  echo "pg_test_server: running as root and neither 'postgres' nor 'nobody' exists" >&2
  exit 1
}

start() {
  pick_user
  local initdb pg_ctl dir
  initdb=$(find_bin initdb)
  pg_ctl=$(find_bin pg_ctl)
  dir=$(mktemp -d "${TMPDIR:-/tmp}/cellforge-pg.XXXXXX")
  chmod 755 "$dir"
  mkdir "$dir/data" "$dir/socket"
  [[ $(id -u) -eq 0 ]] && chown "$PG_USER" "$dir/data" "$dir/socket"
  if ! as_user "$initdb" -D "$dir/data" -U cellforge_admin -A trust -E UTF8 --locale=C.UTF-8 \
    >"$dir/initdb.log" 2>&1; then
    cat "$dir/initdb.log" >&2
    rm -rf "$dir"
    exit 1
  fi
  if ! as_user "$pg_ctl" -D "$dir/data" -l "$dir/data/server.log" -w -t 60 \
    -o "-c listen_addresses='' -c unix_socket_directories='$dir/socket' -c fsync=off" \
    start >/dev/null; then
    cat "$dir/data/server.log" >&2
    rm -rf "$dir"
    exit 1
  fi
  local url="postgresql:///postgres?host=$dir/socket&user=cellforge_admin"
  { psql "$url" -qAtc "CREATE ROLE cellforge LOGIN CREATEROLE" \
      && psql "$url" -qAtc "CREATE DATABASE cellforge OWNER cellforge"; } >/dev/null \
    || { echo "pg_test_server: CREATE ROLE / DATABASE failed" >&2; stop_dir "$dir"; exit 1; }
  echo "export CELLFORGE_PG_DIR='$dir'"
  echo "export CELLFORGE_PG_URL='postgresql:///cellforge?host=$dir/socket&user=cellforge'"
}

stop_dir() {
  local dir=$1 pg_ctl
  [[ -d $dir/data ]] || { echo "pg_test_server: no server in '$dir'" >&2; exit 1; }
  pick_user
  pg_ctl=$(find_bin pg_ctl)
  as_user "$pg_ctl" -D "$dir/data" -m fast -w stop >/dev/null 2>&1 || true
  rm -rf "$dir"
}

case "${1:-}" in
  start) start ;;
  stop) stop_dir "${2:-${CELLFORGE_PG_DIR:?pg_test_server: set CELLFORGE_PG_DIR or pass the dir}}" ;;
  *) echo "usage: $0 start|stop [dir]" >&2; exit 2 ;;
esac
