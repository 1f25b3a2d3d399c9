#!/usr/bin/env bash
# Under datagram loss (ctest runs this through scripts/netns-run --loss 10): commands are retried
# until answered, a client assembles a complete, hash-checked frame within a bounded time, and
# an image sent as the design in pieces arrives whole.
# Usage: loss_test.sh BUILD_DIR
set -euo pipefail
build=$1
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
work=$(mktemp -d)
"$build/server/flagd" --log-level warn >"$work/flagd.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null || true; rm -rf "$work"' EXIT

source "$(dirname "$0")/checks.sh"
await_server "$build/client/flagctl" FLAGSIM_ || fail "no status from the server despite retries"
for i in 1 2 3; do
  expect 0 "command $i answered despite loss" "$build/client/flagctl" --timeout 5 wind $((4 + i)) 0 1
done
for i in 1 2 3; do
  start=$(date +%s%N)
  expect 0 "snapshot $i complete within 15 s despite loss" "$build/client/flagctl" --timeout 15 snapshot -o "$work/frame.png"
  echo "      took $(( ($(date +%s%N) - start) / 1000000 )) ms"
done
# An image of some 700 KB (noise does not compress) as the flag's design: 15 pieces.
"$build/tests/noise_png" 420 420 "$work/noise.png"
bytes=$(stat -c %s "$work/noise.png")
expect 0 "a $bytes-byte image sent as the design, $(( (bytes + 49151) / 49152 )) pieces, arrives whole despite loss" \
  "$build/client/flagctl" --timeout 10 design "$work/noise.png"
contains "design noise.png (420 x 420 px)" "  the server's answer names it, as it decoded it"
expect 0 "PARAMS asked for despite loss" "$build/client/flagctl" --timeout 10 params
matches "^design +image" "  they say design image"
finish
