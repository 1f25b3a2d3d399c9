#!/usr/bin/env bash
# The bus across a network that carries no multicast, through LCM's TCP provider: three hosts as
# network namespaces on a bridge with no multicast route, inside the private namespace ctest gives
# this test (scripts/netns-run). Host 1 runs LCM's hub (lcm.lcm.TCPService, Java, from LCM's own
# jar), host 2 flagd on tcpq://10.78.0.1:7700, host 3 the client:
#   - multicast does not cross here: a udpm:// client on host 3 hears no server
#   - over tcpq:// host 3 reads the server's status, steers it, takes a whole frame and records
#     the session, which replays bit for bit
# Usage: tcp_bus_test.sh BUILD_DIR
set -euo pipefail
build=$1
lcm_jar=/usr/share/java/lcm.jar
for command in java nsenter; do
  command -v "$command" >/dev/null || { echo "skipped: no $command (scripts/install-deps.sh --java installs it)"; exit 77; }
done
[[ -f $lcm_jar ]] || { echo "skipped: no $lcm_jar (liblcm-java)"; exit 77; }
flagd=$build/server/flagd flagctl=$build/client/flagctl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT  # the rest ends with the test's PID namespace (scripts/netns-run)
source "$(dirname "$0")/checks.sh"
source "$(dirname "$0")/hosts.sh"

switch
for host in 1 2 3; do add_host "$host" 10.78.0; done  # no multicast route
bus=tcpq://10.78.0.1:7700

nsenter -t "${holders[1]}" -n java -cp "$lcm_jar" lcm.lcm.TCPService 7700 >"$work/hub.log" 2>&1 &
for _ in $(seq 100); do  # until the hub listens (at most 20 s)
  on 1 bash -c 'exec 3<>/dev/tcp/127.0.0.1/7700' 2>/dev/null && break
  sleep 0.2
done
nsenter -t "${holders[2]}" -n "$flagd" --lcm-url "$bus" --prefix TCP_ --set frame_rate=10 --log-level warn \
  >"$work/flagd.log" 2>&1 &
ok=""
for _ in $(seq 50); do
  on 3 "$flagctl" --lcm-url "$bus" --prefix TCP_ --timeout 0.5 status >/dev/null 2>&1 && { ok=1; break; }
  sleep 0.2
done
[[ -n $ok ]] && pass "host 3 hears the server on host 2 through the hub on host 1" ||
  { fail "no STATUS over $bus" "$work/flagd.log"; finish; }

if on 3 "$flagctl" --lcm-url "udpm://239.255.76.67:7667?ttl=1" --prefix TCP_ --timeout 1 status >"$work/out" 2>&1; then
  fail "a udpm:// client heard the server: this network carries multicast after all" "$work/out"
else
  pass "multicast does not cross this network (udpm:// hears nothing)"
fi

tcp() { on 3 "$flagctl" --lcm-url "$bus" --prefix TCP_ --timeout 10 "$@"; }
tcp record -o "$work/session.lcmlog" --duration 6 >"$work/record.txt" 2>&1 &
recorder=$!
await_bytes "$work/session.lcmlog" 0 || fail "the recorder on host 3 writes nothing"
expect 0 "a wind over tcpq" tcp wind 9 0 2
contains "accepted" "  accepted"
expect 0 "a stiffness over tcpq" tcp set stiffness=3500
expect 0 "the parameters over tcpq" tcp params
matches "^stiffness +3500 " "  the server took it"
expect 0 "a whole frame over tcpq" tcp snapshot -o "$work/frame.png"
matches "complete" "  assembled and hash-checked"
wait "$recorder" || true
cat "$work/record.txt"
expect 0 "the recording made over tcpq replays bit for bit" "$flagd" replay --prefix TCP_ "$work/session.lcmlog"
contains "every hash equal, bit for bit" "  every hash equal"
matches "[1-9][0-9]* command\(s\)" "  with the commands sent over tcpq"
finish
