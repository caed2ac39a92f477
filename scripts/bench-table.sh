#!/usr/bin/env bash
# Prints one markdown report of every benchmark table, each row beside its
# target from docs/design.md §11:
#   - the immersion DP (n vs median time, memory)       examples/bench_dp.rs
#   - frame generation (vertices × frames per second)   examples/bench_frames.rs
#   - rendering (120 PNG frames at 1024×1024)            render/examples/bench_render.rs
#   - the convex-combination mesh solver (time/frame)    examples/bench_mesh.rs
# Usage: scripts/bench-table.sh [> report.md]
# The criterion benches (`cargo bench`) measure the same code with
# statistics; this script is the quick table. Figures are medians of
# repeated runs on this machine; compare rows of one run, not across runs.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v cargo >/dev/null || { echo "bench-table: cargo is not on PATH" >&2; exit 2; }
export CARGO_TERM_COLOR=never
echo "Building the benchmark examples (release)..." >&2
cargo build --release --quiet --examples
cargo build --release --quiet -p immerse-render --examples

echo "# immerse benchmarks ($(date -u +%Y-%m-%d), $(nproc) cores)"
echo
echo "## Immersion DP — targets: decision + witness n = 1000 < 50 ms, n = 2000 < 300 ms; max–min n = 1000 < 2 s"
echo
cargo run --release --quiet --example bench_dp
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
cargo run --release --quiet --example bench_mesh
