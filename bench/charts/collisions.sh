#!/usr/bin/env bash
# Runs the self-collision benchmark (built beforehand: ninja -C build collision_bench) and charts it:
#   bench/charts/collisions.sh [BENCH_BINARY] [collision_bench options...]
#   default: build/bench/collision_bench, its default options (--repetitions 5 --seconds 10)
# Writes docs/collisions/cost.csv and cost.txt (the table as printed) and
# docs/collisions/crossings-vs-cost.png (gnuplot, collisions.gp). Takes some minutes: the
# 256 x 192 flag steps slowly. Timings are of this machine at the time; compare the ratios.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
binary=$(realpath "${1:-$root/build/bench/collision_bench}")
shift $(($# > 0 ? 1 : 0))
out=$root/docs/collisions
mkdir -p "$out"

"$binary" --csv "$out/cost.csv" "$@" | tee "$out/cost.txt"
gnuplot -e "csv='$out/cost.csv'; png='$out/crossings-vs-cost.png'" "$root/bench/charts/collisions.gp"
echo "collisions.sh: wrote $out/cost.csv, cost.txt and crossings-vs-cost.png"
