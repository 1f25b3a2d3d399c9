#!/usr/bin/env bash
# The command line's contract, as a new user meets it: exit codes (0 ok, 1 a file or ffmpeg
# failed, 2 usage, 3 rejected, 4 no answer, 5 nothing to export), messages that name what was
# wrong in the units typed, help that says what each subcommand does, logs on stderr, and the
# tables (params, status, keyframe list) answered at once. flagd and flagctl over udpm://,
# inside a private network namespace (ctest runs this through scripts/netns-run).
# Usage: cli_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
scenes=$(cd "$(dirname "$0")/../../scenes" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=CLI_
work=$(mktemp -d)
server=""
cleanup() {
  [[ -n $server ]] && kill "$server" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

source "$(dirname "$0")/checks.sh"
lacks() {  # lacks TEXT DESCRIPTION: the last command's output does not have TEXT
  if grep -qF -- "$1" "$work/out"; then fail "$2: '$1' in:" "$work/out"; else pass "$2"; fi
}

echo "-- the command line"
expect 2 "an unknown subcommand is a usage error" "$flagctl" bogus
contains "'bogus' is not a subcommand" "  that names the word"
contains "wind, set, reset" "  and lists the subcommands"
expect 2 "an unknown camera move is a usage error" "$flagctl" camera spin 3
contains "'spin' is not a subcommand of camera" "  that names the word"
expect 2 "camera without a move is a usage error" "$flagctl" camera
contains "camera needs a subcommand; allowed: rotate-x, rotate-y" "  that lists the moves"
expect 2 "--timeout 0 is a usage error" "$flagctl" --timeout 0 status
contains "--timeout: 0 is out of range; allowed above 0" "  with the bound as typed"
if [[ $(wc -c <"$work/out") -lt 200 ]]; then pass "  in a short message"; else fail "  a long message" "$work/out"; fi
expect 2 "flagctl --prefix with a '-' is a usage error" "$flagctl" --prefix my-prefix status
contains "--prefix: 'my-prefix' is not a channel prefix; allowed 1 .. 52 letters, digits and '_'" \
  "  that names the prefix and what is allowed"
expect 2 "an empty flagctl --prefix is a usage error" "$flagctl" --prefix "" status
contains "--prefix: '' is 0 characters; allowed 1 .. 52" "  that says so"
expect 2 "flagd --prefix with a space is a usage error" "$flagd" --prefix "A B" --duration 0.01
contains "--prefix: 'A B' is not a channel prefix" "  that names the prefix"
expect 2 "serve --listen with a port that is not all digits is a usage error" "$flagctl" --prefix NOBODY_ \
  serve --listen 127.0.0.1:80x
contains "the port '80x' is not one; allowed 0 .. 65535 in digits" "  that names the port and what is allowed"
expect 2 "serve --servers with a prefix that is none is a usage error" "$flagctl" serve --servers ALPHA_,my-prefix \
  --listen 127.0.0.1:0
contains "--servers my-prefix: 'my-prefix' is not a channel prefix; allowed 1 .. 52 letters, digits and '_', or all" \
  "  that names it and what is allowed"
expect 4 "flagctl servers with no server on the bus" "$flagctl" --timeout 0.5 servers
contains "no server's STATUS on" "  says so"
expect 2 "watch --duration -1 is a usage error" "$flagctl" --prefix NOBODY_ watch --duration -1
contains "--duration: -1 is out of range; allowed 0 or more" "  with the bound as typed"
expect 2 "record --duration -1 is a usage error" "$flagctl" --prefix NOBODY_ record -o "$work/never.lcmlog" \
  --duration -1
contains "--duration: -1 is out of range; allowed 0 or more" "  with the bound as typed"
if [[ ! -e $work/never.lcmlog ]]; then pass "  and writes no log"; else fail "  a log was written"; fi
expect 0 "camera rotate-x --help" "$flagctl" camera rotate-x --help
if [[ $(head -n 1 "$work/out") == "turn the scene about the x axis through the target" ]]; then
  pass "  says first what the move does"
else fail "  does not start with what the move does" "$work/out"; fi
expect 0 "reset --help" "$flagctl" reset --help
contains "the camera stays" "  says that the camera stays"
expect 2 "a parameter set twice is a usage error" "$flagctl" --prefix NOBODY_ set stiffness=1500 stiffness=1600
contains "stiffness is set twice (stiffness=1500, stiffness=1600)" "  that names it"
expect 2 "a snapshot to a picture format it cannot write is a usage error" "$flagctl" --prefix NOBODY_ \
  snapshot -o "$work/x.bmp"
contains "allowed NAME.png or NAME.jpg" "  and names the formats"

echo "-- files"
expect 1 "record into a directory that is not there fails" "$flagctl" --prefix NOBODY_ --timeout 0.5 \
  record -o /nonexistent/x.lcmlog
contains "/nonexistent/x.lcmlog" "  naming the file"
expect 1 "snapshot into a directory that is not there fails before asking" "$flagctl" --prefix NOBODY_ \
  --timeout 30 snapshot -o /nonexistent/x.png
contains "flagctl snapshot: cannot write /nonexistent/x.png: there is no directory /nonexistent" \
  "  naming the file and why"
expect 1 "export of a log that is not there fails" "$flagctl" export /nonexistent.lcmlog -o "$work/out"
contains "cannot read /nonexistent.lcmlog" "  naming the log"

# Garbage on TILE and FRAME, and no server: snapshot waits its --timeout for a frame, then says
# how much it ignored (the spray goes on until snapshot has ended).
"$flagctl" --prefix GARBAGE_ --timeout 2 snapshot -o "$work/garbage.png" >"$work/garbage.out" 2>&1 &
snapshot=$!
while kill -0 $snapshot 2>/dev/null; do
  "$build/tests/lcm_spray" "$LCM_DEFAULT_URL" 4 GARBAGE_TILE GARBAGE_FRAME >/dev/null
done
code=0
wait $snapshot || code=$?
if [[ $code == 4 ]] && grep -Eq "flagctl snapshot: [1-9][0-9]* undecodable TILE or FRAME message\(s\) ignored" \
  "$work/garbage.out"; then
  pass "snapshot counts the TILE and FRAME messages it could not decode (exit $code)"
else fail "snapshot on garbage: exit $code" "$work/garbage.out"; fi

echo "-- flagd"
expect 2 "flagd render refuses a directory as the scene" "$flagd" render --scene "$scenes" --duration 0.1 \
  -o "$work/dir.lcmlog"
contains "is a directory" "  and says so"
expect 2 "flagd render --fps 0 is a usage error" "$flagd" render --duration 0.1 -o "$work/x.lcmlog" --fps 0
contains "--fps: 0 is out of range; a render draws frames, so allowed above 0 .. 120 Hz" "  with what is allowed"
"$flagd" --fast --duration 0.05 --log-level info >"$work/stdout" 2>"$work/stderr"
if [[ ! -s $work/stdout ]] && grep -q "scene 'breeze'" "$work/stderr"; then pass "flagd logs to stderr, not stdout"
else fail "flagd logs on stdout:" "$work/stdout"; fi

echo "-- a live server"
"$flagd" --prefix $prefix --log-level warn >"$work/flagd.log" 2>&1 &
server=$!
await_server "$flagctl" $prefix || fail "no status from the server"
# The tables come once a second; params, status and keyframe list ask for them with a question
# (a tables-only REFRESH) and print the first that comes. That the server answers a question at
# once, on its simulated clock, is ServerTest.AQuestionGetsTheTablesAndNoMoreThanTenTimesASecond;
# that the question goes out unsigned and is not refused, integration.signed_commands. Here: each
# prints its table.
expect 0 "params" "$flagctl" --prefix $prefix params
contains "stiffness" "  the parameter table"
expect 0 "keyframe list" "$flagctl" --prefix $prefix keyframe list
contains "key(s)" "  the timeline"
expect 3 "camera orbit by 1e9 degrees rejected" "$flagctl" --prefix $prefix camera orbit 1e9 0
contains "angle: 1e+09 degrees is out of range; allowed -360 .. 360 degrees" "  in degrees, as typed"
expect 0 "a snapshot as JPEG" "$flagctl" --prefix $prefix --timeout 5 snapshot -o "$work/frame.jpg"
if [[ $(head -c 3 "$work/frame.jpg" | od -An -tx1 | tr -d ' ') == ffd8ff ]]; then pass "  is JPEG data"
else fail "  $work/frame.jpg is not JPEG data"; fi
expect 0 "a key at 1 s" "$flagctl" --prefix $prefix keyframe add 1 --set stiffness=1500
expect 0 "seek past it" "$flagctl" --prefix $prefix keyframe seek 1.5
expect 0 "remove the last key" "$flagctl" --prefix $prefix keyframe remove 1
expect 0 "the timeline" "$flagctl" --prefix $prefix keyframe list
contains "paused at 0 s of 0 s" "  is back at 0, not past its end"
expect 3 "play with no keys is rejected" "$flagctl" --prefix $prefix keyframe play
contains "play with no keys" "  and says why"
expect 0 "the timeline" "$flagctl" --prefix $prefix keyframe list
contains "paused at 0 s of 0 s, speed 1, loop off, 0 key(s)" "  is still paused, not gliding"

echo "-- a camera size change mid-session, exported"
"$flagctl" --prefix $prefix record -o "$work/resized.lcmlog" >"$work/record.out" 2>&1 &
recorder=$!
# A keyframe and frames at the first size (a 1280 x 720 frame is tens of KB), then the change,
# then frames at the new size; the recorder stops on SIGINT.
await_bytes "$work/resized.lcmlog" 2000000 || fail "the recording did not grow" "$work/record.out"
expect 0 "camera size mid-session" "$flagctl" --prefix $prefix camera size 320 180
await_bytes "$work/resized.lcmlog" $(($(stat -c %s "$work/resized.lcmlog") + 1000000)) ||
  fail "the recording did not grow after the change" "$work/record.out"
kill -INT "$recorder"
wait "$recorder" || fail "the recording" "$work/record.out"
if command -v ffprobe >/dev/null; then
  expect 0 "export of the whole session into one MP4" "$flagctl" --prefix $prefix export "$work/resized.lcmlog" -o "$work/resized.mp4"
  matches "note: [1-9][0-9]* frame\(s\) of another size than the first \(1280 x 720\) scaled to fit it" \
    "  the frames after the change scaled to the first size"
  size=$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height -of csv=p=0 "$work/resized.mp4")
  if [[ $size == 1280,720 ]]; then pass "  one video at 1280 x 720"; else fail "  the video is $size"; fi
fi

finish
