#!/usr/bin/env bash
# What running a sweep through Slurm costs against running it here (scripts/sweep), on a
# one-node Slurm of its own (scripts/slurm-cluster), in a private network namespace:
#   1. overhead: POINTS trivial points (a render of one frame each), one a task, local with a
#      task per core against a Slurm array of as many at once: wall time per point, and the
#      difference, which is Slurm's per task
#   2. the work-precision chart's points at the present defaults, to completion: serially
#      (lab work-precision), locally in parallel and through Slurm, CHUNK points a task
# Prints a table; the sweeps' folders stay in OUT.
#   bench/sweep_bench.sh [BUILD_DIR] [OUT] [POINTS] [CHUNK]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build} out=${2:-$(mktemp -d)} points=${3:-40} chunk=${4:-4}
[[ -n ${FLAGSIM_IN_NETNS:-} ]] || exec env FLAGSIM_IN_NETNS=1 "$root/scripts/netns-run" -- "$0" "$build" "$out" "$points" "$chunk"
mkdir -p "$out"
out=$(cd "$out" && pwd)
cluster=$root/scripts/slurm-cluster
sweep=$root/scripts/sweep
lab=$build/bench/lab
trap '"$cluster" stop "$out/cluster"' EXIT
"$cluster" start "$out/cluster"
export SLURM_CONF=$out/cluster/slurm.conf
cores=$(nproc)

# seconds COMMAND...: runs it quietly, prints its wall time in s (3 decimals)
seconds() {
  local start end
  start=$(date +%s%N)
  "$@" >"$out/last.log" 2>&1 || { echo "failed: $*" >&2; tail "$out/last.log" >&2; exit 1; }
  end=$(date +%s%N)
  awk -v ns=$((end - start)) 'BEGIN { printf "%.3f", ns / 1e9 }' 
}

scenes=()
for ((i = 0; i < points; ++i)); do scenes+=(--scene breeze); done
local_trivial=$(seconds "$sweep" --lab "$lab" --jobs "$cores" --out "$out/trivial-local" render "${scenes[@]}" --duration 0.05 --fps 20)
slurm_trivial=$(seconds "$sweep" --lab "$lab" --engine slurm --throttle "$cores" --out "$out/trivial-slurm" render "${scenes[@]}" --duration 0.05 --fps 20)
serial=$(seconds "$lab" work-precision --csv "$out/work-precision-serial.csv")
local_wp=$(seconds "$sweep" --lab "$lab" --jobs "$cores" --chunk "$chunk" --out "$out/wp-local" work-precision)
slurm_wp=$(seconds "$sweep" --lab "$lab" --engine slurm --throttle "$cores" --chunk "$chunk" --out "$out/wp-slurm" work-precision)
wp_points=$(($(wc -l <"$out/wp-local/points.txt") - 1))
same=no
cmp -s <(cut -d, -f1-6 "$out/work-precision-serial.csv") <(cut -d, -f1-6 "$out/wp-slurm/work-precision.csv") &&
  cmp -s <(cut -d, -f1-6 "$out/work-precision-serial.csv") <(cut -d, -f1-6 "$out/wp-local/work-precision.csv") && same=yes

printf '%s cores, %s\n' "$cores" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
printf '%-52s %10s %12s\n' "run" "wall s" "s per point"
row() { awk -v what="$1" -v s="$2" -v n="$3" 'BEGIN { printf "%-52s %10.2f %12.3f\n", what, s, s / n }'; }
row "trivial points ($points), local, $cores at once" "$local_trivial" "$points"
row "trivial points ($points), Slurm array, $cores at once" "$slurm_trivial" "$points"
awk -v slurm="$slurm_trivial" -v here="$local_trivial" -v n="$points" -v cores="$cores" \
  'BEGIN { printf "Slurm overhead per task, each slot: %.3f s\n", (slurm - here) / n * cores }' 
row "work-precision ($wp_points points), serial" "$serial" "$wp_points"
row "work-precision, local, $cores at once, $chunk a task" "$local_wp" "$wp_points"
row "work-precision, Slurm array, $cores at once, $chunk a task" "$slurm_wp" "$wp_points"
echo "errors of the three runs equal, bit for bit (cost is timing): $same"
echo "sweeps in $out"
