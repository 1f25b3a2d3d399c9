#!/usr/bin/env bash
# The soak: flagd, its gateway (flagctl serve) and a recorder for a long session, in two parts.
#   fast  an hour of simulated time in --fast mode, the server recording its own inputs
#         (--record-inputs), with the chaos client and the protocol clients at work
#   real  ten minutes of real time: eight protocol clients on the gateway (bench/soak/clients.mjs),
#         the chaos client (bench/soak/chaos_client.cpp: random valid and invalid wind,
#         parameters, camera moves, keyframe edits, size changes, resets, keyframe requests and
#         questions, one at a time, each answer awaited) and flagctl record taking the whole bus
# Every 5 s it samples each process's resident memory and open file descriptors. At the end:
# memory after the warm-up (a tenth of each part, at least 30 s) against the end (medians of
# windows a warm-up long) and its trend, descriptors,
# commands sent and answered, whether every process lived and stopped cleanly, the real-time
# factor the clients saw, and flagd replay of both recordings (every hash equal, bit for bit).
#   bench/soak.sh [BUILD_DIR] [REAL_SECONDS=600] [FAST_SIMULATED_SECONDS=3600]
# Results in BUILD_DIR/bench/soak/: samples.csv, chaos-*.json, clients-*.json, summary.txt.
# Runs inside a private network namespace (scripts/netns-run), so nothing leaves the machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
real_seconds=${2:-600}
fast_seconds=${3:-3600}
if [[ -z ${FLAGSIM_IN_NETNS:-} ]]; then
  FLAGSIM_IN_NETNS=1 exec "$root/scripts/netns-run" -- "$0" "$build" "$real_seconds" "$fast_seconds"
fi
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
flagd=$build/server/flagd
flagctl=$build/client/flagctl
out=$build/bench/soak
rm -rf "$out"
mkdir -p "$out"
summary=$out/summary.txt
: >"$summary"
say() { echo "$*" | tee -a "$summary"; }
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true' EXIT

# sample PART NAME PID: one line of samples.csv (seconds since the part began, resident KB, fds).
sample() {
  local rss fds
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$3/status" 2>/dev/null) || return 0
  fds=$(ls "/proc/$3/fd" 2>/dev/null | wc -l)
  echo "$1,$2,$((SECONDS - part_start)),$rss,$fds" >>"$out/samples.csv"
}
echo "part,process,seconds,resident_kb,fds" >"$out/samples.csv"

# growth PART NAME WARMUP: the process's resident memory after the warm-up against the end, each
# the median of a window as long as the warm-up (a window, not one sample: the chaos client's image
# sizes and grids move memory up and down by megabytes for seconds at a time), the peak, the
# least-squares trend after the warm-up (a leak shows there whatever the windows), and descriptors.
growth() {
  awk -F, -v part="$1" -v name="$2" -v warm="$3" '
    function median(list, n,    i, j, v) {
      for (i = 2; i <= n; ++i) { v = list[i]; for (j = i - 1; j >= 1 && list[j] > v; --j) list[j + 1] = list[j]; list[j + 1] = v }
      return n % 2 ? list[(n + 1) / 2] : (list[n / 2] + list[n / 2 + 1]) / 2
    }
    $1 == part && $2 == name && $3 >= warm { ++n; t[n] = $3; rss[n] = $4 / 1024; fd[n] = $5 }
    END {
      if (n < 2) { printf "  %-9s too few samples after the warm-up\n", name; exit }
      peak = 0; fdmax = 0; st = 0; sr = 0; stt = 0; str = 0
      for (i = 1; i <= n; ++i) {
        if (rss[i] > peak) peak = rss[i]; if (fd[i] > fdmax) fdmax = fd[i]
        st += t[i]; sr += rss[i]; stt += t[i] * t[i]; str += t[i] * rss[i]
        if (t[i] < t[1] + warm) first[++nf] = rss[i]
        if (t[i] > t[n] - warm) last[++nl] = rss[i]
      }
      slope = (n * str - st * sr) / (n * stt - st * st)  # MB per s
      m0 = median(first, nf); m1 = median(last, nl)
      printf "  %-9s resident %6.1f MB after the warm-up (%d-%d s), %6.1f MB at the end (%d-%d s): %+.1f %%; peak %.1f MB; trend %+.1f MB/h; fds %d -> %d (at most %d)\n",
             name, m0, t[1], t[1] + warm, m1, t[n] - warm, t[n], 100 * (m1 - m0) / m0, peak, 3600 * slope, fd[1], fd[n], fdmax
    }' "$out/samples.csv" | tee -a "$summary"
}

