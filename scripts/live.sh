#!/usr/bin/env bash
# The live view in one command: installs what is missing, builds, starts flagd and its gateway
# (flagctl serve) on this machine, and prints the URL to open in a browser (or in Foxglove).
# Ctrl-C stops both.
#   scripts/live.sh                      the default scene
#   scripts/live.sh --scene gale         flagd's options go to flagd
#   FLAGSIM_LISTEN=0.0.0.0:8080 scripts/live.sh   beyond loopback: a token is generated and printed
# LCM runs on this host's multicast with TTL 0 (LCM_DEFAULT_URL, if set, wins): nothing leaves it.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh --target flagd --target flagctl  # the two binaries, not the tests and benchmarks
export LCM_DEFAULT_URL="${LCM_DEFAULT_URL:-udpm://239.255.76.67:7667?ttl=0}"
build/server/flagd --log-level warn "$@" &
server=$!
gateway=""
trap 'kill $server $gateway 2>/dev/null || true; wait' EXIT
build/client/flagctl serve --listen "${FLAGSIM_LISTEN:-127.0.0.1:8080}" &
gateway=$!
wait $gateway
