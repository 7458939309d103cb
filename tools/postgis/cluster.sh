#!/usr/bin/env bash
# A throw-away PostgreSQL + PostGIS cluster for the tests and the write benchmark.
#
#   tools/postgis/cluster.sh start STATE [--durable]   make, start, create the test database
#   tools/postgis/cluster.sh stop STATE                stop and remove everything it made
#
# The cluster lives in a fresh temporary folder (mktemp -d) and listens only on a unix socket in
# that folder (no TCP port, so it cannot meet another server). initdb refuses root, so as root
# the server runs as the `postgres` user (Debian's package makes it; else `nobody`), owning the
# folder; as anybody else, as that user.
#
# STATE (e.g. build/postgis) receives:
#   conninfo   the GDAL connection string of the test database, "PG:host=... dbname=fdrtest user=..."
#              or, when the server cannot be started here, one line "SKIP: <why>"
#   cluster    the temporary folder (read by `stop`)
#   log        the server's log
# `start` exits 0 in both cases (so CTest's fixture always runs and the tests themselves say
# why they skip); it exits non-zero only on a wrong command line.
#
# The database `fdrtest` has the postgis extension, a schema `coast`, and a role `fdr_pw` with
# password `fdr-secret` (password login over the socket: the wrong-password tests need one).
# Without --durable the server runs with fsync off and minimal WAL (a test cluster loses nothing
# that matters); --durable keeps PostgreSQL's defaults, for honest write timings.
set -uo pipefail

cmd="${1:-}"
state="${2:-}"
mode="${3:-}"
if [ -z "$cmd" ] || [ -z "$state" ]; then
  echo "usage: $0 start|stop STATE_DIR [--durable]" >&2
  exit 2
fi
mkdir -p "$state"
state="$(cd "$state" && pwd)"

DB=fdrtest
PW_ROLE=fdr_pw
PW=fdr-secret
PORT=5432

skip() {
  echo "SKIP: $*" > "$state/conninfo"
  echo "cluster.sh: PostgreSQL test server not started: $*" >&2
  exit 0
}

# The newest installed server's programs (Debian keeps them off PATH in /usr/lib/postgresql/N/bin).
find_bindir() {
  local d
  for d in $(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V -r); do
    [ -x "$d/initdb" ] && [ -x "$d/pg_ctl" ] && { echo "$d"; return 0; }
  done
  d="$(dirname "$(command -v initdb 2>/dev/null || echo /nonexistent/initdb)")"
  [ -x "$d/initdb" ] && [ -x "$d/pg_ctl" ] && { echo "$d"; return 0; }
  return 1
}

# Runs a command as the cluster's owner (root cannot run initdb or the server).
as_owner() {
  if [ "$(id -u)" -eq 0 ]; then
    if command -v runuser > /dev/null; then
      runuser -u "$owner" -- "$@"
    else
      setpriv --reuid="$owner" --regid="$(id -g "$owner")" --init-groups -- "$@"
    fi
  else
    "$@"
  fi
}

do_stop() {
  [ -f "$state/cluster" ] || { rm -f "$state/conninfo"; return 0; }
  local dir
  dir="$(cat "$state/cluster")"
  owner="$(stat -c %U "$dir" 2>/dev/null || id -un)"
  local bindir
  bindir="$(find_bindir)" || bindir=""
  if [ -n "$bindir" ] && [ -f "$dir/data/postmaster.pid" ]; then
    (cd "$dir" && as_owner "$bindir/pg_ctl" -D "$dir/data" -m immediate -w stop > /dev/null 2>&1) || true
  fi
  case "$dir" in
    */fdrpg.*) rm -rf "$dir" ;;  # only what `start` made
  esac
  rm -f "$state/cluster" "$state/conninfo"
}

