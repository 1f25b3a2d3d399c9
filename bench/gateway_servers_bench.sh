#!/usr/bin/env bash
# One gateway for several servers: its CPU and memory, and the frames each client gets against
# what its server draws. Two configurations in one run, so they compare by ratio on the day's
# machine: 1 server with 2 clients, and 4 servers with 8 clients (2 on each server). Each flagd
# at its defaults but for a 640 x 360 picture (30 frames a second); the clients are Foxglove's
# own protocol client (tests/web/servers_watch.mjs, one Node process, a connection each).
#   bench/gateway_servers_bench.sh [BUILD_DIR] [SECONDS]
# Runs inside a private network namespace (scripts/netns-run), so nothing leaves the machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
seconds=${2:-10}
if [[ -z ${FLAGSIM_IN_NETNS:-} ]]; then
  FLAGSIM_IN_NETNS=1 exec "$root/scripts/netns-run" -- "$0" "$build" "$seconds"
fi
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
flagd=$build/server/flagd flagctl=$build/client/flagctl
work=$(mktemp -d)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$work"' EXIT
ticks=$(getconf CLK_TCK)

cpu_seconds() {  # PID: user + system CPU seconds so far
  awk -v hz="$ticks" '{ printf "%.3f", ($14 + $15) / hz }' "/proc/$1/stat"
}

# measure SERVERS CLIENTS: one configuration, from fresh servers and a fresh gateway.
measure() {
  local servers=$1 clients=$2 prefixes=()
  for n in $(seq "$servers"); do
    prefixes+=("S${n}_")
    "$flagd" --prefix "S${n}_" --log-level warn &
    pids+=($!)
  done
  for prefix in "${prefixes[@]}"; do
    "$flagctl" --prefix "$prefix" --timeout 10 camera size 640 360 >/dev/null
  done
  "$flagctl" serve --listen 127.0.0.1:0 --record-dir "$work/rec" >"$work/serve.log" 2>&1 &
  local gateway=$!
  pids+=($gateway)
  local port=""
  for _ in $(seq 100); do
    port=$(sed -n 's#.*live view *http://[^:]*:\([0-9]*\)/.*#\1#p' "$work/serve.log")
    [[ -n $port ]] && break
    sleep 0.1
  done
  local list
  list=$(IFS=,; echo "${prefixes[*]}")
  local cpu0 cpu1
  cpu0=$(cpu_seconds "$gateway")
  local start=$SECONDS
  node "$root/tests/web/servers_watch.mjs" "ws://127.0.0.1:$port/" --servers "$list" --clients "$clients" \
    --seconds "$seconds" --spread >"$work/watch.json"
  cpu1=$(cpu_seconds "$gateway")
  local rss
  rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$gateway/status")
  node -e '
    const [file, servers, clients, cpu, wall, rss] = process.argv.slice(1);
    const out = JSON.parse(require("fs").readFileSync(file, "utf8"));
    const got = out.updates_per_second.map((r) => Object.entries(r)[0]);
    const ratios = out.share_of_frames.map((r) => Object.values(r)[0]);
    console.log(`${servers} servers, ${clients} clients: gateway ${(100 * cpu / wall).toFixed(1)} % of a core, ` +
      `${(rss / 1024).toFixed(1)} MB resident`);
    console.log(`  clients got ${got.map(([p, f]) => `${p} ${f.toFixed(1)}`).join(", ")} frames/s`);
    console.log(`  each client got ${Math.min(...ratios).toFixed(3)} .. ${Math.max(...ratios).toFixed(3)} of the frames its server drew (by frame id)`);
  ' "$work/watch.json" "$servers" "$clients" "$(awk -v a="$cpu0" -v b="$cpu1" 'BEGIN { print b - a }')" \
    "$((SECONDS - start))" "$rss"
  kill "${pids[@]}" 2>/dev/null || true
  wait "${pids[@]}" 2>/dev/null || true
  pids=()
}

echo "== $(nproc) cores, $seconds s a configuration"
measure 1 2
measure 4 8
