"""The matplotlib example of docs/python.md runs, and its depth is right."""

import importlib.util
import subprocess
import sys

import numpy as np

from conftest import CURVES, ROOT

SCRIPT = ROOT / "docs" / "examples" / "morph_strip.py"


def winding(outline, xs, ys):
    """Winding number of a closed polygon around each grid point (angle sums)."""
    px, py = np.meshgrid(xs, ys)
    total = np.zeros_like(px)
    for p, q in zip(outline, np.roll(outline, -1, axis=0)):
        a = np.arctan2(p[1] - py, p[0] - px)
        b = np.arctan2(q[1] - py, q[0] - px)
        total += (b - a + np.pi) % (2 * np.pi) - np.pi
    return np.rint(total / (2 * np.pi)).astype(int)


def test_script_writes_the_strip(tmp_path):
    out = tmp_path / "strip.png"
    run = subprocess.run(
        [sys.executable, str(SCRIPT), "--frames", "5", "-o", str(out)],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert run.returncode == 0, run.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "5 frames, deepest overlap 2 layers" in run.stdout


def test_depth_is_the_winding_number():
    """Over an immersed disk, the layers over a point are the boundary's winding number."""
    spec = importlib.util.spec_from_file_location("morph_strip", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    import immerse

    tween = immerse.Tween(CURVES / "spiral-strip-400deg-n30.json", CURVES / "curl-strip-n10.json")
    for t in (0.0, 0.4, 1.0):
        frame = tween.frame(t)
        lo, hi = frame.points.min(axis=0), frame.points.max(axis=0)
        # Grid points off every edge: an irrational offset.
        xs = np.linspace(lo[0], hi[0], 61) + 1e-3 * np.sqrt(2)
        ys = np.linspace(lo[1], hi[1], 61) + 1e-3 * np.sqrt(3)
        d = module.depth(frame, xs, ys)
        w = winding(frame.points, xs, ys)
        assert d.max() == 2
        assert (d == w).all()
