#!/usr/bin/env bash
# The live view's figures (bench/live_view/measure.mjs): frames a browser shows against the
# bus, a command's round trip to the canvas, the server with 0, 1 and 8 browsers, the gateway's
# CPU, memory and bytes per client. Two configurations: flagd's defaults (32 x 24 flag, 30
# frames a second) and 64 x 48 at 60 frames a second, both 1280 x 720.
#   bench/live_view.sh [BUILD_DIR] [SECONDS]      results: BUILD_DIR/bench/live_view-*.json
# Runs inside a private network namespace (scripts/netns-run), so nothing leaves the machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
seconds=${2:-10}
if [[ -z ${FLAGSIM_IN_NETNS:-} ]]; then
  FLAGSIM_IN_NETNS=1 exec "$root/scripts/netns-run" -- "$0" "$build" "$seconds"
fi
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
mkdir -p "$build/bench"
server=""
gateway=""
trap 'kill $server $gateway 2>/dev/null || true' EXIT

# measure NAME FLAGD_OPTION...: one configuration, from a fresh server and gateway.
measure() {
  local name=$1
  shift
  "$build/server/flagd" --log-level warn "$@" &
  server=$!
  # One server, plain topics (/flag/tiles), which measure.mjs follows.
  "$build/client/flagctl" --prefix FLAGSIM_ serve --listen 127.0.0.1:0 --record-dir /tmp >"$build/bench/serve.log" 2>&1 &
  gateway=$!
  local port=""
  for _ in $(seq 100); do
    port=$(sed -n 's#.*live view *http://[^:]*:\([0-9]*\)/.*#\1#p' "$build/bench/serve.log")
    [[ -n $port ]] && break
    sleep 0.1
  done
  echo "== $name: flagd $*"
  node "$root/bench/live_view/measure.mjs" "http://127.0.0.1:$port/" "$seconds" "$build/bench/live_view-$name.json"
  kill $gateway $server
  wait $gateway $server 2>/dev/null || true
}

measure defaults
measure 64x48-60fps --set cols=64 --set rows=48 --set frame_rate=60
