#!/usr/bin/env bash
# Contact sheets of the presets: each scene rendered offline for 10 s (flagd render, no
# network), eight frames from t = 1.25 s to 10 s side by side, four to a row, each frame with
# its time. What a person sees the flag do, at a glance.
#   bench/charts/contact_sheets.sh [BUILD_DIR] [OUT_DIR] [SCENE...]
#   default: build, docs/contact, hanging calm breeze gale  -> OUT_DIR/SCENE.png
# Needs ffmpeg (scripts/install-deps.sh installs it).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${1:-$root/build}
out=${2:-$root/docs/contact}
shift $(($# > 2 ? 2 : $#))
scenes=("$@")
((${#scenes[@]})) || scenes=(hanging calm breeze gale)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
for scene in "${scenes[@]}"; do
  # 0.8 frames a second: frames at 0, 1.25, ..., 10 s; the first (the start) is left out.
  "$build/server/flagd" render --scene "$scene" --duration 10.1 --fps 0.8 --png-dir "$work/$scene" >/dev/null 2>&1
  inputs=()
  for i in 1 2 3 4 5 6 7 8; do
    inputs+=(-i "$work/$scene/$(printf 'frame_%06d.png' "$i")")
  done
  labels=""
  for i in 0 1 2 3 4 5 6 7; do
    t=$(awk -v i="$i" 'BEGIN { printf "%.2f", (i + 1) * 1.25 }')
    labels+="[$i:v]scale=480:-1,drawtext=text='$scene  t = $t s':x=10:y=10:fontcolor=white:box=1:boxcolor=black@0.5[f$i];"
  done
  ffmpeg -loglevel error -y "${inputs[@]}" -filter_complex \
    "${labels}[f0][f1][f2][f3][f4][f5][f6][f7]xstack=inputs=8:layout=0_0|w0_0|w0+w1_0|w0+w1+w2_0|0_h0|w0_h0|w0+w1_h0|w0+w1+w2_h0" \
    "$out/$scene.png"
  echo "contact_sheets.sh: $out/$scene.png"
done
