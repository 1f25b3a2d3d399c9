#!/usr/bin/env bash
# Runs the physics lab's experiments (built beforehand: ninja -C build lab) and charts them:
#   bench/charts/lab.sh [LAB_BINARY] [EXPERIMENT...]    default: build/bench/lab, all of them
# Writes docs/lab/EXPERIMENT.csv and .txt (the table as printed), and the charts
# docs/lab/work-precision.png, stability.png, cost.png and threads.png (gnuplot, lab_*.gp).
# Timings are of this machine at the time: run it with the machine otherwise idle.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
binary=$(realpath "${1:-$root/build/bench/lab}")
shift || true
cd "$root"  # the charts load bench/charts/lab_common.gp
experiments=("$@")
((${#experiments[@]})) || experiments=(orders stability work-precision cost threads cheapest)
out=$root/docs/lab
mkdir -p "$out"

for experiment in "${experiments[@]}"; do
  echo "lab.sh: $experiment"
  "$binary" "$experiment" --csv "$out/$experiment.csv" | tee "$out/$experiment.txt"
  chart=$root/bench/charts/lab_$experiment.gp
  if [[ -f $chart ]]; then
    gnuplot -e "csv='$out/$experiment.csv'; png='$out/$experiment.png'" "$chart"
    echo "lab.sh: wrote $out/$experiment.png"
  fi
done
