# Hosts as network namespaces on one bridge, for the tests of a bus across hosts; sourced, inside
# the private namespace ctest gives the test (scripts/netns-run), whose end ends them.
holders=()  # by host number: the process holding its namespace

# switch: the bridge the hosts are plugged into; it floods multicast to every port (no
# snooping), as an unmanaged switch does.
switch() {
  ip link add switch type bridge mcast_snooping 0
  ip link set switch up
}

# on HOST COMMAND...: runs COMMAND in host HOST's network namespace. In the background, start it
# with `nsenter -t "${holders[HOST]}" -n COMMAND &` instead, so that $! is COMMAND's own pid
# (nsenter execs it) and not a subshell's, which a kill would leave COMMAND running past.
on() {
  local host=$1
  shift
  nsenter -t "${holders[$host]}" -n "$@"
}

# add_host N SUBNET [multicast]: a namespace held by a sleeping process, its end of a veth pair on
# the switch, SUBNET.N/24; with `multicast`, the multicast group routed out of it (without, LCM's
# udpm:// reaches no other host).
add_host() {
  local host=$1 subnet=$2
  unshare --net sleep 100000 &
  holders[$host]=$!
  while [[ $(readlink "/proc/${holders[$host]}/ns/net") == $(readlink /proc/self/ns/net) ]]; do sleep 0.01; done
  ip link add "h$host" type veth peer name "port$host"
  ip link set "h$host" netns "${holders[$host]}"
  ip link set "port$host" master switch up
  on "$host" ip link set lo up
  on "$host" ip addr add "$subnet.$host/24" dev "h$host"
  on "$host" ip link set "h$host" up
  if [[ ${3:-} == multicast ]]; then
    on "$host" ip link set "h$host" multicast on
    on "$host" ip route add 224.0.0.0/4 dev "h$host"
  fi
}
