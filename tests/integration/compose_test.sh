#!/usr/bin/env bash
# docker/compose.yaml runs N servers: checked as YAML (tests/web/compose_check.mjs) against a prefix
# flagd really draws with --prefix auto. No Docker is needed, and none is touched.
# Usage: compose_test.sh SOURCE_DIR BUILD_DIR NODE
set -euo pipefail
source_dir=$1 build=$2 node=$3
prefix=$("$build/server/flagd" --lcm-url memq:// --prefix auto --fast --duration 0.002 2>&1 |
  sed -n 's/.* with prefix \([A-Za-z0-9_]*\)$/\1/p')
[[ $prefix =~ ^FLAGSIM_[0-9A-F]{6}_$ ]] || { echo "FAIL  flagd --prefix auto said no prefix of its own: '$prefix'"; exit 1; }
echo "ok    flagd --prefix auto drew $prefix"
"$node" "$source_dir/tests/web/compose_check.mjs" "$source_dir/docker/compose.yaml" "$prefix"