# start_gateway: flagctl serve on a free port; sets gateway (its pid) and port.
start_gateway() {
  "$flagctl" serve --listen 127.0.0.1:0 --record-dir "$out" >"$out/serve-$1.log" 2>&1 &
  gateway=$!
  pids+=("$gateway")
  port=""
  for _ in $(seq 100); do
    port=$(sed -n 's#.*live view *http://[^:]*:\([0-9]*\)/.*#\1#p' "$out/serve-$1.log")
    [[ -n $port ]] && return
    sleep 0.1
  done
  echo "soak: no URL from flagctl serve" >&2
  exit 1
}

await_server() {
  for _ in $(seq 100); do
    "$flagctl" --timeout 0.5 status >/dev/null 2>&1 && return 0
    sleep 0.2
  done
  echo "soak: no answer from flagd" >&2
  exit 1
}

# stop NAME PID: SIGTERM, and its exit code, in the summary.
stop() {
  if ! kill -0 "$2" 2>/dev/null; then
    local code=0
    wait "$2" || code=$?
    say "  $1 had ended by itself, exit code $code"
    return
  fi
  kill -TERM "$2"
  local code=0
  wait "$2" || code=$?
  say "  $1 stopped on SIGTERM, exit code $code"
}

# replay NAME LOG: flagd replay of the log, its verdict in the summary.
replay() {
  local code=0
  "$flagd" replay "$2" --threads 2 >"$out/replay-$1.out" 2>&1 || code=$?
  say "  flagd replay of the $1 recording: exit $code"
  sed 's/^/    /' "$out/replay-$1.out" | tee -a "$summary"
}

# simulated_seconds: the server's simulated time, from its status.
simulated_seconds() {
  "$flagctl" --timeout 2 status 2>/dev/null | sed -n 's/^sim time: *\([0-9.]*\) s.*/\1/p'
}

# done_yet PART: whether the part has run its course: REAL_SECONDS of wall time, or
# FAST_SIMULATED_SECONDS of simulated time.
done_yet() {
  if [[ $1 == real ]]; then
    ((SECONDS - part_start >= real_seconds))
  else
    awk -v t="$(simulated_seconds)" -v end="$fast_seconds" 'BEGIN { exit !(t != "" && t >= end) }'
  fi
}

# run_part PART FLAGD_OPTION...: flagd, its gateway, the protocol clients, the chaos client and
# (real) a recorder, sampled every 5 s until the part is done; then the chaos client and the
# clients are stopped first (a command in flight is answered), the rest after them.
run_part() {
  local part=$1
  shift
  part_start=$SECONDS
  "$flagd" --log-level warn "$@" >"$out/flagd-$part.log" 2>&1 &
  local server=$!
  pids+=("$server")
  await_server
  start_gateway "$part"
  node "$root/bench/soak/clients.mjs" "ws://127.0.0.1:$port/" 8 86400 "$out/clients-$part.json" \
    >"$out/clients-$part.out" 2>&1 &
  local clients=$!
  pids+=("$clients")
  "$build/bench/chaos_client" --duration 86400 --seed 7 --report "$out/chaos-$part.json" \
    >"$out/chaos-$part.out" 2>&1 &
  local chaos=$!
  pids+=("$chaos")
  local recorder=""
  if [[ $part == real ]]; then
    "$flagctl" record -o "$out/real.lcmlog" >"$out/record-real.out" 2>&1 &
    recorder=$!
    pids+=("$recorder")
  fi
  while kill -0 "$server" 2>/dev/null && ! done_yet "$part"; do
    sample "$part" flagd "$server"
    sample "$part" gateway "$gateway"
    [[ -n $recorder ]] && sample "$part" recorder "$recorder"
    sleep 5
  done
  local chaos_code=0 clients_code=0
  kill -INT "$chaos" "$clients" 2>/dev/null || true
  wait "$chaos" || chaos_code=$?
  wait "$clients" || clients_code=$?
  local warm=$(((SECONDS - part_start) / 10))
  ((warm < 30)) && warm=30
  say "== $part: flagd $* ($((SECONDS - part_start)) s of wall time, $(simulated_seconds) s simulated)"
  growth "$part" flagd $warm
  growth "$part" gateway $warm
  [[ -n $recorder ]] && growth "$part" recorder $warm
  say "  chaos client (exit $chaos_code):"
  sed 's/^/    /' "$out/chaos-$part.out" | tee -a "$summary"
  say "  protocol clients (exit $clients_code): $(cat "$out/clients-$part.out")"
  [[ -n $recorder ]] && stop recorder "$recorder"
  stop gateway "$gateway"
  stop flagd "$server"
}

say "soak on $(nproc) cores, $(date -u +%Y-%m-%dT%H:%MZ): $real_seconds s of real time, $fast_seconds s simulated fast"
run_part fast --fast --record-inputs "$out/fast-inputs.lcmlog"
replay "fast part's own (--record-inputs)" "$out/fast-inputs.lcmlog"
run_part real
replay "real part's (flagctl record)" "$out/real.lcmlog"
say "results: $out"
