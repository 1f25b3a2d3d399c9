#!/usr/bin/env bash
# Runs the physics lab's experiments (built beforehand: ninja -C build lab) and charts them:
#   bench/charts/lab.sh [LAB_BINARY] [EXPERIMENT...]    default: build/bench/lab, all of them
# Writes docs/lab/EXPERIMENT.csv and .txt (the table as printed), and the charts
# docs/lab/work-precision.png, stability.png, cost.png and threads.png (gnuplot, lab_*.gp).
# work-precision also runs `bullet_bench --work-precision` when it is built beside the lab (it
# needs Bullet): docs/lab/work-precision-bullet.csv and .txt, Bullet's point on the same chart.
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

bullet_bench=$(dirname "$binary")/bullet_bench

# Bullet's rows for the work-precision chart, right after the lab's (the machine's speed drifts):
# prints the gnuplot assignment that adds them, or nothing without bullet_bench.
bullet_rows() {
  if [[ ! -x $bullet_bench ]]; then
    echo "lab.sh: no $bullet_bench (Bullet not found at configure time): the chart has no Bullet" >&2
    return
  fi
  echo "lab.sh: work-precision, Bullet" >&2
  "$bullet_bench" --work-precision --csv "$out/work-precision-bullet.csv" >"$out/work-precision-bullet.txt"
  cat "$out/work-precision-bullet.txt" >&2
  echo "bullet='$out/work-precision-bullet.csv'; "
}

for experiment in "${experiments[@]}"; do
  echo "lab.sh: $experiment"
  "$binary" "$experiment" --csv "$out/$experiment.csv" | tee "$out/$experiment.txt"
  extra=""
  [[ $experiment == work-precision ]] && extra=$(bullet_rows)
  chart=$root/bench/charts/lab_$experiment.gp
  if [[ -f $chart ]]; then
    gnuplot -e "${extra}csv='$out/$experiment.csv'; png='$out/$experiment.png'" "$chart"
    echo "lab.sh: wrote $out/$experiment.png"
  fi
done
