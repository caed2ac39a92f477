#!/usr/bin/env bash
# Prints one markdown report of every benchmark table, each row beside its
# target from docs/design.md §11:
#   - the immersion DP (n vs median time, memory)       examples/bench_dp.rs
#   - check and maxmin at scale (the command line)        examples/bench_dp.rs --scale
#   - frame generation (vertices × frames per second)   examples/bench_frames.rs
#   - rendering (120 PNG frames at 1024×1024)            render/examples/bench_render.rs
#   - the convex-combination mesh solver (time/frame)    examples/bench_mesh.rs
# Usage: scripts/bench-table.sh [--baseline OLD_IMMERSE] [> report.md]
# With --baseline, the scale rows also time that earlier `immerse` binary
# (up to 10,000 points for check; build it from an older commit).
# The criterion benches (`cargo bench`) measure the same code with
# statistics; this script is the quick table. Figures are medians of
# repeated runs on this machine; compare rows of one run, not across runs.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v cargo >/dev/null || { echo "bench-table: cargo is not on PATH" >&2; exit 2; }
export CARGO_TERM_COLOR=never
baseline=()
if [[ "${1:-}" == --baseline ]]; then
    [[ -x "${2:-}" ]] || { echo "bench-table: --baseline needs an executable immerse binary" >&2; exit 2; }
    baseline=(--baseline "$2")
fi
echo "Building the benchmark examples (release)..." >&2
cargo build --release --quiet --examples --bin immerse
cargo build --release --quiet -p immerse-render --examples

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
cargo run --release --quiet --example bench_mesh
