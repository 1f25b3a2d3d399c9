#!/usr/bin/env bash
# Builds the flagsim container image (docker/Dockerfile) and runs commands in it.
#   scripts/docker.sh build                     build the image, or bring it up to date
#   scripts/docker.sh run [--] [CMD [ARG...]]   run CMD in the image (building it first if there is
#                                               none); without CMD, the image's own command (flagd)
#   e.g. scripts/docker.sh run -- flagd --fast --duration 2
#
# With Docker when a Docker engine answers; otherwise with buildah, which needs no daemon and so
# also works on build machines and inside other containers. On the buildah path the base image
# debian:bookworm is taken from local storage, or, when it is not there, made from Debian's
# package mirror with debootstrap: a machine that reaches a Debian mirror but no container
# registry can still build. That path runs as root (chroot isolation and debootstrap need it)
# and installs buildah and debootstrap with apt-get when they are missing.
#
# Containers use the host's network (Docker: --network host; buildah's chroot isolation has no
# network of its own), because LCM's multicast does not cross Docker's bridge networks. Mind the
# multicast TTL in LCM_DEFAULT_URL: ttl=0, the default, keeps every datagram on this host.
#
# Environment:
#   FLAGSIM_IMAGE           image name (default: flagsim)
#   FLAGSIM_ENGINE          docker or buildah, to choose instead of detecting
#   FLAGSIM_MARCH           the image's target CPU (default: x86-64, any; x86-64-v3 for AVX2
#                           machines only, faster)
#   FLAGSIM_PULL_BASE=1     buildah: try to pull debian:bookworm from a registry before
#                           bootstrapping it (off by default: isolated machines would only wait)
#   FLAGSIM_STORAGE_DRIVER  buildah storage driver (default: vfs)
#   DEBIAN_MIRROR           mirror to bootstrap from (default: this host's Debian source, else
#                           http://deb.debian.org/debian)
#   LCM_DEFAULT_URL         passed into the container when set
set -euo pipefail

readonly image=${FLAGSIM_IMAGE:-flagsim}
readonly march=${FLAGSIM_MARCH:-x86-64}
readonly base_image=debian:bookworm
readonly suite=bookworm
readonly keyring=/usr/share/keyrings/debian-archive-keyring.gpg
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
readonly repo_root

say() { echo "docker.sh: $*" >&2; }
die() { say "error: $*"; exit 1; }

# usage [STATUS] : the header's first lines; on stdout when asked for, on stderr after a mistake.
usage() {
  local status=${1:-2}
  if ((status == 0)); then
    sed -n '2,6s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"
  else
    sed -n '2,6s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2
  fi
  exit "$status"
}

# ---- cleanup: temporary files and working containers are removed however the script ends --------
temp_paths=()
buildah_containers=()
cleanup() {
  local ctr
  for ctr in "${buildah_containers[@]}"; do buildah_cmd rm "$ctr" >/dev/null 2>&1 || true; done
  ((${#temp_paths[@]} == 0)) || rm -rf -- "${temp_paths[@]}"
}
trap cleanup EXIT

# ---- choosing the engine -------------------------------------------------------------------------
pick_engine() {
  case ${FLAGSIM_ENGINE:-} in
    docker | buildah) echo "$FLAGSIM_ENGINE"; return ;;
    '') ;;
    *) die "FLAGSIM_ENGINE must be docker or buildah, not '$FLAGSIM_ENGINE'" ;;
  esac
  # A docker client alone is not enough: it must reach an engine. The timeout keeps a stale
  # DOCKER_HOST from stalling every call.
  if command -v docker >/dev/null && timeout 20 docker info >/dev/null 2>&1; then
    echo docker
  else
    echo buildah
  fi
}

# npm's trust, as this host has it: when the host's npm is told to trust a certificate authority
# of its own (`npm config get cafile`: a TLS-inspecting proxy's, say), the build stage's npm,
# which fetches the page's packages, gets the same file (npm-ca.pem in the build context, removed
# after the build; the runtime image never sees it).
stage_npm_ca() {
  local cafile
  cafile=$(npm config get cafile 2>/dev/null || true)
  [[ -n $cafile && $cafile != null && -f $cafile ]] || return 0
  cp "$cafile" "$repo_root/npm-ca.pem"
  temp_paths+=("$repo_root/npm-ca.pem")
}

# ---- Docker --------------------------------------------------------------------------------------
docker_build() {
  stage_npm_ca
  docker build --build-arg FLAGSIM_MARCH="$march" -t "$image" -f "$repo_root/docker/Dockerfile" "$repo_root"
}

