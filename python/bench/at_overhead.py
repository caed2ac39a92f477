"""Python call overhead of one Tween.at against the Rust call (docs/python.md).

The pair is the one of the Rust benchmark `tween/500` (benches/morph.rs):
spiral strips of 250 stations turning 1.4 and 0.7 times, width 0.3
(testkit/src/shapes.rs). Compare its median with

    cargo bench --bench morph -- tween/500

    python python/bench/at_overhead.py
"""

import timeit

import numpy as np

import immerse


def spiral_strip(m, turns, width):
    th = turns * 2 * np.pi * np.arange(m) / (m - 1)
    r = 1.0 + 0.12 * th / (2 * np.pi)
    outer = np.column_stack([np.cos(th), np.sin(th)]) * (r + width / 2)[:, None]
    inner = np.column_stack([np.cos(th), np.sin(th)]) * (r - width / 2)[:, None]
    return np.vstack([outer, inner[::-1]])


def main():
    tween = immerse.Tween(spiral_strip(250, 1.4, 0.3), spiral_strip(250, 0.7, 0.3))
    assert tween.vertex_count == 500
    ts = [i / 96 for i in range(97)]
    state = {"i": 0}

    def one():
        state["i"] = (state["i"] + 1) % 97
        tween.at(ts[state["i"]])

    rounds = [timeit.timeit(one, number=2000) / 2000 for _ in range(7)]
    median = sorted(rounds)[len(rounds) // 2]
    print(f"Tween.at, n = 500: median {median * 1e6:.1f} µs per call (7 rounds of 2000)")


if __name__ == "__main__":
    main()
