#!/usr/bin/env bash
# Runs the shading benchmark (built beforehand: ninja -C build shading_bench) and charts it:
#   bench/charts/shading.sh [BENCH_BINARY]     default: build/bench/shading_bench
# Writes docs/shading.csv (the benchmark's table) and docs/shading.png (gnuplot, shading.gp).
# Paths are the repository's whatever the working directory; needs gnuplot (Debian: gnuplot-nox).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
binary=${1:-$root/build/bench/shading_bench}

"$binary" --csv "$root/docs/shading.csv"
gnuplot -e "csv='$root/docs/shading.csv'; png='$root/docs/shading.png'" "$root/bench/charts/shading.gp"
echo "shading.sh: wrote $root/docs/shading.csv and $root/docs/shading.png"