docker_run() {
  docker image inspect "$image" >/dev/null 2>&1 || docker_build
  # --init: a small PID 1 that forwards signals and reaps children, so that any command, not
  # only one that handles SIGTERM itself, stops on Ctrl-C and `docker stop`.
  local options=(--rm --init --interactive --network host)
  [[ -t 0 && -t 1 ]] && options+=(--tty)
  [[ -n ${LCM_DEFAULT_URL:-} ]] && options+=(--env "LCM_DEFAULT_URL=$LCM_DEFAULT_URL")
  docker run "${options[@]}" "$image" "$@"
}

# ---- buildah -------------------------------------------------------------------------------------
# vfs works everywhere, also where overlay mounts cannot nest (inside another container); it costs
# disk space (each layer is a full copy), not correctness.
buildah_cmd() { buildah --storage-driver "${FLAGSIM_STORAGE_DRIVER:-vfs}" "$@"; }

buildah_has_image() { buildah_cmd inspect --type image "$1" >/dev/null 2>&1; }

# Re-runs this script, with the arguments it was given, as root: chroot isolation and
# debootstrap need it.
need_root() {
  ((EUID == 0)) && return
  command -v sudo >/dev/null || die "the buildah path needs root; run this script as root"
  say "the buildah path needs root: re-running with sudo"
  local keep=FLAGSIM_IMAGE,FLAGSIM_ENGINE,FLAGSIM_PULL_BASE,FLAGSIM_STORAGE_DRIVER
  keep+=,DEBIAN_MIRROR,LCM_DEFAULT_URL
  exec sudo --preserve-env="$keep" -- "${BASH_SOURCE[0]}" "${script_args[@]}"
}

