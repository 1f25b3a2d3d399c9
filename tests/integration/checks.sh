# Checks shared by the integration scripts (sourced; they set $work, a scratch directory). Each
# prints "ok" or "FAIL" with what it checked and counts it; the script ends with
# `finish`, which exits 1 if any check failed.
failures=0
passes=0
# pass DESCRIPTION; fail DESCRIPTION [FILE]: count a check, FILE (indented) saying why it failed.
pass() {
  passes=$((passes + 1))
  echo "ok    $1"
}
fail() {
  failures=$((failures + 1))
  echo "FAIL  $1"
  if [[ -f ${2:-} ]]; then sed 's/^/      /' "$2"; fi
  return 0
}
# expect CODE DESCRIPTION COMMAND...: runs COMMAND, checks its exit code, keeps its output.
expect() {
  local code=$1 what=$2
  shift 2
  local got=0 start=$SECONDS
  "$@" >"$work/out" 2>&1 || got=$?
  local took=$((SECONDS - start))
  if [[ $got == "$code" ]]; then pass "$what (exit $got, ${took} s)"
  else fail "$what: exit $got after ${took} s, expected $code" "$work/out"; fi
}
# found GREP_MODE PATTERN DESCRIPTION: the last command's output has PATTERN.
found() {
  if grep -q "$1" -- "$2" "$work/out"; then pass "$3"
  else fail "$3: no '$2' in:" "$work/out"; fi
}
contains() { found -F "$@"; }  # fixed text
matches() { found -E "$@"; }   # extended regular expression
# await_server FLAGCTL PREFIX: until a server on PREFIX answers status (at most 10 s).
await_server() {
  for _ in $(seq 50); do
    "$1" --prefix "$2" --timeout 0.5 status >/dev/null 2>&1 && return 0
    sleep 0.2
  done
  return 1
}
# await_bytes FILE BYTES: until FILE holds more than BYTES (at most 30 s): a recorder is taking
# what the bus carries.
await_bytes() {
  for _ in $(seq 300); do
    (($(stat -c %s "$1" 2>/dev/null || echo 0) > $2)) && return 0
    sleep 0.1
  done
  return 1
}
# await_text FILE PATTERN [SECONDS]: until FILE has a line matching the extended regular
# expression PATTERN (at most SECONDS, 30 by default): a reader running in the background has seen
# what the test waits for.
await_text() {
  for _ in $(seq $((${3:-30} * 10))); do
    grep -Eq -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  return 1
}
# gateway_url LOG: the first address `flagctl serve` printed in LOG, the live view's (it listens
# on port 0: a free one; at most 10 s). gateway_port LOG: its port.
gateway_url() {
  for _ in $(seq 100); do
    if grep -q "live view" "$1"; then
      sed -n 's#.*live view *\(https\?://[^ ]*\).*#\1#p' "$1" | head -1
      return 0
    fi
    sleep 0.1
  done
  echo "no URL in $1" >&2
  cat "$1" >&2
  return 1
}
gateway_port() {
  local url
  url=$(gateway_url "$1") || return 1
  sed 's#^https\?://[^/]*:\([0-9]*\)/.*#\1#' <<<"$url"
}
# finish: the tally, and the exit code.
finish() {
  echo "$passes passed, $failures failed"
  [[ $failures == 0 ]]
}
