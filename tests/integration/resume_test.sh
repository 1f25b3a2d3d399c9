#!/usr/bin/env bash
# A server killed outright (SIGKILL) mid-session, recording its own inputs, and started again
# from that record: over udpm:// inside a private network namespace (ctest runs this through
# scripts/netns-run). The killed server's log replays (flagd replay, every checkpoint hash
# equal); `flagd --resume` starts from its last checkpoint with that checkpoint's state hash
# (as the replay found it), says what came after it and is lost (the commands counted from
# their ACKs' steps), and serves commands; its own new record replays from where it resumed.
# Usage: resume_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=RESUME_
work=$(mktemp -d)
server=""
cleanup() {
  [[ -n $server ]] && kill "$server" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
source "$(dirname "$0")/checks.sh"
source "$(dirname "$0")/log_checks.sh"
ctl() { "$flagctl" --prefix $prefix --timeout 3 "$@"; }
commands=()  # the step each accepted command took effect at, from its ACK
send() {
  expect 0 "$1" ctl "${@:2}"
  commands+=("$(sed -n 's/^accepted at step \([0-9]*\)$/\1/p' "$work/out")")
}
small=(--set cols=16 --set rows=12 --set frame_rate=10)

echo "-- a session, recording its inputs"
"$flagd" --prefix $prefix --log-level warn --record-inputs "$work/inputs.lcmlog" "${small[@]}" \
  >"$work/flagd.log" 2>&1 &
server=$!
await_server "$flagctl" $prefix || { fail "flagd answers" "$work/flagd.log"; finish; }
send "wind" wind 7 0 2 --ramp 0.5
send "parameters" set stiffness=2500
# Past the first periodic checkpoint (step 2500, 5 s): a command after it is lost in the kill.
if await_step 2500; then pass "the server steps past its periodic checkpoint at step 2500"
else fail "the server's step: $(status_step)"; fi
send "a command after the checkpoint" set damping=0.08
kill -KILL $server
code=0
{ wait $server; } 2>/dev/null || code=$?  # no "Killed" from the shell
server=""
if ((code == 137)); then pass "flagd is killed (SIGKILL)"; else fail "flagd's exit: $code" "$work/flagd.log"; fi

echo "-- the killed server's record"
expect 0 "flagd replay of it" "$flagd" replay "$work/inputs.lcmlog" --prefix $prefix
contains "every hash equal" "  every checkpoint hash equal"
checkpoint_step=$(sed -n 's/.*the last checked: step \([0-9]*\), state hash.*/\1/p' "$work/out")
checkpoint_hash=$(sed -n 's/.*the last checked: step [0-9]*, state hash \([0-9a-f]*\).*/\1/p' "$work/out")
if [[ -n $checkpoint_step ]] && ((checkpoint_step >= 2500)); then
  pass "  its last checkpoint: step $checkpoint_step, state hash $checkpoint_hash"
else fail "  no checkpoint at or past step 2500 checked" "$work/out"; fi
expect 5 "flagctl export of it: an inputs log holds no frames" "$flagctl" --prefix $prefix export "$work/inputs.lcmlog" \
  -o "$work/frames/"
contains "holds no complete frame" "  and says so"

echo "-- resumed from it"
lost=0
for step in "${commands[@]}"; do ((step >= checkpoint_step)) && lost=$((lost + 1)); done
"$flagd" --prefix $prefix --log-level warn --resume "$work/inputs.lcmlog" --record-inputs "$work/resumed.lcmlog" \
  >"$work/resumed.log" 2>&1 &
server=$!
await_server "$flagctl" $prefix || { fail "the resumed flagd answers" "$work/resumed.log"; finish; }
cp "$work/resumed.log" "$work/out"
sed "s/^/      /" "$work/out"
contains "state hash $checkpoint_hash, equal to the checkpoint's" "  with the checkpoint's state hash"
matches "checkpoint at step $checkpoint_step \(t = [0-9.]+ s\)" "  at the checkpoint's step"
contains " $lost command(s) are lost" "  $lost command(s) after the checkpoint said lost"
lost_to=$(sed -n 's/.*the log goes on to step \([0-9]*\) .*/\1/p' "$work/out")
if [[ -n $lost_to ]] && ((lost_to >= ${commands[2]})); then pass "  the loss runs to step $lost_to, past the last command"
else fail "  where the loss ends: '$lost_to'" "$work/out"; fi
send "the resumed server takes commands" set stiffness=3000
if ((${commands[3]} >= checkpoint_step)); then pass "  at step ${commands[3]}, on from the checkpoint"
else fail "  at step ${commands[3]}, before the checkpoint at $checkpoint_step"; fi
if await_step "${commands[3]}"; then pass "  and steps on"; else fail "  the step: $(status_step)"; fi
kill -TERM $server
expect 0 "the resumed server stops on SIGTERM" wait $server
server=""
expect 0 "flagd replay of the resumed server's record" "$flagd" replay "$work/resumed.lcmlog" --prefix $prefix
contains "resumed at step $checkpoint_step (resume checkpoint)" "  from its resume checkpoint"
contains "the first checkpoint's state hash $checkpoint_hash" "  whose state hash is the killed server's"
contains "every hash equal" "  every checkpoint hash equal"

echo "-- what --resume refuses"
expect 2 "recording into the log it reads" "$flagd" --resume "$work/inputs.lcmlog" --record-inputs "$work/inputs.lcmlog"
contains "is the log --resume reads" "  says so"
expect 2 "with flagd replay" "$flagd" --resume "$work/inputs.lcmlog" replay "$work/inputs.lcmlog"
contains "does not go with render or replay" "  says so"
expect 2 "with another scene" "$flagd" --resume "$work/inputs.lcmlog" --scene gale
contains "excludes" "  says the two exclude each other"
: >"$work/empty.lcmlog"
expect 2 "a log without a checkpoint" "$flagd" --resume "$work/empty.lcmlog"
contains "no whole CHECKPOINT" "  says so"
echo 'name = "gale"' >"$work/scene.lcmlog"
expect 2 "a file that is not a log" "$flagd" --resume "$work/scene.lcmlog"
contains "scene.lcmlog: at byte 0, event 0: not an LCM event log" "  says so, in the reader's words"
expect 2 "a log that does not exist" "$flagd" --resume "$work/none.lcmlog"
finish