# install_packages PACKAGE... : from Debian's packages, quietly.
install_packages() {
  command -v apt-get >/dev/null || die "$* missing, and no apt-get here: install $* and retry"
  say "installing $* from Debian's packages"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

# The Debian mirror this host already uses (deb822 first, then one-line sources), so the
# bootstrap goes where apt-get goes; deb.debian.org when the host has none for bookworm.
debian_mirror() {
  if [[ -n ${DEBIAN_MIRROR:-} ]]; then echo "$DEBIAN_MIRROR"; return; fi
  local mirror=''
  if [[ -r /etc/apt/sources.list.d/debian.sources ]]; then
    mirror=$(awk '$1 == "URIs:" { print $2; exit }' /etc/apt/sources.list.d/debian.sources)
  fi
  if [[ -z $mirror && -r /etc/apt/sources.list ]]; then
    # One-line entries may carry [options] before the URI: drop them first.
    mirror=$(sed -E 's/\[[^]]*\]//' /etc/apt/sources.list \
      | awk -v s="$suite" '$1 == "deb" && $3 == s { print $2; exit }')
  fi
  echo "${mirror:-http://deb.debian.org/debian}"
}

# Gives the bootstrapped system the same apt sources as the official image (the release,
# its updates and security), so `apt-get install` in the Dockerfile sees current packages.
write_apt_sources() {
  local rootfs=$1 mirror=${2%/} security=http://deb.debian.org/debian-security
  [[ $mirror == */debian ]] && security=$mirror-security
  rm -f "$rootfs/etc/apt/sources.list"
  cat >"$rootfs/etc/apt/sources.list.d/debian.sources" <<EOF
Types: deb
URIs: $mirror
Suites: $suite $suite-updates
Components: main
Signed-By: $keyring

Types: deb
URIs: $security
Suites: $suite-security
Components: main
Signed-By: $keyring
EOF
}

# Settings every container image wants, as the official one has them: apt keeps no package
# caches or translations (they would only bloat each layer that installs something), and package
# scripts start no services (an image build has no init to run them).
write_container_config() {
  local rootfs=$1
  cat >"$rootfs/etc/apt/apt.conf.d/90container" <<'EOF'
Dir::Cache::pkgcache "";
Dir::Cache::srcpkgcache "";
Acquire::Languages "none";
DPkg::Post-Invoke { "rm -f /var/cache/apt/archives/*.deb || true"; };
EOF
  printf '#!/bin/sh\nexit 101\n' >"$rootfs/usr/sbin/policy-rc.d"
  chmod 755 "$rootfs/usr/sbin/policy-rc.d"
}

# Drops what debootstrap leaves behind that no image should carry: package lists and caches.
trim_rootfs() {
  local rootfs=$1
  rm -rf "$rootfs"/var/lib/apt/lists/* "$rootfs"/var/cache/apt/*.bin
  rm -f "$rootfs"/var/cache/apt/archives/*.deb
  rm -f "$rootfs"/var/log/bootstrap.log
}

# debootstrap installs the release as it was; this adds what -updates and -security have fixed
# since, as a freshly published official image would have it.
upgrade_container() {
  buildah_cmd run --isolation chroot --env DEBIAN_FRONTEND=noninteractive "$1" -- sh -c \
    'apt-get update -qq && apt-get upgrade -y -qq >/dev/null && rm -rf /var/lib/apt/lists/*'
}

# commit_rootfs DIR : stores DIR, brought up to date, as localhost/$base_image in buildah's local
# storage. The localhost/ name says it was made here; FROM debian:bookworm finds it all the same.
commit_rootfs() {
  local rootfs=$1 ctr mount_point
  ctr=$(buildah_cmd from scratch)
  buildah_containers+=("$ctr")
  mount_point=$(buildah_cmd mount "$ctr")
  cp -a "$rootfs"/. "$mount_point"/
  buildah_cmd umount "$ctr" >/dev/null
  # The same defaults as the official image: a shell to start with.
  buildah_cmd config --cmd bash \
    --env PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin "$ctr"
  upgrade_container "$ctr"
  buildah_cmd commit --quiet "$ctr" "localhost/$base_image" >/dev/null
}

# Makes $base_image from Debian's package mirror: the only source some machines can reach.
bootstrap_base() {
  if ! command -v debootstrap >/dev/null || [[ ! -r $keyring ]]; then
    install_packages debootstrap debian-archive-keyring gpgv
  fi
  local mirror rootfs log
  mirror=$(debian_mirror)
  rootfs=$(mktemp -d "${TMPDIR:-/var/tmp}/flagsim-rootfs.XXXXXX")
  log=$(mktemp "${TMPDIR:-/var/tmp}/flagsim-debootstrap.XXXXXX.log")
  temp_paths+=("$rootfs")
  say "making $base_image from $mirror with debootstrap (a minute or two, once per machine)"
  # --keyring: verify the mirror's signatures, and fail rather than go on unverified.
  debootstrap --variant=minbase --keyring="$keyring" "$suite" "$rootfs" "$mirror" >"$log" 2>&1 \
    || die "debootstrap failed; its log is $log"
  rm -f "$log"
  write_apt_sources "$rootfs" "$mirror"
  write_container_config "$rootfs"
  trim_rootfs "$rootfs"
  commit_rootfs "$rootfs"
  say "made localhost/$base_image in buildah's local storage"
}

# The base image must be local: the build itself never pulls (--pull=never).
ensure_base() {
  buildah_has_image "$base_image" && return
  if [[ ${FLAGSIM_PULL_BASE:-0} == 1 ]]; then
    buildah_cmd pull "docker.io/library/$base_image" && return
    say "could not pull $base_image from a registry: bootstrapping it instead"
  fi
  bootstrap_base
}

buildah_build() {
  command -v buildah >/dev/null || install_packages buildah
  ensure_base
  stage_npm_ca
  # --layers keeps each step's result, so a source change does not reinstall the toolchain.
  buildah_cmd bud --pull=never --isolation chroot --layers --build-arg FLAGSIM_MARCH="$march" \
    -t "$image" -f "$repo_root/docker/Dockerfile" "$repo_root"
}

# The image's CMD, one word a line, for running it when no command was given
# (buildah run, unlike docker run, needs one).
buildah_image_cmd() {
  local template='{{range .OCIv1.Config.Cmd}}{{println .}}{{end}}'
  buildah_cmd inspect --type image --format "$template" "$image"
}

buildah_run() {
  command -v buildah >/dev/null || install_packages buildah
  buildah_has_image "$image" || buildah_build
  local command=("$@")
  ((${#command[@]})) || mapfile -t command < <(buildah_image_cmd)
  ((${#command[@]})) || die "no command given and the image $image has none"
  local ctr options=(--isolation chroot)
  [[ -t 0 && -t 1 ]] && options+=(--tty)
  [[ -n ${LCM_DEFAULT_URL:-} ]] && options+=(--env "LCM_DEFAULT_URL=$LCM_DEFAULT_URL")
  ctr=$(buildah_cmd from --pull=never --quiet "$image")
  buildah_containers+=("$ctr")
  buildah_cmd run "${options[@]}" "$ctr" -- "${command[@]}"
}

# ---- command line --------------------------------------------------------------------------------
main() {
  (($#)) || usage
  local action=$1
  shift
  case $action in
    build) (($# == 0)) || usage ;;
    run) [[ ${1:-} != -- ]] || shift ;;
    -h | --help | help) usage 0 ;;
    *) say "unknown command '$action'"; usage ;;
  esac

  local engine
  engine=$(pick_engine)
  [[ $engine == docker ]] || need_root
  say "using $engine"
  "${engine}_${action}" "$@"
}

script_args=("$@")
main "$@"
