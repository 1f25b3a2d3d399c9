#!/usr/bin/env bash
# One gateway for two servers, over udpm:// inside a private network namespace (ctest runs this
# through scripts/netns-run): flagd with prefix ALPHA_ and flagd with BETA_ (small frames, 10 a
# second, since both share this machine's cores; BETA_ with a design of its own), then
# flagctl serve (no --prefix: every server heard), and Chromium on its page steering ALPHA_ with BETA_ beside it
# (servers_test.mjs). The page's screenshot stays in BUILD_DIR/tests/live_view/servers.png.
# Usage: servers_view_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
tests=$(cd "$(dirname "$0")/../web" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
work=$(mktemp -d)
shots=$build/tests/live_view
mkdir -p "$shots"
alpha="" gateway=""
cleanup() {
  [[ -n $gateway ]] && kill "$gateway" 2>/dev/null || true
  [[ -n $alpha ]] && kill "$alpha" 2>/dev/null || true
  [[ -f $work/beta.pid ]] && kill "$(cat "$work/beta.pid")" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

source "$(dirname "$0")/checks.sh"


echo "-- two servers"
"$flagd" --prefix ALPHA_ --set frame_rate=10 --log-level warn >"$work/ALPHA_.log" 2>&1 &
alpha=$!
# BETA_'s command line is servers_test.mjs's too: it stops this flagd and starts another.
"$flagd" --prefix BETA_ --set frame_rate=10 --set design=tricolour --log-level warn >"$work/BETA_.log" 2>&1 &
echo $! >"$work/beta.pid"
for prefix in ALPHA_ BETA_; do
  if await_server "$flagctl" $prefix; then pass "$prefix answers"; else fail "no STATUS of $prefix" "$work/$prefix.log"; finish; fi
  # Small pictures: two servers and a browser share this machine's cores.
  expect 0 "  its camera at 320 x 180" "$flagctl" --prefix $prefix --timeout 10 camera size 320 180
done

echo "-- one gateway for both: flagctl serve without --prefix serves every server it hears"
"$flagctl" serve --listen 127.0.0.1:0 >"$work/serve.log" 2>&1 &
gateway=$!
url=$(gateway_url "$work/serve.log")
pass "flagctl serve listens ($url)"
if grep -q "servers every server heard" "$work/serve.log"; then pass "  for every server heard"
else fail "  not for every server heard" "$work/serve.log"; fi

start=$SECONDS
if node "$tests/servers_test.mjs" "$url" "$flagctl" "$shots" "$flagd" "$work/beta.pid" >"$work/node.out" 2>&1; then
  sed 's/^/      /' "$work/node.out"
  pass "Chromium on the page: ALPHA_ steered, BETA_ beside, the list, commands, a server gone and back ($((SECONDS - start)) s)"
else
  fail "Chromium on the page ($((SECONDS - start)) s)" "$work/node.out"
fi

kill -TERM "$gateway"
if wait "$gateway"; then pass "the gateway stops cleanly"; else fail "the gateway's exit" "$work/serve.log"; fi
gateway=""
finish
