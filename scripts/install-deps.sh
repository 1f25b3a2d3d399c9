#!/usr/bin/env bash
# Installs what flagsim needs to build, test and run, from Debian's packages (bookworm).
# Idempotent and non-interactive: installs only what is missing.
#   scripts/install-deps.sh          build and run
#   scripts/install-deps.sh --browser  also Chromium, for the live view's browser tests
#   scripts/install-deps.sh --java   also a JDK: the lcm-spy types jar, LCM's TCP hub (integration.tcp_bus) and
#                                    the Java binding's check (messages.bindings)
#   scripts/install-deps.sh --sanitize  also clang 14, its sanitizer runtimes and symbolizer (test.sh --sanitize)
#   scripts/install-deps.sh --bench  also Mesa's EGL and OpenGL (the llvmpipe comparison), Bullet (the soft body
#                                    comparison) and gnuplot (charts)
#   scripts/install-deps.sh --fuzz   also clang 14 and libFuzzer, for the fuzz targets (scripts/fuzz.sh)
#   scripts/install-deps.sh --slurm  also Slurm's daemons, client and munge: integration.slurm starts a
#                                    one-node cluster of its own (nothing starts by itself)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # toolchain
  libeigen3-dev                                  # linear algebra (given)
  liblcm-dev liblcm-bin liblcm-java              # LCM 1.3.1: library, lcm-gen/logger/logplayer, lcm.jar
  liblcm-lua lua5.2                              # LCM's Lua module and its Lua: the bindings test decodes a log in Lua
  libcli11-dev                                   # command lines of flagd and flagctl
  libtomlplusplus-dev                            # scene files (TOML)
  libspdlog-dev                                  # server logging
  libzstd-dev libxxhash-dev                      # tile compression, image and state hashes
  libpng-dev                                     # snapshots and exported frames
  libssl-dev                                     # signed commands: OpenSSL's HMAC-SHA-256 and random keys
  libboost-dev nlohmann-json3-dev libjpeg-dev    # the live view's gateway: HTTP/WebSocket, JSON, JPEG
  ffmpeg                                         # flagctl export's MP4 and GIF encoder; ffprobe for its test
  libgtest-dev libbenchmark-dev                  # tests and benchmarks
  iproute2 nftables util-linux                   # private network namespaces for the udpm tests
  faketime                                       # integration.hosts: a host whose clock runs ahead
)
for option in "$@"; do
  case $option in
    --browser) packages+=(chromium) ;;
    --java) packages+=(default-jdk-headless) ;;
    --sanitize) packages+=(clang-14 libclang-rt-14-dev llvm-14) ;;  # llvm-14: llvm-symbolizer, for reports
    --bench) packages+=(libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri gnuplot-nox libbullet-dev) ;;
    --fuzz) packages+=(clang-14 libfuzzer-14-dev libclang-rt-14-dev llvm-14) ;;
    --slurm) packages+=(slurmctld slurmd slurm-client munge) ;;
    *) echo "install-deps: unknown option $option (known: --browser, --java, --sanitize, --bench, --fuzz, --slurm)" >&2; exit 2 ;;
  esac
done
# Node.js and npm build the live view's page (and run its tests): the machine's own if it has
# them, else Debian's.
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=()
if [[ $(id -u) != 0 ]]; then sudo=(sudo); fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
