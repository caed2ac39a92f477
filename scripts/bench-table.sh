#!/usr/bin/env bash
# Prints one markdown report of every benchmark table, each row beside its
# target from docs/design.md §11:
#   - the immersion DP (n vs median time, memory)       examples/bench_dp.rs
#   - check and maxmin at scale (the command line)        examples/bench_dp.rs --scale
#   - frame generation (vertices × frames per second)   examples/bench_frames.rs
#   - rendering (120 PNG frames at 1024×1024)            render/examples/bench_render.rs
#   - the convex-combination mesh solver (time/frame)    mesh/examples/bench_mesh.rs
#   - with --morph-scale: `immerse morph` at n = 400 to 5000 beside flubber
#     0.4.2 (installed into a temporary folder with npm, as
#     scripts/peer-compare.sh does)                       examples/bench_morph_scale.rs
# Usage: scripts/bench-table.sh [--baseline OLD_IMMERSE] [--morph-scale] [> report.md]
# With --baseline, the scale rows (and with --morph-scale the morph rows)
# also time that earlier `immerse` binary (up to 10,000 points for check;
# build it from an older commit).
# --morph-scale takes a few minutes more (n = 5000, seven runs per row) and
# needs node and npm for the flubber columns (without them they say "not
# run").
# The criterion benches (`cargo bench`) measure the same code with
# statistics; this script is the quick table. Figures are medians of
# repeated runs on this machine; compare rows of one run, not across runs.
set -euo pipefail
morph_scale=false
baseline=()
usage="usage: scripts/bench-table.sh [--baseline OLD_IMMERSE] [--morph-scale]"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --morph-scale) morph_scale=true; shift ;;
    --baseline)
      [[ -x "${2:-}" ]] || { echo "bench-table: --baseline needs an executable immerse binary ($usage)" >&2; exit 2; }
      baseline=(--baseline "$2"); shift 2 ;;
    *) echo "bench-table: unknown option $1 ($usage)" >&2; exit 2 ;;
  esac
done
cd "$(dirname "$0")/.."
command -v cargo >/dev/null || { echo "bench-table: cargo is not on PATH" >&2; exit 2; }
export CARGO_TERM_COLOR=never
echo "Building the benchmark examples (release)..." >&2
cargo build --release --quiet --examples --bin immerse
cargo build --release --quiet -p immerse-render --examples
cargo build --release --quiet -p immerse-mesh --examples

echo "# immerse benchmarks ($(date -u +%Y-%m-%d), $(nproc) cores)"
echo
echo "## Immersion DP — targets: decision + witness n = 1000 < 50 ms, n = 2000 < 300 ms; max–min n = 1000 < 2 s"
echo
cargo run --release --quiet --example bench_dp
echo
echo "## Scale — targets: check n = 5,000 < 1 s, n = 20,000 < 30 s; maxmin n = 4,000 < 10 s"
echo
cargo run --release --quiet --example bench_dp -- --scale --cli target/release/immerse "${baseline[@]}"
echo
echo "## Frame generation — target: 10,000 vertices at > 1,000 frames/s"
echo
cargo run --release --quiet --example bench_frames
echo
echo "## Rendering — target: 120 frames of 1024×1024 PNG in < 4 s on two cores"
echo
cargo run --release --quiet -p immerse-render --example bench_render
echo
echo "## Mesh solver (convex method) — target: 100,000 interior vertices < 0.1 s per frame"
echo
cargo run --release --quiet -p immerse-mesh --example bench_mesh
if $morph_scale; then
  echo
  echo "## \`immerse morph\` by vertex count — targets: n = 400 < 0.06 s, n = 2000 < 0.5 s, n = 5000 < 3 s, growth at most n² log n"
  echo
  cargo build --release --quiet --bin immerse
  flubber=()
  if command -v node >/dev/null && command -v npm >/dev/null; then
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/immerse-bench.XXXXXX")
    trap 'rm -rf "$tmp"' EXIT
    if scripts/peer/install-flubber.sh "$tmp/npm" >/dev/null; then
      flubber=(--flubber "$tmp/npm")
    fi
  fi
  target/release/examples/bench_morph_scale ${flubber[@]+"${flubber[@]}"} ${baseline[@]+"${baseline[@]}"}
fi
