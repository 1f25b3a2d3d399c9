#!/usr/bin/env bash
# Several hosts on one bus: five network namespaces joined by a bridge (veth pairs; LCM's
# multicast with ttl=1 crossing it), inside the private namespace ctest gives this test
# (scripts/netns-run). Host 1 runs flagd with prefix ALPHA_, host 2 flagd with BETA_ (both taking
# only signed commands; small frames, 10 a second, since both share this machine's cores), host 3
# records each, host 4 runs one gateway for both (flagctl serve --servers all), host 5 steers
# both through 5 % loss on its link.
#   - how near real time each server runs beside the others (a figure, printed), and the
#     datagrams host 5's link lost (counted)
#   - the gateway offers both servers under their prefixes; a Foxglove client on host 4 takes
#     both pictures and steers one of them through it
#   - a command reaches its own server only, and is applied once though resent
#   - the recordings hold both sessions whole: each replays bit for bit
#   - signed commands are taken across hosts whose clocks differ within the freshness window
#     (30 s; host 5's clock set 20 s ahead), and refused as stale beyond it (45 s ahead)
# Usage: hosts_test.sh BUILD_DIR
set -euo pipefail
build=$1
for command in faketime nsenter nft; do
  command -v "$command" >/dev/null || { echo "skipped: no $command (scripts/install-deps.sh installs it)"; exit 77; }
