#!/usr/bin/env bash
# Builds the fuzz targets (tests/fuzz, docs/fuzzing.md) with clang, libFuzzer, AddressSanitizer
# and UndefinedBehaviorSanitizer in build-fuzz/, and runs each for SECONDS (default 60) on a
# scratch copy of its seed corpus, with a per-input time and memory limit, then runs every input
# of the grown corpus once more with LeakSanitizer checking each (a leak check after every input
# while fuzzing would take most of the time: the bus's library keeps a little memory per
# instance, so libFuzzer checks them all). Any crash, sanitizer report, timeout, leak or
# out-of-memory input is saved. Ends with a table per target and exits 1 if any target found
# something.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     every target, or those named (e.g. png replay)
#
# FUZZ_JOBS=N runs N targets at a time (default 1; each takes one core). Each target's run is in
# build-fuzz/fuzz/TARGET/: corpus/ (the seeds and what the run added), findings/ (the inputs
# that failed, each replayable with build-fuzz/tests/fuzz/TARGET_fuzz FILE), fuzz.log and
# leaks.log.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then
  seconds=$1
  shift
fi
jobs=${FUZZ_JOBS:-1}
timeout_per_input=10  # s: an input taking longer is a finding (a hang)
rss_limit_mb=2048     # a run growing past this is a finding (out of memory)

scripts/install-deps.sh --fuzz
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  -DFLAGSIM_FUZZ=ON -DFLAGSIM_SANITIZE=address,undefined -DFLAGSIM_BUILD_BENCH=OFF -DFLAGSIM_WEB=OFF >/dev/null
cmake --build build-fuzz --target flagsim_fuzz_targets -- -j2

targets=("$@")
if ((${#targets[@]} == 0)); then
  for source in tests/fuzz/*_fuzz.cpp; do
    name=$(basename "$source" _fuzz.cpp)
    targets+=("$name")
  done
fi

export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1
runs=build-fuzz/fuzz

# One target: a fresh copy of its seeds, then libFuzzer for `seconds`, then the leak check of
# what it grew.
run_target() {
  local name=$1 dir=$runs/$1
  local fuzzer=build-fuzz/tests/fuzz/${name}_fuzz
  local limits=(-timeout=$timeout_per_input -rss_limit_mb=$rss_limit_mb -artifact_prefix="$dir/findings/")
  rm -rf "$dir"
  mkdir -p "$dir/corpus" "$dir/findings"
  cp tests/fuzz/corpus/"$name"/* "$dir/corpus/"
  # A finding ends a run with a non-zero status; findings are counted from findings/ below.
  "$fuzzer" "$dir/corpus" -max_total_time="$seconds" -detect_leaks=0 -print_final_stats=1 "${limits[@]}" \
    >"$dir/fuzz.log" 2>&1 || true
  "$fuzzer" -runs=0 -detect_leaks=1 "${limits[@]}" "$dir/corpus" >"$dir/leaks.log" 2>&1 || true
}

echo "fuzz: ${#targets[@]} target(s), ${seconds} s each, $jobs at a time"
for name in "${targets[@]}"; do
  [[ -f tests/fuzz/${name}_fuzz.cpp ]] || { echo "fuzz: no target $name" >&2; exit 2; }
  while (($(jobs -rp | wc -l) >= jobs)); do wait -n; done
  run_target "$name" &
done
wait

# The table: libFuzzer's figures from each log (the INITED line for the start, the last status
# line and the final stats for the end).
summary=$runs/summary.txt
{
  printf '%-18s %9s %8s %8s %13s %13s %s\n' target "exec/s" seeds corpus "cov start/end" "ft start/end" findings
  for name in "${targets[@]}"; do
    log=$runs/$name/fuzz.log
    seeds=$(find tests/fuzz/corpus/"$name" -type f | wc -l)
    corpus=$(find "$runs/$name/corpus" -type f | wc -l)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
    start=$(grep -m1 'INITED' "$log" || true)
    end=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
    field() { sed -n "s/.* $1: \\([0-9]*\\).*/\\1/p" <<<"$2"; }
    findings=$(find "$runs/$name/findings" -type f | wc -l)
    list=$(find "$runs/$name/findings" -type f -printf '%f ' | cut -c1-60)
    printf '%-18s %9s %8s %8s %13s %13s %s\n' "$name" "${rate:-?}" "$seeds" "$corpus" \
      "$(field cov "$start")/$(field cov "$end")" "$(field ft "$start")/$(field ft "$end")" \
      "$findings${list:+ ($list)}"
  done
} | tee "$summary"
echo "fuzz: table in $summary; logs, corpora and findings in $runs/TARGET/"
found=0
for name in "${targets[@]}"; do found=$((found + $(find "$runs/$name/findings" -type f | wc -l))); done
if ((found > 0)); then
  echo "fuzz: $found finding(s): each input in $runs/TARGET/findings/ replays with build-fuzz/tests/fuzz/TARGET_fuzz FILE" >&2
  exit 1
fi
