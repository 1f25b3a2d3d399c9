#!/usr/bin/env bash
# A flagd render log played back by lcm-logplayer over udpm://, inside a private network
# namespace (ctest runs this through scripts/netns-run): flagctl watch reads its states and
# flagctl snapshot assembles a hash-checked frame from it, as from a live server.
# Usage: playback_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
prefix=PLAY_
work=$(mktemp -d)
watcher="" snapper=""
cleanup() {
  [[ -n $watcher ]] && kill "$watcher" 2>/dev/null || true
  [[ -n $snapper ]] && kill "$snapper" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

source "$(dirname "$0")/checks.sh"

cat >"$work/small.toml" <<'TOML'
name = "small"
[camera]
width = 240
height = 160
TOML
frames=30
"$flagd" render --scene "$work/small.toml" --duration 3 --fps 10 --prefix $prefix -o "$work/run.lcmlog" \
  --png-dir "$work/rendered" >"$work/render.out" 2>&1 || fail "flagd render" "$work/render.out"

# Readers first, then the player: the log lasts 3 s of simulated time, so as long in real time.
# A reader may start listening after the player has begun, so the log is played again until both
# have what they wait for: the watcher a line about frames, the snapshot a whole frame.
"$flagctl" --prefix $prefix --timeout 60 watch >"$work/watch.out" 2>&1 &
watcher=$!
"$flagctl" --prefix $prefix --timeout 60 snapshot -o "$work/snapshot.png" >"$work/snapshot.out" 2>&1 &
snapper=$!
if lcm-logplayer "$work/run.lcmlog" >"$work/player.out" 2>&1; then pass "lcm-logplayer plays the render's log"
else fail "lcm-logplayer exit $?" "$work/player.out"; fi
for _ in $(seq 10); do
  grep -q "FRAME" "$work/watch.out" && ! kill -0 $snapper 2>/dev/null && break
  lcm-logplayer "$work/run.lcmlog" >/dev/null 2>&1
done

kill -INT $watcher
code=0
wait $watcher || code=$?
watcher=""
if [[ $code == 0 ]] && grep -q "states received" "$work/watch.out"; then pass "flagctl watch reads its states"
else fail "flagctl watch: exit $code" "$work/watch.out"; fi
if grep -q "FRAME" "$work/watch.out"; then pass "  and sees its frames"; else fail "  no FRAME in watch" "$work/watch.out"; fi

code=0
wait $snapper || code=$?
snapper=""
if [[ $code == 0 ]]; then pass "flagctl snapshot gets a hash-checked frame from it"
else fail "flagctl snapshot: exit $code" "$work/snapshot.out"; fi
grep -q "no server answered" "$work/snapshot.out" && pass "  and says no server answered its request" ||
  fail "  no word that nobody answered" "$work/snapshot.out"
# The snapshot is one of the frames flagd drew, pixel for pixel.
pixels() { ffmpeg -v error -i "$1" -f rawvideo -pix_fmt rgb24 - | md5sum | cut -d' ' -f1; }
if [[ -f $work/snapshot.png ]]; then
  want=$(pixels "$work/snapshot.png")
  match=""
  for ((k = 0; k < frames; k++)); do
    name=frame_$(printf %06d $k).png
    [[ $(pixels "$work/rendered/$name") == "$want" ]] && match=$name && break
  done
  if [[ -n $match ]]; then pass "  equal to $match as flagd drew it"; else fail "  equal to none of the frames drawn"; fi
fi

finish
