# What the tests of recordings that end badly (killed, a full disk) share, sourced after
# checks.sh; they set $work, $flagd, $flagctl and $prefix.

# status_step: the step of the server's last STATUS (flagctl status), or -1 without an answer.
status_step() {
  "$flagctl" --prefix "$prefix" --timeout 1 status 2>/dev/null |
    sed -n 's/^sim time: .*(step \([0-9]*\))$/\1/p' | grep . || echo -1
}

# await_step STEP: until the server's STATUS is past STEP (at most 60 s).
await_step() {
  for _ in $(seq 300); do
    (($(status_step) > $1)) && return 0
    sleep 0.2
  done
  return 1
}

# log_reads LOG WHAT: a recording of the bus reads to its last whole event: `flagctl export`
# makes PNG frames of it, and `flagd replay` steps it again with every hash equal.
log_reads() {
  local log=$1 what=$2 frames count
  frames=$(mktemp -d "$work/frames.XXXX")
  expect 0 "$what: flagctl export to PNG frames" "$flagctl" --prefix "$prefix" export "$log" -o "$frames/"
  count=$(find "$frames" -name '*.png' | wc -l)
  if ((count > 0)); then pass "  $count whole frame(s) exported"; else fail "  no frame exported" "$work/out"; fi
  expect 0 "$what: flagd replay" "$flagd" replay "$log" --prefix "$prefix"
  contains "every hash equal" "  every recorded hash equal"
  rm -rf "$frames"
}
