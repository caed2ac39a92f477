#!/usr/bin/env bash
# Installs the pinned flubber into DIR with npm (no global install; nothing
# from node_modules is committed) and prints the installed version.
# Used by scripts/peer-compare.sh and scripts/bench-table.sh.
#
# Usage: scripts/peer/install-flubber.sh DIR
set -euo pipefail

FLUBBER_VERSION=0.4.2
dir=${1:?usage: install-flubber.sh DIR}

for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "install-flubber: '$tool' is not installed or not on PATH" >&2
    exit 1
  fi
done

echo "install-flubber: installing flubber@$FLUBBER_VERSION into $dir" >&2
mkdir -p "$dir"
(
  cd "$dir"
  echo '{"name": "immerse-peer-compare", "private": true}' > package.json
  npm install --silent --no-audit --no-fund --no-save "flubber@$FLUBBER_VERSION" >&2
) || { echo "install-flubber: npm install flubber@$FLUBBER_VERSION failed" >&2; exit 1; }
node -p "require('$dir/node_modules/flubber/package.json').version"
