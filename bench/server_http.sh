#!/usr/bin/env bash
# HTTP benchmarks of `stoss serve` on loopback (issue 10), bounded in time and connections:
#  1. status polls: wrk, 50 kept-alive connections, 10 s each, GET /v1/jobs/{id} of a job that runs
#     meanwhile (target >= 1000 polls/s at p99 <= 20 ms on 2 cores):
#     a. at about 1,100 polls/s (each connection polls every 45 ms, a wrk Lua delay): the target's rate;
#     b. saturated (each connection polls again as soon as answered): the most polls/s; 50 requests are
#        always outstanding, so the mean latency is 50 / throughput (Little's law) and p99 is its tail;
#     c. saturated GET /healthz, which reads no job store: what the HTTP layer alone costs;
#  2. slow clients: 50 connections each stalled mid-body on POST /v1/jobs, then GET /healthz 20 times;
#     its latency (target < 1 s).
# The load average is printed before and after: other processes on the machine lengthen the tails.
# usage: bench/server_http.sh [STOSS_BINARY]   (default build/stoss); needs wrk and curl (deploy/packages.txt)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
STOSS="${1:-$ROOT/build/stoss}"
work=$(mktemp -d)
server_pid=
cleanup() {
  [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

"$STOSS" serve --listen 127.0.0.1:0 --data "$work/var" --workers 1 >"$work/serve.log" 2>&1 &
server_pid=$!
port=
for _ in $(seq 200); do
  port=$(grep -o 'http://127.0.0.1:[0-9]*' "$work/serve.log" | head -1 | cut -d: -f3 || true)
  [ -n "$port" ] && break
  sleep 0.05
done
[ -n "$port" ] || { cat "$work/serve.log"; exit 1; }
base="http://127.0.0.1:$port"

# A job that runs through the measurement (the sphere, 2000 steps).
sed 's/"end": *2\(\.0\)\?/"end": 20/' "$ROOT/api/examples/tumbling_sphere.json" >"$work/long.json"
id=$(curl -s -X POST -H 'Content-Type: application/json' --data-binary @"$work/long.json" "$base/v1/jobs" |
  grep -o '"id":"[0-9a-f]*"' | cut -d'"' -f4)
until curl -s "$base/v1/jobs/$id" | grep -q '"status":"running"'; do sleep 0.1; done

filter='Requests/sec|Latency|50%|90%|99%|requests in|Non-2xx|Socket errors'
printf 'function delay()\n  return 45\nend\n' >"$work/paced.lua"
echo "== load average before: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) cores)"
echo "== status polls at ~1,100/s: wrk -t2 -c50 -d10s -s paced.lua (45 ms between polls), while job $id runs"
wrk -t2 -c50 -d10s --latency -s "$work/paced.lua" "$base/v1/jobs/$id" | grep -E "$filter"
echo "== status polls saturated: wrk -t2 -c50 -d10s, keep-alive, while job $id runs"
wrk -t2 -c50 -d10s --latency "$base/v1/jobs/$id" | grep -E "$filter"
echo "== GET /healthz saturated (no job store): wrk -t2 -c50 -d10s, while job $id runs"
wrk -t2 -c50 -d10s --latency "$base/healthz" | grep -E "$filter"
echo "== load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

echo "== slow clients: 50 uploads stalled mid-body, then GET /healthz x20"
fds=()
for _ in $(seq 50); do
  exec {fd}<>"/dev/tcp/127.0.0.1/$port"
  printf 'POST /v1/jobs HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: 100000\r\n\r\n{"format": ' >&"$fd"
  fds+=("$fd")
done
sleep 0.3
times=()
for _ in $(seq 20); do
  times+=("$(curl -s -o /dev/null -m 10 -w '%{http_code} %{time_total}' "$base/healthz")")
done
printf '%s\n' "${times[@]}" | awk '{ n++; if ($1 != 200) bad++; t = $2 * 1000; sum += t; if (t > max) max = t }
  END { printf "healthz: %d answers, %d not 200, mean %.2f ms, max %.2f ms\n", n, bad, sum / n, max }'
for fd in "${fds[@]}"; do exec {fd}>&-; done
