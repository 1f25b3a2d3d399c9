#!/usr/bin/env bash
# Installs what is missing, builds, and runs the tests with CTest.
#   scripts/test.sh [CTEST_ARGS...]                      Release build in build/: every test
#   scripts/test.sh --sanitize address [CTEST_ARGS...]   AddressSanitizer with LeakSanitizer and
#                                                        UndefinedBehaviorSanitizer, in build-asan/
#   scripts/test.sh --sanitize thread [CTEST_ARGS...]    ThreadSanitizer, in build-tsan/: the tests
#                                                        labelled threaded (tests/unit_labels.cmake)
# Extra arguments go to ctest: -L unit (the unit suites only), -R WorkerPool, -j2, ...
# Under a sanitizer any report fails its test (the process exits with an error).
# The sanitizer builds are -O1 with line tables (reports name the file and line; two physics
# tests took 29 s under ASan at -O1 and at -O2 alike) and leave out the benchmarks; asked for the
# unit suites only (-L unit, or ThreadSanitizer's threaded ones), they build only those. They use
# clang 14 (scripts/install-deps.sh --sanitize installs it): with ASan and UBSan it compiled the
# gateway's heaviest file in 42 s of CPU where gcc 12 took 100 s, and its UBSan keeps the vptr
# check that gcc's misfires on (CMakeLists.txt). Suppressions (tests/sanitizers/) cover only
# libraries we do not build.
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=""
if [[ ${1:-} == --sanitize ]]; then
  sanitize=${2:-}
  shift 2 || true
fi
case $sanitize in
  "")
    scripts/install-deps.sh --browser --slurm --java
    scripts/build.sh
    # The unit suites side by side; the integration tests one at a time (RUN_SERIAL).
    exec ctest --test-dir build --output-on-failure --timeout 300 -j"$(nproc)" "$@" ;;
  address) build=build-asan sanitizers=address,undefined ;;
  thread) build=build-tsan sanitizers=thread
    set -- -L threaded "$@" ;;
  *) echo "test.sh: unknown sanitizer '$sanitize' (known: --sanitize address, --sanitize thread)" >&2; exit 2 ;;
esac

scripts/install-deps.sh --browser --sanitize
cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" -DFLAGSIM_SANITIZE="$sanitizers" \
  -DFLAGSIM_BUILD_BENCH=OFF >/dev/null
targets=()
if [[ $sanitize == thread || " $* " == *" -L unit "* ]]; then targets=(--target unit_tests); fi
cmake --build "$build" --parallel "$(nproc)" "${targets[@]}"

# What a report does: print the stack with file and line, then end the process with an error.
supp=$PWD/tests/sanitizers
symbolizer=/usr/lib/llvm-14/bin/llvm-symbolizer
export ASAN_OPTIONS="detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:external_symbolizer_path=$symbolizer"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:external_symbolizer_path=$symbolizer"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp:print_suppressions=0:external_symbolizer_path=$symbolizer"
# Instrumented code runs several times slower: a longer timeout than the normal run's.
exec ctest --test-dir "$build" --output-on-failure --timeout 1200 "$@"
