#!/usr/bin/env bash
# The live view as people and programs use it, over udpm:// inside a private network namespace
# (ctest runs this through scripts/netns-run): flagd and flagctl serve with a token, then clients
# the project did not write: Node's fetch and ws at the gateway's doors (access_test.mjs),
# Foxglove's own protocol client (foxglove_client_test.mjs) and Chromium on the page
# (browser_test.mjs). The page's screenshots stay in BUILD_DIR/tests/live_view/.
# Usage: live_view_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
tests=$(cd "$(dirname "$0")/../web" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=LIVE_
token=$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
work=$(mktemp -d)
shots=$build/tests/live_view
mkdir -p "$shots"
server=""
gateway=""
cleanup() {
  [[ -n $gateway ]] && kill "$gateway" 2>/dev/null || true
  [[ -n $server ]] && kill "$server" 2>/dev/null || true
  [[ -f $work/flagd.pid ]] && kill "$(cat "$work/flagd.pid")" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

source "$(dirname "$0")/checks.sh"


echo "-- the gateway's command line"
expect 0 "flagctl serve --help" "$flagctl" serve --help
contains "--allow-origin" "  lists its options"
expect 2 "--listen without a port is a usage error" "$flagctl" --prefix $prefix serve --listen 127.0.0.1
contains "expected HOST:PORT" "  and says what is expected"
"$flagctl" --prefix $prefix serve --listen 0.0.0.0:0 --record-dir "$work/rec" --tls-dir "$work/tls" \
  >"$work/open.log" 2>&1 &
open_gateway=$!
open_port=$(gateway_port "$work/open.log")
if grep -Eq "live view +https://.*/\?token=[0-9a-f]{32}$" "$work/open.log"; then
  pass "beyond loopback without --token, a token is generated and printed with an https:// URL"
else
  fail "no generated token or no https:// in the URL" "$work/open.log"
fi
if grep -Eq "TLS self-signed certificate .*gateway.crt, SHA-256 fingerprint ([0-9A-F]{2}:){31}[0-9A-F]{2}" "$work/open.log"; then
  pass "  with a self-signed certificate made for it, its fingerprint printed"
else fail "  no certificate or fingerprint printed" "$work/open.log"; fi
open_token=$(sed -n 's#.*live view *https://[^?]*?token=\([0-9a-f]*\)$#\1#p' "$work/open.log" | head -1)
# Another pair, for a client that trusts the wrong certificate and for a key that does not match.
"$flagctl" --prefix $prefix serve --listen 0.0.0.0:0 --tls-dir "$work/other-tls" >"$work/other.log" 2>&1 &
other_gateway=$!
gateway_port "$work/other.log" >/dev/null
kill -TERM $other_gateway
wait $other_gateway || true
if node "$tests/tls_test.mjs" "$open_port" "$open_token" "$work/tls/gateway.crt" "$work/other-tls/gateway.crt" \
  >"$work/tls.out" 2>&1; then
  sed 's/^/      /' "$work/tls.out"
  pass "HTTPS and WSS for a client that trusts it; refused with another certificate; plain HTTP told to use https"
else fail "TLS" "$work/tls.out"; fi
kill -TERM $open_gateway
wait $open_gateway && pass "flagctl serve stops cleanly on SIGTERM" || fail "flagctl serve's exit on SIGTERM"
expect 1 "a key that does not match the certificate" "$flagctl" --prefix $prefix serve --listen 127.0.0.1:0 \
  --tls-cert "$work/tls/gateway.crt" --tls-key "$work/other-tls/gateway.key"
contains "does not match the certificate" "  says so, naming the files"
expect 2 "a certificate without its key" "$flagctl" --prefix $prefix serve --listen 127.0.0.1:0 \
  --tls-cert "$work/tls/gateway.crt"
contains "give --tls-cert and --tls-key together" "  says what to give"

echo "-- a live server and its gateway"
"$flagd" --prefix $prefix --log-level warn >"$work/flagd.log" 2>&1 &
server=$!
echo $server >"$work/flagd.pid"  # the browser test stops this flagd and starts another
for _ in $(seq 50); do
  "$flagctl" --prefix $prefix --timeout 0.5 status >/dev/null 2>&1 && break
  sleep 0.2
done
"$flagctl" --prefix $prefix serve --listen 127.0.0.1:0 --token "$token" --record-dir "$work/rec" \
  >"$work/serve.log" 2>&1 &
gateway=$!
port=$(gateway_port "$work/serve.log")
pass "flagctl serve listens (port $port)"

run_node() {  # run_node DESCRIPTION SCRIPT ARGS...: a Node test; its checks are counted as one
  local what=$1
  shift
  local start=$SECONDS
  if node "$tests/$1" "${@:2}" >"$work/node.out" 2>&1; then
    sed 's/^/      /' "$work/node.out"
    pass "$what ($((SECONDS - start)) s)"
  else
    fail "$what ($((SECONDS - start)) s)" "$work/node.out"
  fi
}
run_node "the gateway's doors: token, origin, hostile clients" access_test.mjs "http://127.0.0.1:$port" "$token"
run_node "Foxglove's own client: channels, image, status, parameters, a service" \
  foxglove_client_test.mjs "ws://127.0.0.1:$port/?token=$token"
run_node "Chromium on the page: picture, camera, parameters, keyboard, timeline, clock, recording, phone, restart" \
  browser_test.mjs "http://127.0.0.1:$port/?token=$token" "$flagctl" $prefix "$shots" "$flagd" "$work/flagd.pid"
server=$(cat "$work/flagd.pid")

kill -TERM "$gateway"
if wait "$gateway"; then pass "the gateway stops cleanly"; else fail "the gateway's exit" "$work/serve.log"; fi
gateway=""
if kill -0 "$server" 2>/dev/null; then pass "flagd (started again by the browser test) runs on"; else fail "flagd died" "$shots/flagd-restarted.log"; fi
finish
