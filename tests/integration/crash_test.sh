#!/usr/bin/env bash
# A recorder killed outright (SIGKILL) in the middle of a live session leaves a log that reads to
# its last whole event: flagctl export makes frames of it and flagd replay steps it again, every
# hash equal. Over udpm:// inside a private network namespace (ctest runs this through
# scripts/netns-run), with real processes:
#   record  `flagctl record`
#   serve   the gateway's recorder: `flagctl serve`, its recording started with Foxglove's own
#           protocol client (tests/web/record_call.mjs), and the gateway killed
# (flagd --record-inputs killed mid-session: resume_test.sh.)
# Usage: crash_test.sh BUILD_DIR record|serve
set -euo pipefail
build=$1
mode=$2
flagd=$build/server/flagd
flagctl=$build/client/flagctl
web_tests=$(cd "$(dirname "$0")/../web" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=CRASH_
work=$(mktemp -d)
server="" recorder=""
cleanup() {
  for pid in $recorder $server; do kill "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
source "$(dirname "$0")/checks.sh"
source "$(dirname "$0")/log_checks.sh"
ctl() { "$flagctl" --prefix $prefix --timeout 3 "$@"; }

# A second of the bus is about 2.6 MB with the default frames: 4 MB holds the checkpoint and the
# keyframe the recorder asked for, with room to spare, and the commands.
recorded_enough=4000000

"$flagd" --prefix $prefix --log-level warn >"$work/flagd.log" 2>&1 &
server=$!
await_server "$flagctl" $prefix || { fail "flagd answers" "$work/flagd.log"; finish; }

case $mode in
  record)
    echo "-- flagctl record, killed"
    # flagctl itself in the background, not the ctl function: $! must be the recorder's pid, not
    # a subshell's whose death would leave the recorder running.
    "$flagctl" --prefix $prefix --timeout 3 record -o "$work/run.lcmlog" >"$work/record.out" 2>&1 &
    recorder=$!
    log=$work/run.lcmlog
    ;;
  serve)
    echo "-- the gateway's recorder (flagctl serve), killed"
    token=$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
    "$flagctl" --prefix $prefix serve --listen 127.0.0.1:0 --token "$token" --record-dir "$work/recordings" \
      >"$work/serve.log" 2>&1 &
    recorder=$!
    port=$(gateway_port "$work/serve.log")
    expect 0 "/flag/record start" node "$web_tests/record_call.mjs" "ws://127.0.0.1:$port/?token=$token" start
    matches '"recording":true' "  a recording runs"
    log=$work/recordings/$(sed -n 's/.*"file":"\([^"]*\)".*/\1/p' "$work/out")
    ;;
  *)
    echo "usage: crash_test.sh BUILD_DIR record|serve" >&2
    exit 2
    ;;
esac
expect 0 "wind while recording" ctl wind 7 0 2 --ramp 0.5
expect 0 "parameters while recording" ctl set stiffness=2500 damping=0.08
if await_bytes "$log" $recorded_enough; then pass "the log grows past $recorded_enough bytes"
else fail "the log holds $(stat -c %s "$log" 2>/dev/null || echo no) bytes"; fi
kill -KILL $recorder
code=0
{ wait $recorder; } 2>/dev/null || code=$?  # no "Killed" from the shell
recorder=""
if ((code == 137)); then pass "the recorder is killed (SIGKILL)"; else fail "the recorder's exit: $code"; fi

echo "-- the killed recorder's log"
expect 0 "the server goes on" ctl set damping=0.05
log_reads "$log" "the log"
finish
