#!/bin/bash
# The service walk-through of docs/walkthrough.md, cancel example and studies shall work as printed: every `$ ` command of its console blocks
# runs against a live `stoss serve` (its 127.0.0.1:8080 replaced by the test's port), exits 0,
# and prints output of the same shape as the page shows — the same lines after ids, numbers,
# times and the worker's host name are masked. A job still running when polled is the one allowed
# difference (the page shows it mid-run).
# usage: test_readme_walkthrough.sh STOSS_BINARY SOURCE_DIR
set -uo pipefail
binary=$1
source_dir=$2
work=$(mktemp -d)
server_pid=
cleanup() {
  [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

"$binary" serve --listen 127.0.0.1:0 --data "$work/var" >"$work/serve.log" 2>&1 &
server_pid=$!
port=
for _ in $(seq 200); do
  port=$(grep -o 'http://127.0.0.1:[0-9]*' "$work/serve.log" | head -1 | cut -d: -f3)
  [ -n "$port" ] && break
  sleep 0.05
done
[ -n "$port" ] || { echo "server did not start:"; cat "$work/serve.log"; exit 1; }

# Commands and their expected output from the walk-through and studies sections: "C<tab>command" and
# "O<tab>line" records; continuation lines of a command (ending in \) are joined.
awk '
  /^### (Walk-through|Cancel and delete|Studies)/ { inside = 1; next }
  /^##/ { inside = 0 }
  inside && /^```console/ { block = 1; next }
  inside && /^```/ { block = 0; next }
  block && /^\$ / { cmd = substr($0, 3); while (cmd ~ /\\$/) { getline more; sub(/\\$/, "", cmd); cmd = cmd more }
                    print "C\t" cmd; next }
  block { print "O\t" $0 }
' "$source_dir/docs/walkthrough.md" >"$work/steps"
[ "$(grep -c '^C' "$work/steps")" -ge 8 ] || { echo "walk-through not found in docs/walkthrough.md"; exit 1; }

mask() {  # what may differ between runs: ids, numbers, timestamps, the worker host; HTTP status codes stay
  perl -pe 's/\r$//; s/\b[0-9a-f]{32}\b/ID/g; s/"(created|started|finished)":"[^"]*"/"$1":T/g; s/by \S+/by HOST/;
            s/(HTTP\/1\.1 \d{3}|"status":\d{3}|^\d{3}(?= ))|-?\d+(?:\.\d+)?(?:e[-+]?\d+)?/defined $1 ? $1 : "N"/ge;
            s/"eta_seconds":(N|null)/"eta_seconds":E/'
}

ln -s "$source_dir/api" "$work/api"
cd "$work" || exit 1
failures=0
check() {  # command, expected output file
  local command=$1 expected=$2
  local actual
  actual=$(bash -c "source ./env; ${command//127.0.0.1:8080/127.0.0.1:$port}; declare -p ID > ./env.new 2>/dev/null || true" 2>&1)
  local status=$?
  [ -s ./env.new ] && mv ./env.new ./env
  if [ $status -ne 0 ]; then
    echo "FAIL (exit $status): $command"; echo "$actual"; failures=$((failures + 1)); return
  fi
  if grep -q '"status":"running"' "$expected"; then
    echo "$actual" | grep -qE '"status":"(queued|running|succeeded)"' && return
  fi
  if ! diff <(mask <"$expected") <(printf '%s\n' "$actual" | tr -d '\r' | sed '/^$/d' | mask) >"$work/diff"; then
    echo "FAIL (output differs from docs/walkthrough.md): $command"; cat "$work/diff"; failures=$((failures + 1))
  fi
}

: >./env
command=
: >expected
while IFS=$'\t' read -r kind text; do
  if [ "$kind" = C ]; then
    [ -n "$command" ] && check "$command" expected
    command=$text
    : >expected
  elif [ -n "$text" ]; then
    printf '%s\n' "$text" >>expected
  fi
done <"$work/steps"
[ -n "$command" ] && check "$command" expected

commands=$(grep -c '^C' "$work/steps")
echo "$commands walk-through commands run, $failures failed"
[ $failures -eq 0 ]