do_start() {
  do_stop  # a cluster left by an interrupted run goes first
  local bindir
  bindir="$(find_bindir)" || skip "no PostgreSQL server programs (initdb, pg_ctl); install postgresql-15 (tools/install-deps.sh)"
  local ver
  ver="$(basename "$(dirname "$bindir")")"
  ls /usr/share/postgresql/"$ver"/extension/postgis.control > /dev/null 2>&1 ||
    ls "$("$bindir/pg_config" --sharedir 2>/dev/null)"/extension/postgis.control > /dev/null 2>&1 ||
    skip "PostgreSQL $ver has no PostGIS extension; install postgresql-$ver-postgis-3 (tools/install-deps.sh)"
  if [ "$(id -u)" -eq 0 ]; then
    owner=postgres
    id -u "$owner" > /dev/null 2>&1 || owner=nobody
  else
    owner="$(id -un)"
  fi
  local dir
  dir="$(mktemp -d "${TMPDIR:-/tmp}/fdrpg.XXXXXX")" || skip "cannot make a temporary folder"
  echo "$dir" > "$state/cluster"
  chmod 700 "$dir"
  [ "$(id -u)" -eq 0 ] && chown "$owner:" "$dir"
  : > "$state/log"
  # The socket path must fit in 107 bytes.
  [ "${#dir}" -lt 90 ] || skip "temporary folder path too long for a unix socket: $dir"
  cd "$dir" || skip "cannot enter $dir"
  as_owner "$bindir/initdb" -D "$dir/data" -U postgres --auth-local=trust --auth-host=reject -E UTF8 \
    --locale=C.UTF-8 > "$dir/initdb.log" 2>&1 ||
    as_owner "$bindir/initdb" -D "$dir/data" -U postgres --auth-local=trust --auth-host=reject -E UTF8 \
      --no-locale > "$dir/initdb.log" 2>&1 ||
    { cat "$dir/initdb.log" >> "$state/log"; skip "initdb failed as user $owner (see $state/log)"; }
  # Password login for the test role, trust for everyone else (over this private socket only).
  as_owner sh -c "printf 'local all $PW_ROLE scram-sha-256\nlocal all all trust\n' > '$dir/data/pg_hba.conf'"
  local opts="-c listen_addresses='' -c unix_socket_directories='$dir' -c port=$PORT -c max_connections=20"
  [ "$mode" = "--durable" ] ||
    opts="$opts -c fsync=off -c synchronous_commit=off -c full_page_writes=off -c wal_level=minimal -c max_wal_senders=0"
  as_owner "$bindir/pg_ctl" -D "$dir/data" -l "$dir/server.log" -o "$opts" -w -t 60 start > /dev/null 2>&1 ||
    { cat "$dir/server.log" >> "$state/log" 2>/dev/null; skip "the server did not start (see $state/log)"; }
  local psql="$bindir/psql"
  [ -x "$psql" ] || psql="$(command -v psql)"
  local q=("$psql" -X -q -v ON_ERROR_STOP=1 -h "$dir" -p "$PORT" -U postgres)
  {
    "${q[@]}" -d postgres -c "CREATE ROLE $PW_ROLE LOGIN PASSWORD '$PW'" &&
      "${q[@]}" -d postgres -c "CREATE DATABASE $DB" &&
      "${q[@]}" -d "$DB" -c "CREATE EXTENSION postgis" &&
      "${q[@]}" -d "$DB" -c "CREATE SCHEMA coast; GRANT ALL ON SCHEMA public, coast TO $PW_ROLE;
                            GRANT SELECT, INSERT ON spatial_ref_sys TO $PW_ROLE"
  } >> "$state/log" 2>&1 || { cat "$dir/server.log" >> "$state/log" 2>/dev/null; skip "creating the PostGIS test database failed (see $state/log)"; }
  echo "PG:host=$dir port=$PORT dbname=$DB user=postgres" > "$state/conninfo"
  echo "cluster.sh: PostgreSQL $ver + PostGIS test server on $dir (database $DB)"
}

case "$cmd" in
  start) do_start ;;
  stop) do_stop ;;
  *) echo "usage: $0 start|stop STATE_DIR [--durable]" >&2; exit 2 ;;
esac
