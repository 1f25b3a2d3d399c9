#!/usr/bin/env bash
# The main job on its embedded defaults: installs what is missing, builds, starts flagd on the
# default scene, and drives it with a short flagctl session that leaves a picture and a log.
#   scripts/demo.sh   -> out/flag.png, out/flag-orbit.png, out/session.lcmlog, out/params.txt, out/status.txt
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh --target flagd --target flagctl  # the two binaries, not the tests and benchmarks
mkdir -p out

# The session itself, run where multicast stays private when possible (a network namespace of
# its own), else on this host's loopback with TTL 0, which never leaves the machine.
session() {
  set -euo pipefail
  local flagd=build/server/flagd flagctl=build/client/flagctl
  "$flagd" --log-level warn &
  demo_server=$!
  trap 'kill $demo_server 2>/dev/null || true' EXIT
  for _ in $(seq 50); do "$flagctl" --timeout 0.5 status >/dev/null 2>&1 && break; sleep 0.2; done
  echo "== flagd is up; the flag in a breeze, then a gust front, then a stiffer cloth"
  "$flagctl" record -o out/session.lcmlog --duration 6 &
  local recorder=$!
  "$flagctl" watch --duration 2
  "$flagctl" wind 12 0 3 --gust 0.4 --ramp 1
  "$flagctl" set stiffness=3000 damping=0.08
  "$flagctl" watch --duration 3
  wait $recorder
  "$flagctl" --timeout 5 snapshot -o out/flag.png
  "$flagctl" camera orbit -35 8
  "$flagctl" --timeout 5 snapshot -o out/flag-orbit.png
  "$flagctl" params >out/params.txt
  "$flagctl" status | tee out/status.txt
  kill -TERM $demo_server
  wait $demo_server
}
export -f session
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
code=0
scripts/netns-run -- bash -c session || code=$?
if [[ $code == 77 ]]; then
  echo "demo: no private network namespace here; running on this host's loopback (TTL 0)"
  bash -c session
elif [[ $code != 0 ]]; then
  exit $code
fi
echo "== left in out/: $(ls out | tr '\n' ' ')"
echo "   play the log back with: lcm-logplayer out/session.lcmlog   (and flagctl watch in another terminal)"
echo "   watch and steer the flag live in a browser: scripts/live.sh, then open the URL it prints"
echo "   (http://127.0.0.1:8080/; Foxglove and Lichtblick connect to ws://127.0.0.1:8080/)"
