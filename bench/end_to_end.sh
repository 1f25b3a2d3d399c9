#!/usr/bin/env bash
# End to end: flagd at 1280 x 720 with a 64 x 48 flag and 60 frames a second, stepping,
# drawing, tiling and publishing on this machine's cores, watched by flagctl. Reports the
# sustained frame rate, the real-time factor, tiles and bytes per frame against a raw frame,
# and how long a snapshot takes from its REFRESH to a complete, hash-checked keyframe.
#   bench/end_to_end.sh [BUILD_DIR] [SECONDS]
# Runs inside a private network namespace (scripts/netns-run), so nothing leaves the machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
seconds=${2:-10}
if [[ -z ${FLAGSIM_IN_NETNS:-} ]]; then
  FLAGSIM_IN_NETNS=1 exec "$root/scripts/netns-run" -- "$0" "$build" "$seconds"
fi
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
flagctl=$build/client/flagctl
"$build/server/flagd" --log-level warn --set cols=64 --set rows=48 --set threads=2 --set frame_rate=60 &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
sleep 3  # past start-up and the first keyframe

echo "flagd: 1280 x 720, 64 x 48 flag, frame_rate 60, threads 2; one STATUS a second for $seconds s"
printf '%-8s %-8s %-8s %-12s %-12s %-10s\n' second rtf frames tiles/frame bytes/frame skipped
raw=$((1280 * 720 * 3))
for ((i = 1; i <= seconds; i++)); do
  "$flagctl" --timeout 3 status >/tmp/flagsim_status.$$ || continue
  awk -v i="$i" '
    /real-time factor/ { rtf = $3 }
    /^frames:/ { hz = $2; tiles = $12; bytes = $15; skipped = $18 }
    END { printf "%-8s %-8s %-8s %-12s %-12s %-10s\n", i, rtf, hz, tiles, bytes, skipped }' /tmp/flagsim_status.$$
done | tee /tmp/flagsim_rows.$$
rm -f /tmp/flagsim_status.$$
awk -v raw="$raw" '{ n++; rtf += $2; hz += $3; tiles += $4; bytes += $5 }
  END { printf "mean: real-time factor %.3f, %.1f frames/s, %.1f tiles and %.0f bytes a frame = %.2f %% of a raw %d-byte frame\n",
               rtf / n, hz / n, tiles / n, bytes / n, 100 * bytes / n / raw, raw }' /tmp/flagsim_rows.$$
rm -f /tmp/flagsim_rows.$$

echo "snapshots (REFRESH to a complete, hash-checked frame):"
for i in 1 2 3 4 5; do "$flagctl" --timeout 5 snapshot -o /dev/null | sed 's/^/  /'; done
