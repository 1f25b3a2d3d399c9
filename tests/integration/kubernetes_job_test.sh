#!/usr/bin/env bash
# scripts/sweep --engine kubernetes writes the sweep as an Indexed Job; a YAML parser checks it
# (tests/web/kubernetes_job_check.mjs). No cluster is needed, and none is touched.
# Usage: kubernetes_job_test.sh SOURCE_DIR BUILD_DIR NODE
set -euo pipefail
source_dir=$1 build=$2 node=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$source_dir/scripts/sweep" --lab "$build/bench/lab" --engine kubernetes --throttle 3 --out "$work/sweep" \
  render --scene breeze --scene calm --scene gale --scene hanging --duration 0.5
[[ -z $(ls "$work/sweep/records" 2>/dev/null) ]] || { echo "FAIL  the kubernetes engine ran points here"; exit 1; }
"$node" "$source_dir/tests/web/kubernetes_job_check.mjs" "$work/sweep/job.yaml" "$work/sweep" 4 3
