#!/usr/bin/env bash
# Configures and builds flagsim in build/ (Release).
#   scripts/build.sh                        everything: binaries, tests, benchmarks
#   scripts/build.sh --target flagd --target flagctl   only these (and what they need)
# Other arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=() configure=()
while (($#)); do
  case $1 in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) configure+=("$1"); shift ;;
  esac
done
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${configure[@]}" >/dev/null
cmake --build build "${targets[@]}"
