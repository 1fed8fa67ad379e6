#!/usr/bin/env bash
# A throwaway PostgreSQL cluster for the tests and benchmarks (no mock): initdb into DIR, run on
# 127.0.0.1:PORT, as the unprivileged user `nobody` when run as root (PostgreSQL refuses root).
#   pg_cluster.sh start DIR PORT   initdb (first time) and start; prints the superuser's URL
#   pg_cluster.sh start DIR auto   a fresh cluster in DIR on a free port (written to DIR/port): the one
#                                  cluster a ctest run shares (CMakeLists.txt, fixture pg_cluster)
#   pg_cluster.sh stop DIR         fast shutdown (the data stays: start again to restart)
#   pg_cluster.sh remove DIR       stop and delete DIR
# The superuser is `stoss` with password `secret` over TCP (scram-sha-256). STOSS_PG_DURABLE=1 keeps
# fsync and synchronous commit on (benchmarks); otherwise they are off (tests).
set -euo pipefail
command=$1
dir=$2
bindir=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)
[[ -x "$bindir/initdb" ]] || bindir=$(pg_config --bindir)
owner=$(id -un)
[[ $(id -u) -eq 0 ]] && owner=nobody

as_owner() {
  if [[ $(id -u) -eq 0 ]]; then setpriv --reuid=nobody --regid=nogroup --clear-groups -- "$@"; else "$@"; fi
}

case "$command" in
  start)
    port=$3
    if [[ "$port" == auto ]]; then
      "$0" remove "$dir"
      port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
    fi
    mkdir -p "$dir"
    chmod 700 "$dir"
    [[ $(id -u) -eq 0 ]] && chown nobody:nogroup "$dir"
    cd "$dir"  # the server's user may not be able to enter the caller's directory (a build under /root)
    if [[ ! -f "$dir/data/PG_VERSION" ]]; then
      echo secret | as_owner tee "$dir/password" >/dev/null
      as_owner "$bindir/initdb" -D "$dir/data" -U stoss --pwfile="$dir/password" --auth-host=scram-sha-256 \
        --auth-local=trust --no-sync -E UTF8 --locale=C >"$dir/initdb.log" 2>&1 ||
        { cat "$dir/initdb.log" >&2; exit 1; }
    fi
    settings="-p $port -k $dir -c listen_addresses=127.0.0.1 -c max_connections=200"
    [[ "${STOSS_PG_DURABLE:-0}" == 1 ]] || settings="$settings -c fsync=off -c synchronous_commit=off -c full_page_writes=off"
    as_owner "$bindir/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 60 -o "$settings" start >/dev/null ||
      { cat "$dir/server.log" >&2; exit 1; }
    echo "$port" | as_owner tee "$dir/port" >/dev/null
    echo "postgresql://stoss:secret@127.0.0.1:$port/postgres"
    ;;
  stop)
    cd "$dir"
    as_owner "$bindir/pg_ctl" -D "$dir/data" -m fast -w -t 60 stop >/dev/null 2>&1 || true
    ;;
  remove)
    if [[ -d "$dir/data" ]]; then (cd "$dir" && as_owner "$bindir/pg_ctl" -D "$dir/data" -m immediate -w stop >/dev/null 2>&1) || true; fi
    rm -rf "$dir"
    ;;
  *)
    echo "usage: pg_cluster.sh start DIR PORT | stop DIR | remove DIR" >&2
    exit 2
    ;;
esac