done
flagd=$build/server/flagd flagctl=$build/client/flagctl
web_tests=$(cd "$(dirname "$0")/../web" && pwd)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=1"
work=$(mktemp -d)
daemons=()
stop() {
  for pid in "${daemons[@]}"; do kill "$pid" 2>/dev/null || true; done
  sleep 0.5
  for pid in "${daemons[@]}" "${holders[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
source "$(dirname "$0")/checks.sh"
source "$(dirname "$0")/hosts.sh"
trap stop EXIT
switch
for host in 1 2 3 4 5; do add_host "$host" 10.77.0 multicast; done
# Host 5's link loses 5 % of the datagrams each way.
on 5 nft add table ip link_loss
on 5 nft add chain ip link_loss input "{ type filter hook input priority 0; }"
on 5 nft add chain ip link_loss output "{ type filter hook output priority 0; }"
on 5 nft add rule ip link_loss input meta l4proto udp numgen random mod 100 lt 5 counter drop
on 5 nft add rule ip link_loss output meta l4proto udp numgen random mod 100 lt 5 counter drop
on 5 nft add rule ip link_loss input meta l4proto udp counter
on 5 nft add rule ip link_loss output meta l4proto udp counter
pass "five hosts on one bridge, host 5's link losing 5 % each way"

"$flagctl" keygen -o "$work/ops.key" >/dev/null
nsenter -t "${holders[1]}" -n "$flagd" --prefix ALPHA_ --key-file "$work/ops.key" --set frame_rate=10 --log-level warn >"$work/alpha.log" 2>&1 &
daemons+=($!)
nsenter -t "${holders[2]}" -n "$flagd" --prefix BETA_ --key-file "$work/ops.key" --set frame_rate=10 --log-level warn >"$work/beta.log" 2>&1 &
daemons+=($!)
for prefix in ALPHA_ BETA_; do
  if on 5 bash -c "source '$(dirname "$0")/checks.sh'; await_server '$flagctl' $prefix"; then
    pass "host 5 hears the server $prefix across the bridge"
  else
    fail "no STATUS of $prefix on host 5"
    finish
  fi
done

expect 0 "flagctl servers on host 5 lists both" on 5 "$flagctl" --timeout 3 servers
matches "^ALPHA_ " "  ALPHA_"
matches "^BETA_ " "  BETA_"

# The recorders ask for a keyframe and checkpoint as they start: signed, as every keyframe request
# to a server with keys must be.
# Small pictures: the test is of the bus, and two servers share this machine's cores.
for prefix in ALPHA_ BETA_; do
  on 5 "$flagctl" --key-file "$work/ops.key" --timeout 10 --prefix "$prefix" camera size 320 180 >/dev/null ||
    fail "camera size for $prefix"
done

nsenter -t "${holders[3]}" -n "$flagctl" --key-file "$work/ops.key" --prefix ALPHA_ record -o "$work/alpha.lcmlog" --duration 12 \
  >"$work/record-alpha.txt" 2>&1 &
recorders=($!)
nsenter -t "${holders[3]}" -n "$flagctl" --key-file "$work/ops.key" --prefix BETA_ record -o "$work/beta.lcmlog" --duration 12 \
  >"$work/record-beta.txt" 2>&1 &
recorders+=($!)
# Host 4: one gateway for both servers, signing what it relays.
nsenter -t "${holders[4]}" -n "$flagctl" --key-file "$work/ops.key" serve --servers all --listen 127.0.0.1:0 --record-dir "$work/gateway" \
  >"$work/serve.txt" 2>&1 &
daemons+=($!)
for _ in $(seq 100); do  # until both recorders are writing (at most 20 s)
  [[ -s $work/alpha.lcmlog && -s $work/beta.lcmlog ]] && break
  sleep 0.2
done

steer() { on 5 "$flagctl" --key-file "$work/ops.key" --timeout 10 "$@"; }
expect 0 "a wind for ALPHA_ from host 5, through the loss" steer --prefix ALPHA_ wind 9 0 2
matches "accepted at step" "  accepted"
expect 0 "a stiffness for BETA_ from host 5" steer --prefix BETA_ set stiffness=3500
expect 0 "ALPHA_'s parameters" on 5 "$flagctl" --timeout 10 --prefix ALPHA_ params
if grep -E "^stiffness " "$work/out" | grep -qv "3500"; then pass "  ALPHA_ kept its stiffness: the command reached BETA_ only"
else fail "  ALPHA_'s stiffness changed" "$work/out"; fi
expect 0 "BETA_'s parameters" on 5 "$flagctl" --timeout 10 --prefix BETA_ params
matches "^stiffness +3500 " "  BETA_ took it"

# Clocks that differ: host 5 runs 20 s ahead (within the 30 s window), then 45 s ahead.
expect 0 "a signed command from a host whose clock is 20 s ahead is taken" \
  on 5 env FAKETIME_DONT_FAKE_MONOTONIC=1 faketime -f +20s "$flagctl" --key-file "$work/ops.key" --timeout 10 \
  --prefix ALPHA_ set damping=0.08
expect 3 "one from a host 45 s ahead is refused" \
  on 5 env FAKETIME_DONT_FAKE_MONOTONIC=1 faketime -f +45s "$flagctl" --key-file "$work/ops.key" --timeout 10 \
  --prefix ALPHA_ set damping=0.09
contains "stale" "  as stale, saying so"

# Real time is a figure, not a check (a test does not time): simulated seconds gained over wall
# seconds between two STATUS some seconds apart, printed for docs/hosts.md.
sim_and_uptime() {  # PREFIX: "SIM UPTIME" from host 5
  on 5 "$flagctl" --timeout 10 --prefix "$1" status |
    awk '/^uptime:/ { up = $2 } /^sim time:/ { sim = $3 } END { print sim, up }'
}
for prefix in ALPHA_ BETA_; do
  read -r sim0 up0 <<<"$(sim_and_uptime "$prefix")"
  sleep 4
  read -r sim1 up1 <<<"$(sim_and_uptime "$prefix")"
  awk -v p="$prefix" -v a="$sim0" -v b="$sim1" -v c="$up0" -v d="$up1" \
    'BEGIN { if (d > c) printf "figure: %s ran at %.3f of real time over %.1f s, beside the other\n", p, (b - a) / (d - c), d - c }'
done

# The gateway on host 4, with Foxglove's own protocol client beside it (loopback in host 4).
if [[ -d $web_tests/node_modules ]] && command -v node >/dev/null; then
  port=$(gateway_port "$work/serve.txt") || fail "no URL from the gateway on host 4" "$work/serve.txt"
  expect 0 "a client of the gateway on host 4 watches both servers and steers BETA_" \
    on 4 node "$web_tests/servers_watch.mjs" "ws://127.0.0.1:$port/" --servers ALPHA_,BETA_ --seconds 3 --steer BETA_
  cat "$work/out"
  matches '"live":true,"path":"/ALPHA_"' "  the gateway lists ALPHA_, live"
  matches '"live":true,"path":"/BETA_"' "  and BETA_"
  matches '"ALPHA_":[1-9][0-9.]*,"BETA_":[1-9]' "  the client takes both pictures"
  matches '"steer":\{"accepted":true' "  BETA_ took the gateway's signed command"
  expect 0 "BETA_'s parameters after the gateway's command" on 5 "$flagctl" --timeout 10 --prefix BETA_ params
  matches "^damping +0.07 " "  BETA_ took it"
  expect 0 "ALPHA_'s parameters" on 5 "$flagctl" --timeout 10 --prefix ALPHA_ params
  matches "^damping +0.08 " "  ALPHA_ kept its own"
else
  echo "skipped: the gateway's part needs node and the tests' Node packages (a build with FLAGSIM_WEB)"
fi

# What host 5's link lost: nft's counters of the dropping rules against all UDP each way.
on 5 nft list table ip link_loss | awk '
  /drop/ { dropped[++d] = $(NF - 3) } /counter packets/ && !/drop/ { total[++t] = $(NF - 2) }
  END { for (i = 1; i <= 2; i++) if (total[i] > 0)
          printf "figure: host 5 %s: %d of %d UDP datagrams lost (%.1f %%)\n", i == 1 ? "in" : "out",
                 dropped[i], total[i] + dropped[i], 100 * dropped[i] / (total[i] + dropped[i]) }'

wait "${recorders[@]}" || true
for name in alpha beta; do
  prefix=${name^^}_
  cat "$work/record-$name.txt"
  expect 0 "the recording of $prefix on host 3 replays bit for bit" "$flagd" replay --prefix "$prefix" "$work/$name.lcmlog"
  contains "every hash equal, bit for bit" "  every hash equal"
  matches "[1-9][0-9]* command\(s\)" "  with the commands host 5 sent it"
done
finish
