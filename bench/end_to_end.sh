#!/usr/bin/env bash
# End to end: flagd at 1280 x 720 with a 64 x 48 flag and 60 frames a second, stepping,
# drawing, tiling and publishing on this machine's cores, watched by flagctl. For each thread
# count in turn, in one run: the sustained frame rate (mean and worst second), the real-time
# factor, tiles and bytes per frame against a raw frame, and how long a snapshot takes from its
# REFRESH to a complete, hash-checked keyframe (median and worst).
#   bench/end_to_end.sh [--busy] [--threads "1 2"] [--snapshots N] [--set NAME=VALUE]... [BUILD_DIR] [SECONDS]
# --set: a parameter for flagd besides the bench's own (antialias=off, say), repeatable.
# --busy: a neighbour process spins on one core throughout (a shell loop), as a busy laptop's
# browser would. Runs inside a private network namespace (scripts/netns-run), so nothing leaves
# the machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
busy=0 thread_counts="1 2" snapshots=20
args=() sets=()
while (($#)); do
  case $1 in
    --busy) busy=1 ;;
    --threads) thread_counts=$2; shift ;;
    --snapshots) snapshots=$2; shift ;;
    --set) sets+=(--set "$2"); shift ;;
    *) args+=("$1") ;;
  esac
  shift
done
build=$(cd "${args[0]:-$root/build}" && pwd)
seconds=${args[1]:-10}
if [[ -z ${FLAGSIM_IN_NETNS:-} ]]; then
  flags=(--threads "$thread_counts" --snapshots "$snapshots" "${sets[@]}")
  ((busy)) && flags+=(--busy)
  FLAGSIM_IN_NETNS=1 exec "$root/scripts/netns-run" -- "$0" "${flags[@]}" "$build" "$seconds"
fi
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
flagctl=$build/client/flagctl
work=$(mktemp -d)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$work"' EXIT
if ((busy)); then
  bash -c 'while :; do :; done' &
  pids+=($!)
  echo "a busy neighbour spins on one core throughout"
fi

# One flagd at `threads`: a row of STATUS a second, then the snapshots.
measure() {
  local threads=$1
  "$build/server/flagd" --log-level warn --set cols=64 --set rows=48 --set threads="$threads" \
    --set frame_rate=60 "${sets[@]}" &
  local server=$!
  pids+=($server)
  sleep 3  # past start-up and the first keyframe
  echo "threads=$threads: one STATUS a second for $seconds s"
  printf '  %-8s %-8s %-8s %-12s %-12s %-10s\n' second rtf frames tiles/frame bytes/frame skipped
  local last_uptime=""
  for ((i = 1; i <= seconds; i++)); do
    # flagctl status answers at once with the last second's report: wait most of a second, then
    # ask until a new one is out (few calls: each is a process on the cores being measured).
    sleep 0.8
    for ((poll = 0; poll < 20; poll++)); do
      "$flagctl" --timeout 3 status >"$work/status" || continue
      uptime=$(awk '/^uptime:/ { print $2 }' "$work/status")
      [[ $uptime != "$last_uptime" ]] && break
      sleep 0.25
    done
    last_uptime=$uptime
    awk -v i="$i" '
      /real-time factor/ { rtf = $3 }
      /^frames:/ { hz = $2; tiles = $12; bytes = $15; skipped = $18 }
      END { printf "%-8s %-8s %-8s %-12s %-12s %-10s\n", i, rtf, hz, tiles, bytes, skipped }' "$work/status"
  done >"$work/rows"
  sed 's/^/  /' "$work/rows"
  awk -v raw=$((1280 * 720 * 3)) -v threads="$threads" '
    { n++; rtf += $2; hz += $3; tiles += $4; bytes += $5; if (n == 1 || $3 < worst) worst = $3 }
    END { printf "  threads=%s mean: real-time factor %.3f, %.1f frames/s (worst second %.1f), %.1f tiles and %.0f bytes a frame = %.2f %% of a raw frame\n",
                 threads, rtf / n, hz / n, worst, tiles / n, bytes / n, 100 * bytes / n / raw }' "$work/rows"
  for ((i = 0; i < snapshots; i++)); do
    "$flagctl" --timeout 5 snapshot -o "$work/snapshot.png" 2>&1 | grep -o '[0-9.]* ms' | head -1 || echo "failed"
  done >"$work/snapshots"
  sort -n "$work/snapshots" | awk -v threads="$threads" '
    /ms/ { ms[n++] = $1 } /failed/ { failed++ }
    END { printf "  threads=%s snapshots (REFRESH to a complete, hash-checked frame): median %.0f ms, worst %.0f ms, %d failed of %d\n",
                 threads, n ? ms[int((n - 1) / 2)] : 0, n ? ms[n - 1] : 0, failed, n + failed }'
  kill "$server"
  wait "$server" 2>/dev/null || true
}

for threads in $thread_counts; do measure "$threads"; done
