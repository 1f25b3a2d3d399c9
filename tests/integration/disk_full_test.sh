#!/usr/bin/env bash
# A disk that fills under each recorder: small tmpfs disks, mounted in a private mount namespace,
# over udpm:// inside a private network namespace (ctest runs this through scripts/netns-run).
# Each recorder ends its recording with a message that says the disk is full, how much the log
# holds and that it is whole (its size checked against the message); the log reads to its end
# (export, replay); and the server and the stream go on:
#   flagd --record-inputs   its record fills while it takes commands and keyframe requests; it
#                           keeps stepping and answering, and its record replays
#   flagctl record          exits 1 with the message; its log exports and replays
#   flagctl serve           the gateway's recorder (started with tests/web/record_call.mjs)
#                           stops and says why, on stderr and in the record service's answer;
#                           the gateway goes on answering; its log exports and replays
# Exits 77 (skipped) where a mount namespace or a tmpfs mount is not allowed.
# Usage: disk_full_test.sh BUILD_DIR
set -euo pipefail
if [[ ${FLAGSIM_MOUNT_NAMESPACE:-} != 1 ]]; then
  if ! unshare --mount --propagation private true 2>/dev/null; then
    echo "disk_full_test: cannot make a private mount namespace here: skipped"
    exit 77
  fi
  FLAGSIM_MOUNT_NAMESPACE=1 exec unshare --mount --propagation private -- "$0" "$@"
fi
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
web_tests=$(cd "$(dirname "$0")/../web" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=FULL_
work=$(mktemp -d)
server="" gateway=""
cleanup() {
  for pid in $gateway $server; do kill "$pid" 2>/dev/null || true; done
  umount "$work"/disk-* 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
source "$(dirname "$0")/checks.sh"
source "$(dirname "$0")/log_checks.sh"
ctl() { "$flagctl" --prefix $prefix --timeout 3 "$@"; }

# disk NAME SIZE: a tmpfs of SIZE bytes at $work/disk-NAME, seen by this test alone.
disk() {
  mkdir -p "$work/disk-$1"
  if ! mount -t tmpfs -o "size=$2" flagsim-test "$work/disk-$1" 2>"$work/mount.err"; then
    echo "disk_full_test: cannot mount a tmpfs here ($(cat "$work/mount.err")): skipped"
    exit 77
  fi
}
# holds_what_it_says LOG: the size the message in $work/out gives is LOG's.
holds_what_it_says() {
  local said
  said=$(sed -n 's/.*the log holds its first [0-9]* events, \([0-9]*\) bytes, every one whole.*/\1/p' "$work/out" | head -1)
  if [[ $said == "$(stat -c %s "$1")" ]]; then pass "  the log is the $said bytes the message says"
  else fail "  the message says '$said' bytes, the log has $(stat -c %s "$1")" "$work/out"; fi
}

disk inputs $((256 << 10))
disk record $((4 << 20))
disk gateway $((4 << 20))

echo "-- flagd --record-inputs: its record fills"
"$flagd" --prefix $prefix --log-level warn --record-inputs "$work/disk-inputs/inputs.lcmlog" >"$work/flagd.log" 2>&1 &
server=$!
await_server "$flagctl" $prefix || { fail "flagd answers" "$work/flagd.log"; finish; }
expect 0 "wind" ctl wind 6 0 1
for _ in $(seq 100); do  # each keyframe request writes a checkpoint into the record
  grep -q "recording inputs:" "$work/flagd.log" && break
  ctl refresh >/dev/null 2>&1 || true
done
cp "$work/flagd.log" "$work/out"
contains "the disk is full" "the server says its record stopped: the disk is full"
contains "every one whole; the server goes on" "  that the record is whole and the server goes on"
holds_what_it_says "$work/disk-inputs/inputs.lcmlog"
expect 0 "the server goes on answering: a full state now" ctl refresh
step=$(sed -n 's/^step \([0-9]*\) .*/\1/p' "$work/out")
expect 0 "  and taking commands" ctl set stiffness=2500
if await_step "$step"; then pass "  and stepping (past step $step, after the disk filled)"
else fail "  its step stays at $step"; fi
expect 0 "flagd replay of its record" "$flagd" replay "$work/disk-inputs/inputs.lcmlog" --prefix $prefix
contains "every hash equal" "  every checkpoint hash equal"

echo "-- flagctl record: its disk fills"
expect 1 "flagctl record stops" ctl record -o "$work/disk-record/run.lcmlog" --duration 120
contains "recording stopped after" "  says it stopped"
contains "the disk is full (No space left on device)" "  because the disk is full"
holds_what_it_says "$work/disk-record/run.lcmlog"
expect 0 "the server goes on" ctl status
expect 0 "the stream goes on: a snapshot" ctl snapshot -o "$work/after-record.png"
log_reads "$work/disk-record/run.lcmlog" "the log"

echo "-- the gateway's recorder: its disk fills"
if ! node -e 'process.exit(0)' 2>/dev/null || [[ ! -d $web_tests/node_modules/@foxglove ]]; then
  echo "      (no Node or no tests/web/node_modules: the gateway's part skipped)"
  finish
  exit
fi
token=$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
"$flagctl" --prefix $prefix serve --listen 127.0.0.1:0 --token "$token" --record-dir "$work/disk-gateway" \
  >"$work/serve.log" 2>&1 &
gateway=$!
url="ws://127.0.0.1:$(gateway_port "$work/serve.log")/?token=$token"
expect 0 "/flag/record start" node "$web_tests/record_call.mjs" "$url" start
log=$work/disk-gateway/$(sed -n 's/.*"file":"\([^"]*\)".*/\1/p' "$work/out")
for _ in $(seq 120); do  # the page polls the same way
  node "$web_tests/record_call.mjs" "$url" status >"$work/status.json" 2>&1 || true
  grep -q '"recording":false' "$work/status.json" && break
  sleep 0.5
done
cp "$work/status.json" "$work/out"
contains '"recording":false' "the recording stopped on its own"
contains "the disk is full (No space left on device)" "  the record service says the disk is full"
holds_what_it_says "$log"
cp "$work/serve.log" "$work/out"
contains "flagctl serve: recording stopped: writing $log stopped: the disk is full" "  and so does the gateway's stderr"
expect 0 "the gateway goes on answering" node "$web_tests/record_call.mjs" "$url" status
expect 0 "the server and the stream go on: a snapshot" ctl snapshot -o "$work/after-gateway.png"
log_reads "$log" "the gateway's log"
finish
