#!/usr/bin/env bash
# flagd and flagctl as real processes over udpm://, inside a private network namespace
# (ctest runs this through scripts/netns-run). Usage: session_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
spray=$build/tests/lcm_spray
scenes=$(cd "$(dirname "$0")/../../scenes" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=ITEST_
work=$(mktemp -d)
server=""
second=""
watcher=""
cleanup() {
  [[ -n $watcher ]] && kill "$watcher" 2>/dev/null || true
  [[ -n $server ]] && kill "$server" 2>/dev/null || true
  [[ -n $second ]] && kill "$second" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

source "$(dirname "$0")/checks.sh"

echo "-- startup errors"
expect 2 "flagd rejects an unknown scene" "$flagd" --scene no-such-scene
contains "presets: breeze, calm, gale, hanging" "  and lists the presets"
expect 2 "flagd rejects --set stiffness=nan" "$flagd" --set stiffness=nan
contains "stiffness: 'nan' is not a finite number" "  and names the parameter"
expect 0 "flagd --help" "$flagd" --help
expect 0 "flagctl --help" "$flagctl" --help
expect 2 "flagctl without a subcommand" "$flagctl"
expect 2 "flagctl wind with two numbers" "$flagctl" wind 1 2
printf '[[timeline.keys]]\ntime = 0\nparameters = { cols = 40 }\n' >"$work/bad.toml"
expect 2 "flagd rejects a key that sets the grid" "$flagd" --scene "$work/bad.toml"
contains "timeline.keys[0].parameters.cols: cannot be animated" "  and names the key and field"
expect 0 "flagd plays the swing example's timeline" "$flagd" --prefix SWING_ --scene "$scenes/swing.toml" --fast \
  --duration 1 --log-level info
contains "scene 'swing'" "  from the scene file"

echo "-- a live server"
"$flagd" --prefix $prefix --log-level warn >"$work/flagd.log" 2>&1 &
server=$!
for _ in $(seq 50); do
  "$flagctl" --prefix $prefix --timeout 0.5 status >/dev/null 2>&1 && break
  sleep 0.2
done
expect 0 "status answers" "$flagctl" --prefix $prefix status
contains "symplectic_euler" "  and names the integrator"
contains "auto chooses integrator and grid" "  and what auto chooses"
expect 0 "wind accepted" "$flagctl" --prefix $prefix wind 8 -0.5 2 --gust 0.3 --ramp 1
contains "accepted at step" "  and says when it took effect"
expect 3 "wind with NaN rejected" "$flagctl" --prefix $prefix wind 8 nan 0
contains "velocity.y" "  with the field named"
expect 3 "wind over the speed limit rejected" "$flagctl" --prefix $prefix wind 100 0 0
expect 0 "set accepted" "$flagctl" --prefix $prefix set stiffness=1500 damping=0.08
expect 3 "set out of range rejected" "$flagctl" --prefix $prefix set stiffness=-3
contains "allowed 1 .. 1e+05 N/m" "  with the allowed range"
expect 3 "set of an unknown name rejected" "$flagctl" --prefix $prefix set colour=red
contains "unknown parameter 'colour'" "  with the name"
expect 2 "set without NAME=VALUE is a usage error" "$flagctl" --prefix $prefix set stiffness
expect 0 "params lists the table" "$flagctl" --prefix $prefix params
matches "^stiffness +1500 " "  with the new value"
expect 0 "refresh gets a full state" "$flagctl" --prefix $prefix refresh
matches "[0-9]+ x [0-9]+ nodes" "  of the whole flag, on the grid auto chose"
expect 4 "no answer on another prefix" "$flagctl" --prefix NOBODY_ --timeout 1 status

echo "-- frames"
expect 0 "snapshot writes a hash-checked frame" "$flagctl" --prefix $prefix --timeout 5 snapshot -o "$work/frame.png"
contains "1280 x 720" "  at the default size"
if [[ $(head -c 8 "$work/frame.png" | od -An -tx1 | tr -d ' ') == 89504e470d0a1a0a ]]; then
  passes=$((passes + 1)); echo "ok      and it is a PNG"
else failures=$((failures + 1)); echo "FAIL    $work/frame.png is not a PNG"; fi
expect 0 "camera orbit accepted" "$flagctl" --prefix $prefix camera orbit 20 5
expect 0 "camera orbit under the ground stops at it" "$flagctl" --prefix $prefix camera orbit 0 -60
expect 3 "camera eye under the ground rejected" "$flagctl" --prefix $prefix camera eye 1 -1 3
contains "vector: the eye would be at y = -1 m" "  saying where the eye would be"
expect 0 "camera eye accepted" "$flagctl" --prefix $prefix camera eye 2.6 1.9 4.4
expect 0 "camera zoom accepted" "$flagctl" --prefix $prefix camera zoom 2
expect 0 "camera scale without --about zooms" "$flagctl" --prefix $prefix camera scale 0.5
# Scaling the world 100 times about the origin would sink the eye (y / 100 < 0.05 m); a zoom of
# 100 only brings it near the target.
expect 3 "camera scale --about the origin that would sink the eye rejected" "$flagctl" --prefix $prefix \
  camera scale 100 --about 0 0 0
contains "factor: the eye would be at y = " "  naming the ground"
expect 0 "camera scale 100 without --about zooms, to 0.1 m from the target" "$flagctl" --prefix $prefix \
  camera scale 100
expect 3 "camera fov out of range rejected" "$flagctl" --prefix $prefix camera fov 200
contains "angle: 200 degrees is out of range; allowed 10 .. 120 degrees" "  in degrees"
expect 0 "camera fov accepted" "$flagctl" --prefix $prefix camera fov 50
expect 0 "camera reset accepted" "$flagctl" --prefix $prefix camera reset
expect 0 "camera rotate-x --help describes its argument" "$flagctl" camera rotate-x --help
matches "degrees +FLOAT REQUIRED +[a-z]" "  with a description"
expect 0 "camera size accepted" "$flagctl" --prefix $prefix camera size 320 180
expect 3 "camera size too large rejected" "$flagctl" --prefix $prefix camera size 9000 100
contains "width: 9000 is out of range" "  with the field named"
expect 0 "snapshot follows the new size" "$flagctl" --prefix $prefix --timeout 5 snapshot -o "$work/small.png"
contains "320 x 180" "  at 320 x 180"
# watch until its line a second reports frames (it stops on SIGINT).
"$flagctl" --prefix $prefix --timeout 30 watch >"$work/watch.out" 2>&1 &
watcher=$!
if await_text "$work/watch.out" "FRAME +[0-9.]+ Hz"; then pass "watch reports frames with their rate"
else fail "watch reported no frames" "$work/watch.out"; fi
kill -INT $watcher
wait $watcher || fail "watch on SIGINT" "$work/watch.out"
watcher=""
expect 0 "frames can be turned off" "$flagctl" --prefix $prefix set frame_rate=0
expect 0 "and a snapshot still gets one" "$flagctl" --prefix $prefix --timeout 5 snapshot -o "$work/asked.png"
expect 0 "frames back on" "$flagctl" --prefix $prefix set frame_rate=30

echo "-- keyframes"
expect 0 "keyframe add accepted" "$flagctl" --prefix $prefix keyframe add 0 --set stiffness=1500 --wind 6 0 1 \
  --law smooth
expect 0 "a second key with wind and camera" "$flagctl" --prefix $prefix keyframe add 2 --set stiffness=3000 \
  --wind 0 0 -6 --gust 0.2 --eye 2.6 1.9 4.4 --target 0.8 2.2 0 --fov 45
expect 3 "a key with NaN rejected" "$flagctl" --prefix $prefix keyframe add 1 --set stiffness=nan
contains "key.parameters.stiffness: nan is not a finite number" "  with the field named"
expect 3 "a key that sets the grid rejected" "$flagctl" --prefix $prefix keyframe add 1 --set cols=40
contains "cannot be animated" "  and why"
expect 3 "removing a key that is not there rejected" "$flagctl" --prefix $prefix keyframe remove 7
contains "no key at 7 s; keys at 0, 2 s" "  with the keys there are"
expect 2 "--gust without --wind is a usage error" "$flagctl" --prefix $prefix keyframe add 1 --gust 0.3
expect 2 "--set without a number is a usage error" "$flagctl" --prefix $prefix keyframe add 1 --set stiffness=x
expect 0 "keyframe loop on" "$flagctl" --prefix $prefix keyframe loop on
expect 0 "keyframe play" "$flagctl" --prefix $prefix keyframe play
expect 0 "keyframe list" "$flagctl" --prefix $prefix keyframe list
matches "^playing at [0-9.]+ s of 2 s, speed 1, loop on" "  playing and looping"
matches "^2 +linear +0 0 -6 +0.2 +eye 2.6 1.9 4.4, target 0.8 2.2 0, fov 45 +stiffness=3000" "  with what each key sets"
expect 0 "params follow the timeline" "$flagctl" --prefix $prefix params
matches "^stiffness +((1[5-9]|2[0-9])[0-9]{2}(\.[0-9]+)?|3000) " "  between its keys' stiffness"
expect 0 "keyframe pause" "$flagctl" --prefix $prefix keyframe pause
expect 0 "keyframe clear" "$flagctl" --prefix $prefix keyframe clear
expect 0 "an empty timeline is listed" "$flagctl" --prefix $prefix keyframe list
contains "paused at 0 s of 0 s" "  at 0, paused"
expect 4 "no TIMELINE on another prefix" "$flagctl" --prefix NOBODY_ --timeout 1 keyframe list

echo "-- hostile bytes"
expect 0 "spray garbage on every command channel" "$spray" "$LCM_DEFAULT_URL" 40 \
  ${prefix}WIND ${prefix}PARAM ${prefix}REFRESH ${prefix}CAMERA ${prefix}KEYFRAME
# A STATUS goes out each second: until one counts all that was sprayed.
for _ in $(seq 50); do
  "$flagctl" --prefix $prefix status >"$work/status.out" 2>&1 && grep -q "200 undecodable dropped" "$work/status.out" &&
    break
  sleep 0.2
done
expect 0 "the server still answers" "$flagctl" --prefix $prefix status
contains "200 undecodable dropped" "  and counted what it dropped on each channel"
expect 0 "and still takes commands" "$flagctl" --prefix $prefix wind 5 0 1

echo "-- recording"
expect 0 "record two seconds" "$flagctl" --prefix $prefix record -o "$work/session.lcmlog" --duration 2
contains "events" "  and report them"
expect 0 "watch the live stream" "$flagctl" --prefix $prefix watch --duration 2.5
contains "states received" "  and see states"

echo "-- a second server on the same prefix"
"$flagd" --prefix $prefix --log-level warn >"$work/second.log" 2>&1 &
second=$!
# Until a server has heard the other's STATUS (either may answer a status question first).
counted=0
for _ in $(seq 50); do
  if "$flagctl" --prefix $prefix --timeout 0.5 status >"$work/out" 2>&1 &&
    grep -q "1 other server(s) on this prefix" "$work/out"; then
    counted=1
    break
  fi
  sleep 0.2
done
if ((counted)); then pass "status names the other server and counts it"
else fail "no status counted the other server" "$work/out"; fi
# Both take the command; the first answer comes from either, which may not yet have heard the
# other's STATUS (a second apart): until an answer warns.
for _ in $(seq 10); do
  "$flagctl" --prefix $prefix wind 6 0 1 >"$work/wind.out" 2>&1 && grep -q "hears 1 other server" "$work/wind.out" &&
    break
  sleep 0.5
done
expect 0 "a command both take is accepted" "$flagctl" --prefix $prefix wind 6 0 1
contains "hears 1 other server(s) on prefix $prefix" "  with a warning that another took it too"
kill -TERM "$second"
wait "$second" || true
cp "$work/second.log" "$work/out"
contains "another server (id" "the second server warned loudly"

echo "-- stopping"
kill -TERM "$server"
code=0
wait "$server" || code=$?
server=""
if [[ $code == 0 ]]; then passes=$((passes + 1)); echo "ok    flagd stops cleanly on SIGTERM"
else failures=$((failures + 1)); echo "FAIL  flagd exit $code on SIGTERM"; cat "$work/flagd.log"; fi

echo "-- playback"
# The watcher may start listening after the player has begun: the log is played until it has
# printed a line about what it heard, then the watcher is stopped.
"$flagctl" --prefix $prefix --timeout 60 watch >"$work/watch.out" 2>&1 &
watcher=$!
expect 0 "lcm-logplayer plays the log" lcm-logplayer "$work/session.lcmlog"
for _ in $(seq 10); do
  await_text "$work/watch.out" "^t +[0-9.]+ s" 1 && break
  lcm-logplayer "$work/session.lcmlog" >/dev/null 2>&1
done
kill -INT $watcher
code=0
wait $watcher || code=$?
cp "$work/watch.out" "$work/out"
if [[ $code == 0 ]]; then passes=$((passes + 1)); echo "ok    flagctl watch reads the played-back log"
else failures=$((failures + 1)); echo "FAIL  flagctl watch on playback: exit $code"; fi
contains "states received" "  and sees its states"

finish
