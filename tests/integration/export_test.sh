#!/usr/bin/env bash
# flagd render and flagctl export as real processes, no network: a short scene rendered to a log
# and PNGs, the log exported to PNGs, an MP4, a GIF (frames counted by ffprobe) and MCAP (read
# by @mcap/core, Foxglove's reader, when tests/web's dependencies are installed), a copy cut
# mid-event exported up to its cut, and bad arguments. Needs ffmpeg (scripts/install-deps.sh).
# Usage: export_test.sh BUILD_DIR
set -euo pipefail
build=$1
flagd=$build/server/flagd
flagctl=$build/client/flagctl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

source "$(dirname "$0")/checks.sh"
equal() {  # equal GOT WANTED DESCRIPTION
  if [[ $1 == "$2" ]]; then pass "$3 ($1)"; else fail "$3: $1, expected $2"; fi
}
pngs() { find "$1" -name 'frame_*.png' | wc -l; }
frames_in() {  # the frames ffprobe decodes in a video
  ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
    -of default=nokey=1:noprint_wrappers=1 "$1"
}
pixels() { ffmpeg -v error -i "$1" -f rawvideo -pix_fmt rgb24 - | md5sum | cut -d' ' -f1; }  # decoded, not file bytes

if ! command -v ffmpeg >/dev/null || ! command -v ffprobe >/dev/null; then
  echo "FAIL  ffmpeg and ffprobe are needed: scripts/install-deps.sh installs them"
  exit 1
fi

# A small image with an odd height (the MP4 pads it to even), a short run.
cat >"$work/small.toml" <<'TOML'
name = "small"
[camera]
width = 200
height = 115
TOML
duration=1.5
fps=8
expected=$(awk -v d=$duration -v f=$fps 'BEGIN { n = d * f; print (n == int(n)) ? n : int(n) + 1 }')  # frames at k/fps < d
log=$work/run.lcmlog

echo "-- flagd render"
expect 0 "render $duration s at $fps fps" "$flagd" render --scene "$work/small.toml" --duration $duration --fps $fps \
  -o "$log" --png-dir "$work/rendered" --set cols=24 --set rows=16
contains "$expected frames" "  and says how many frames"
equal "$(pngs "$work/rendered")" "$expected" "  PNG frames written"
if [[ $(pixels "$work/rendered/frame_000000.png") != $(pixels "$work/rendered/frame_$(printf %06d $((expected - 1))).png") ]]; then
  pass "  the flag moves between the first and last frames"
else fail "  the first and last frames are the same picture"; fi
expect 0 "flagd render --help" "$flagd" render --help
contains "--png-dir" "  lists its options"
expect 2 "render with nothing to write" "$flagd" render --duration 1
contains "give -o LOG, --png-dir DIR or both" "  says what to give"
expect 2 "render at an fps out of range" "$flagd" render --duration 1 -o "$work/x.lcmlog" --fps 500
contains "allowed above 0 .. 120 Hz" "  with the range"
expect 0 "flagd's own command line still runs" "$flagd" --fast --duration 0.2 --log-level warn

echo "-- flagctl export"
expect 0 "export to a directory" "$flagctl" export "$log" -o "$work/exported/"
equal "$(pngs "$work/exported")" "$expected" "  PNG frames exported"
same=0
for ((k = 0; k < expected; k++)); do
  name=frame_$(printf %06d $k).png
  [[ $(pixels "$work/exported/$name") == $(pixels "$work/rendered/$name") ]] && same=$((same + 1))
done
equal "$same" "$expected" "  frames pixel for pixel the ones flagd drew"
expect 0 "export to MP4" "$flagctl" export "$log" -o "$work/run.mp4"
equal "$(frames_in "$work/run.mp4")" "$expected" "  frames in the MP4"
equal "$(ffprobe -v error -select_streams v:0 -show_entries stream=codec_name,pix_fmt,width,height,r_frame_rate \
  -of csv=p=0 "$work/run.mp4")" "h264,200,116,yuv420p,$fps/1" "  H.264, yuv420p, padded to even, at $fps fps"
expect 0 "export to GIF" "$flagctl" export "$log" -o "$work/run.gif"
equal "$(frames_in "$work/run.gif")" "$expected" "  frames in the GIF"

