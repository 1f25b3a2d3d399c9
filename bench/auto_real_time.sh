#!/usr/bin/env bash
# Real time under auto: each preset at each grid (auto's own, or one set by the user with the
# integrator left to auto), flagd stepping, drawing and publishing in real time at threads=2. For
# each: the model auto runs at the end, its real-time factor over SECONDS of wall time (simulated
# seconds per wall second, from the first STATUS after a 3 s start to the last) and the frame
# rate of the last second.
#   bench/auto_real_time.sh [--busy] [--grids "auto 64x48 128x96"] [--scenes "breeze gale"] [BUILD_DIR] [SECONDS]
# --busy: a neighbour process spins on one core throughout. Runs inside a private network
# namespace (scripts/netns-run), so nothing leaves the machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
busy=0 grids="auto 64x48 128x96 256x192" scenes="breeze calm gale hanging"
args=()
while (($#)); do
  case $1 in
    --busy) busy=1 ;;
    --grids) grids=$2; shift ;;
    --scenes) scenes=$2; shift ;;
    *) args+=("$1") ;;
  esac
  shift
done
build=$(cd "${args[0]:-$root/build}" && pwd)
seconds=${args[1]:-10}
if [[ -z ${FLAGSIM_IN_NETNS:-} ]]; then
  runner=("$root/scripts/netns-run" --)
  if ((busy)); then
    runner=("$root/scripts/busy-run" --cores 1 -- "${runner[@]}")
    echo "a busy neighbour spins on one core throughout"
  fi
  FLAGSIM_IN_NETNS=1 exec "${runner[@]}" "$0" --grids "$grids" --scenes "$scenes" "$build" "$seconds"
fi
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
flagctl=$build/client/flagctl
work=$(mktemp -d)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$work"' EXIT

sim_time() { awk '/^sim time:/ { print $3 }' "$1"; }
uptime() { awk '/^uptime:/ { print $2 }' "$1"; }

printf '%-8s %-8s %-46s %-6s %-7s %s\n' scene grid "model at the end" rtf frames "auto's word"
for scene in $scenes; do
  for grid in $grids; do
    sets=(--set threads=2)
    [[ $grid != auto ]] && sets+=(--set cols="${grid%x*}" --set rows="${grid#*x}")
    "$build/server/flagd" --log-level warn --scene "$scene" "${sets[@]}" &
    server=$!
    pids+=($server)
    sleep 3
    "$flagctl" --timeout 10 status >"$work/first" || true
    sleep "$seconds"
    "$flagctl" --timeout 10 status >"$work/last" || true
    kill "$server"; wait "$server" 2>/dev/null || true
    rtf=$(awk -v s0="$(sim_time "$work/first")" -v s1="$(sim_time "$work/last")" \
      -v u0="$(uptime "$work/first")" -v u1="$(uptime "$work/last")" \
      'BEGIN { printf "%.3f", (s1 - s0) / (u1 - u0) }')
    model=$(sed -n 's/^model: *//p' "$work/last" | sed 's/; auto chooses.*//')
    frames=$(awk '/^frames:/ { print $2 }' "$work/last")
    word=$(sed -n 's/^auto: *//p' "$work/last")
    printf '%-8s %-8s %-46s %-6s %-7s %s\n' "$scene" "$grid" "$model" "$rtf" "$frames" "$word"
  done
done
