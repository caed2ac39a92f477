#!/usr/bin/env bash
# Peer comparison: immerse against flubber (npm) and a plain linear
# interpolation, on the same pairs of curves.
#
# Usage: scripts/peer-compare.sh [MAX_SEGMENT_LENGTH]
#
# 1. Creates a temporary folder (mktemp -d) and installs the pinned
#    flubber version into it with scripts/peer/install-flubber.sh (npm, no
#    global install; nothing from node_modules is committed). The folder
#    is removed on exit.
# 2. `cargo run --release --example peer_check -- export DIR` writes the
#    pairs (cleaned, oriented points as immerse reads them from curves/,
#    SVGs included) as DIR/pair-NN.json.
# 3. `node scripts/peer/flubber_frames.mjs` writes flubber's 41
#    in-betweens per pair and its wall time (DIR/flubber-NN.json).
# 4. `cargo run --release --example peer_check -- DIR` judges flubber's
#    frames, a linear interpolation's and immerse's with immerse's exact
#    checker and prints a markdown table on stdout.
#
# MAX_SEGMENT_LENGTH is passed to flubber's maxSegmentLength option:
# "false" (default; flubber then uses the same vertex count as immerse) or
# a number in curve units (flubber's own default is 10).
#
# Needs node and npm on PATH and the npm registry reachable.
# See docs/peer-comparison.md for the table this produced.
set -euo pipefail

SEGMENT=${1:-false}

for tool in node npm cargo; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "peer-compare: '$tool' is not installed or not on PATH; it is needed for the comparison" >&2
    exit 1
  fi
done

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/immerse-peer.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

mkdir -p "$tmp/pairs"
installed=$("$root/scripts/peer/install-flubber.sh" "$tmp/npm")
echo "peer-compare: flubber $installed, node $(node --version)" >&2

cd "$root"
cargo build --quiet --release --example peer_check
cargo run --quiet --release --example peer_check -- export "$tmp/pairs"
node scripts/peer/flubber_frames.mjs "$tmp/pairs" "$tmp/npm" "$SEGMENT"
echo "flubber $installed (maxSegmentLength: $SEGMENT), $(node --version), 41 frames per pair"
echo
cargo run --quiet --release --example peer_check -- "$tmp/pairs"