echo "-- MCAP, read by Foxglove's own reader"
expect 0 "export to MCAP" "$flagctl" export "$log" -o "$work/run.mcap"
matches "run.mcap: [0-9]+ messages, .*$expected on /flag/image" "  one image per frame, and the other channels, counted"
expect 2 "--fps with MCAP" "$flagctl" export "$log" -o "$work/x.mcap" --fps 5
contains "--fps is for videos" "  says it is for videos"
web_tests=$(cd "$(dirname "$0")/../web" && pwd)
if command -v node >/dev/null && [[ -d $web_tests/node_modules/@mcap/core ]]; then
  if node "$web_tests/mcap_check.mjs" "$work/run.mcap" /flag/image /flag/scene /flag/state /flag/params >"$work/mcap.out" 2>&1; then
    pass "  @mcap/core streams and seeks it, every message decoding with its schema"
  else fail "  @mcap/core on the MCAP file" "$work/mcap.out"; fi
else
  echo "SKIP  @mcap/core on the MCAP file: node or tests/web's dependencies are not installed"
fi

echo "-- a log cut mid-event (a recorder killed mid-write)"
size=$(stat -c %s "$log")
cut=$((size * 6 / 10))
# an event boundary there would be a whole, shorter log: move into the event
[[ $(od -An -tx1 -j $cut -N4 "$log" | tr -d ' ') == eda1da01 ]] && cut=$((cut + 5))
head -c $cut "$log" >"$work/cut.lcmlog"
expect 0 "export of the cut log" "$flagctl" export "$work/cut.lcmlog" -o "$work/cut/"
contains "cut.lcmlog: at byte" "  names the file and the byte where it stops"
contains "cut short" "  and says it was cut short"
contains "exported everything before it" "  and what was exported"
got=$(pngs "$work/cut")
if ((got > 0 && got < expected)); then pass "  fewer frames ($got of $expected)"; else fail "  $got frames of $expected"; fi
last=frame_$(printf %06d $((got - 1))).png
equal "$(pixels "$work/cut/$last")" "$(pixels "$work/rendered/$last")" "  the last one exported is the frame flagd drew"

echo "-- a size change mid-log"
# Two runs of different sizes and shapes, one after the other in one log (as a camera size
# command mid-session leaves it): one video at the first size, later frames scaled to fit.
cat >"$work/tall.toml" <<'TOML'
name = "tall"
[camera]
width = 120
height = 160
TOML
expect 0 "a second render at 120 x 160" "$flagd" render --scene "$work/tall.toml" --duration 0.5 --fps $fps \
  -o "$work/tall.lcmlog" --set cols=24 --set rows=16
cat "$log" "$work/tall.lcmlog" >"$work/sizes.lcmlog"
tall_frames=$(awk -v d=0.5 -v f=$fps 'BEGIN { n = d * f; print (n == int(n)) ? n : int(n) + 1 }')
expect 0 "export of both into one MP4" "$flagctl" export "$work/sizes.lcmlog" -o "$work/sizes.mp4"
matches "note: [1-9][0-9]* frame\(s\) of another size than the first \(200 x 115\) scaled to fit it" \
  "  saying what it did"
equal "$(frames_in "$work/sizes.mp4")" "$((expected + tall_frames))" "  every frame of both in the video"
equal "$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height -of csv=p=0 "$work/sizes.mp4")" \
  "200,116" "  at the first frame's size (padded to even)"

echo "-- bad input"
expect 2 "an output that is neither directory, .mp4 nor .gif" "$flagctl" export "$log" -o "$work/run.avi"
contains "allowed: a directory (ending in / or existing) for PNG frames, NAME.mp4 or NAME.gif" "  names the allowed ones"
expect 1 "a log that is not there" "$flagctl" export "$work/none.lcmlog" -o "$work/none/"
contains "none.lcmlog" "  is named"
head -c 5000 /dev/urandom >"$work/noise.lcmlog"
expect 5 "a file that is not a log" "$flagctl" export "$work/noise.lcmlog" -o "$work/noise/"
contains "not an LCM event log" "  says so"
expect 5 "a log with no frames on the prefix" "$flagctl" --prefix OTHER_ export "$log" -o "$work/other/"
contains "no complete frame on OTHER_FRAME" "  says so"
expect 1 "a video into a directory that is not there" "$flagctl" export "$log" -o /nonexistent/out.mp4
contains "cannot write /nonexistent/out.mp4: there is no directory /nonexistent" "  says so"
if [[ $(wc -l <"$work/out") == 1 ]]; then pass "  in one line: no ffmpeg error, no summary of frames not written"
else fail "  in more than one line" "$work/out"; fi
mkdir "$work/empty-path"
expect 1 "no ffmpeg on PATH" env PATH="$work/empty-path" "$flagctl" export "$log" -o "$work/none.mp4"
contains "ffmpeg is not installed" "  says so"

finish
