#!/usr/bin/env bash
# A live session recorded and replayed: flagd over udpm:// inside a private network namespace
# (ctest runs this through scripts/netns-run) takes wind, parameter, keyframe, camera and
# refresh commands while two flagctl recorders run, one from the start and one from
# mid-session, and flagd records its own inputs; flagd replay then steps each log again and
# checks every state hash (the inputs log: every checkpoint's), at 1 and 2 threads, and a copy of
# a log cut mid-event replays up to where it ends. Velocity Verlet carries
# forces between substeps, so a checkpoint that did not carry them would show.
# Usage: replay_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=REPLAY_
work=$(mktemp -d)
server="" full="" mid=""
cleanup() {
  for pid in $server $full $mid; do kill "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
source "$(dirname "$0")/checks.sh"
ctl() { "$flagctl" --prefix $prefix --timeout 3 "$@"; }

"$flagd" --prefix $prefix --log-level warn --record-inputs "$work/inputs.lcmlog" --set cols=16 --set rows=12 --set threads=2 --set frame_rate=10 --set integrator=verlet &
server=$!
await_server "$flagctl" $prefix || fail "no status from the server"
# The full recording runs until SIGINT, after the last command: however long the session takes
# on this machine, it holds all of it.
"$flagctl" --prefix $prefix record -o "$work/full.lcmlog" >"$work/full.out" 2>&1 &  # $!: flagctl's own
full=$!
await_bytes "$work/full.lcmlog" 10000 || fail "the full recording did not start" "$work/full.out"

echo "-- a session: every kind of command, while recording"
expect 0 "wind with a ramp" ctl wind 8 0 3 --ramp 0.5
expect 0 "set stiffness and damping" ctl set stiffness=3000 damping=0.08
expect 0 "keyframe at 0 s" ctl keyframe add 0 --wind 4 0 1
expect 0 "keyframe at 2 s, smooth" ctl keyframe add 2 --wind -3 1 4 --set stiffness=2500 --law smooth
expect 0 "keyframe loop on: it plays until paused" ctl keyframe loop on
expect 0 "keyframe play" ctl keyframe play
expect 0 "camera orbit" ctl camera orbit 20 5
ctl record -o "$work/mid.lcmlog" --duration 4 >"$work/mid.out" 2>&1 &
mid=$!
await_bytes "$work/mid.lcmlog" 10000 || fail "the later recording did not start" "$work/mid.out"
expect 0 "set friction during play" ctl set friction=0.3
expect 0 "refresh" ctl refresh
expect 0 "keyframe change during play (a glide)" ctl keyframe change 2 --wind 2 2 2
expect 0 "keyframe pause" ctl keyframe pause
expect 0 "reset to the scene" ctl reset
# What the bus carried after the reset reaches the recorder before it stops.
await_bytes "$work/full.lcmlog" $(($(stat -c %s "$work/full.lcmlog") + 10000)) ||
  fail "the full recording did not grow after the reset" "$work/full.out"
kill -INT $full
wait $full || fail "the full recording" "$work/full.out"
wait $mid || fail "the later recording" "$work/mid.out"
full="" mid=""
kill $server  # it stops cleanly: the end checkpoint, and its inputs log closed
expect 0 "flagd stops on SIGTERM" wait $server
server=""  # the replays below have the machine to themselves

echo "-- replayed from the start"
expect 0 "flagd replay, 1 thread" "$flagd" replay "$work/full.lcmlog" --prefix $prefix --threads 1
contains "every hash equal" "  every recorded hash equal"
matches "resumed at step [0-9]+ \((start|refresh) checkpoint\)" "  from the log's first checkpoint"
matches " 11 command\(s\) and [0-9]+ switch\(es\) of auto.s model applied" "  with the session's eleven commands (a refresh changes nothing)"
expect 0 "flagd replay, 2 threads" "$flagd" replay "$work/full.lcmlog" --prefix $prefix --threads 2
contains "every hash equal" "  every recorded hash equal"

echo "-- recorded from mid-session"
expect 0 "flagd replay of the later recording" "$flagd" replay "$work/mid.lcmlog" --prefix $prefix
contains "refresh checkpoint" "  resumes at the checkpoint its recorder asked for"
contains "every hash equal" "  every recorded hash equal"

echo "-- the server's own record of its inputs (--record-inputs)"
expect 0 "flagd replay of the inputs log" "$flagd" replay "$work/inputs.lcmlog" --prefix $prefix
contains "resumed at step 0 (start checkpoint)" "  from the session's start"
matches " ([89]|[1-9][0-9]+) command\(s\) and [0-9]+ switch\(es\) of auto.s model applied, 0 state and [1-9][0-9]* checkpoint" \
  "  with the session's commands, checked at its checkpoints"
contains "every hash equal" "  every checkpoint hash equal"

echo "-- a log cut mid-event"
size=$(stat -c %s "$work/full.lcmlog")
head -c $((size * 2 / 3 + 7)) "$work/full.lcmlog" >"$work/cut.lcmlog"
expect 0 "flagd replay of a cut log" "$flagd" replay "$work/cut.lcmlog" --prefix $prefix
contains "the log ends early" "  says where it ends"
contains "every hash equal" "  and what it holds replays"

echo "-- nothing to replay"
expect 2 "flagd replay with another prefix" "$flagd" replay "$work/full.lcmlog" --prefix OTHER_
contains "no whole CHECKPOINT" "  says there is no checkpoint"
echo 'name = "gale"' >"$work/scene.lcmlog"
expect 2 "flagd replay of a file that is not a log" "$flagd" replay "$work/scene.lcmlog"
contains "scene.lcmlog: at byte 0, event 0: not an LCM event log" "  says so, in the reader's words"
expect 2 "flagd replay of a missing file" "$flagd" replay "$work/none.lcmlog"
expect 2 "flagd replay without a log" "$flagd" replay
finish
