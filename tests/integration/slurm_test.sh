#!/usr/bin/env bash
# A sweep and a batch render through a real one-node Slurm cluster, started here in a private
# network namespace (ctest runs this through scripts/netns-run) and stopped by pid at the end;
# their gathered results must equal a local run's bit for bit, but for the cost column, which is
# timing. A task whose record is missing is run again, alone, by --resume.
# Usage: slurm_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1 build=$2
for command in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
  if ! command -v "$command" >/dev/null; then
    echo "skipped: no $command: Slurm is not installed here (scripts/install-deps.sh --slurm installs it)"
    exit 77
  fi
done
work=$(mktemp -d)
cluster=$source_dir/scripts/slurm-cluster
trap '"$cluster" stop "$work/cluster"; rm -rf "$work"' EXIT
source "$(dirname "$0")/checks.sh"

if "$cluster" start "$work/cluster" >"$work/out" 2>&1; then pass "a one-node Slurm cluster is up, its node idle"
else
  fail "scripts/slurm-cluster start" "$work/out"
  finish
fi
export SLURM_CONF=$work/cluster/slurm.conf

sweep=$source_dir/scripts/sweep
lab=$build/bench/lab
# work-precision, quick: two integrators at three steps; two points a task.
expect 0 "the sweep, locally" "$sweep" --lab "$lab" --out "$work/local" --chunk 2 work-precision --quick
expect 0 "the sweep, as a Slurm array" "$sweep" --lab "$lab" --engine slurm --timeout 300 --out "$work/slurm" --chunk 2 \
  work-precision --quick
matches "Slurm job [0-9]+, array 0,1,2," "  one array of three tasks"
cut -d, -f1-6 "$work/local/work-precision.csv" >"$work/local.errors"
cut -d, -f1-6 "$work/slurm/work-precision.csv" >"$work/slurm.errors"
if [[ $(wc -l <"$work/local.errors") == 7 ]] && cmp -s "$work/local.errors" "$work/slurm.errors"; then
  pass "  its six points' errors equal the local run's, bit for bit (the cost column is timing)"
else
  diff "$work/local.errors" "$work/slurm.errors" >"$work/out" || true
  fail "  the gathered errors differ from the local run's" "$work/out"
fi
if grep -q "^# node: " "$work"/slurm/records/*.csv; then pass "  each record names the node its cost came from"
else fail "  a record without its node"; fi

# A batch render of two scenes.
expect 0 "a batch render, locally" "$sweep" --lab "$lab" --out "$work/render-local" render --scene breeze --scene calm \
  --duration 0.5 --fps 6
expect 0 "the batch render, as a Slurm array" "$sweep" --lab "$lab" --engine slurm --timeout 300 --out "$work/render-slurm" \
  render --scene breeze --scene calm --duration 0.5 --fps 6
if cmp -s "$work/render-local/render.csv" "$work/render-slurm/render.csv"; then
  pass "  its frames equal the local run's, bit for bit (their SHA-256)"
else
  diff "$work/render-local/render.csv" "$work/render-slurm/render.csv" >"$work/out" || true
  fail "  the rendered frames differ" "$work/out"
fi

# A task that left no record (as a node lost midway would) is found by its record and run again.
rm "$work/slurm/records/3.csv"
expect 0 "a sweep resumed after a record went missing" "$sweep" --lab "$lab" --engine slurm --timeout 300 --resume \
  --out "$work/slurm" --chunk 2 work-precision
matches "array 1, " "  only the task that lost its record (1) is submitted again"
cut -d, -f1-6 "$work/slurm/work-precision.csv" >"$work/slurm.errors"
if cmp -s "$work/local.errors" "$work/slurm.errors"; then pass "  and the gathered table is whole again"
else fail "  the resumed table differs"; fi

# A task that fails every time is named, after its retries.
expect 0 "a render to spoil" "$sweep" --lab "$lab" --engine slurm --timeout 300 \
  --retries 1 --out "$work/render-bad" render --scene breeze --duration 0.5 --fps 6
sed -i 's/scene=breeze/scene=nowhere.toml/' "$work/render-bad/points.txt"
rm -rf "$work/render-bad/records"
expect 1 "a task that fails every time (its scene is nowhere) is reported after its retries" "$sweep" --lab "$lab" --engine slurm \
  --timeout 300 --retries 1 --resume --out "$work/render-bad" render
contains "tasks 0 failed 2 times" "  naming the task and how often it failed"
finish
