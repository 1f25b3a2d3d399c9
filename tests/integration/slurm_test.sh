#!/usr/bin/env bash
# A sweep and a batch render through a real one-node Slurm cluster, started here in a private
# network namespace (ctest runs this through scripts/netns-run) and stopped by pid at the end;
# their gathered results must equal a local run's bit for bit, but for the cost column, which is
# timing. A task whose record is missing is run again, alone, by --resume.
# Usage: slurm_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1 build=$2
for command in munged slurmctld slurmd sbatch squeue sinfo; do
  if ! command -v "$command" >/dev/null; then
    echo "skipped: no $command: Slurm is not installed here (scripts/install-deps.sh --slurm installs it)"
    exit 77
  fi
done
work=$(mktemp -d)
chmod 0755 "$work"
pids=()
stop() {
  # the jobs' processes first (scontrol knows them), then the daemons, TERM and then KILL
  for pid in $(scontrol listpids 2>/dev/null | awk 'NR > 1 {print $1}'); do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  sleep 0.5
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap stop EXIT
source "$(dirname "$0")/checks.sh"

# slurmctld looks its address up and needs a loopback address besides 127.0.0.1; it runs as the
# controller only on the host SlurmctldHost names (this one), which the node need not be.
ip addr add 127.0.0.2/8 dev lo

# munge: a key of our own, its socket's folder open to all, nothing on its path writable by others.
mkdir -m 0711 "$work/munge"
mkdir -m 0711 "$work/munge/run"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 0600 "$work/munge/munge.key"
munged -F --force --socket="$work/munge/run/munge.socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/seed" &
pids+=($!)

node=flagsim-node
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<EOF
ClusterName=flagsim
SlurmctldHost=$(hostname -s)(127.0.0.1)
MailProg=/bin/true
SlurmUser=root
SlurmctldPort=6817
SlurmdPort=6818
AuthType=auth/munge
AuthInfo=socket=$work/munge/run/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
MessageTimeout=5
ReturnToService=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=flagsim Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
for _ in $(seq 50); do [[ -S $work/munge/run/munge.socket ]] && break; sleep 0.1; done
slurmctld -D -f "$SLURM_CONF" >/dev/null 2>&1 &
pids+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" >/dev/null 2>&1 &
pids+=($!)
idle="" started=$SECONDS
while ((SECONDS - started < 20)); do
  idle=$(timeout 5 sinfo -h -o %t 2>/dev/null || true)
  [[ $idle == idle ]] && break
  sleep 0.2
done
if [[ $idle == idle ]]; then pass "a one-node Slurm cluster is up, its node idle"
else
  fail "no idle node after 20 s (sinfo: '$idle')" "$work/slurmctld.log"
  finish
fi

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
