"""check and triangulate: answers, facts, input forms, errors."""

import subprocess

import numpy as np
import pytest

import immerse
from conftest import CURVES, ROOT, star

SQUARE = [[0, 0], [1, 0], [1, 1], [0, 1]]
FIGURE_EIGHT = [[0, 0], [2, 2], [2, 0], [0, 2]]


def test_square_is_self_overlapping_and_its_facts():
    r = immerse.check(SQUARE)
    assert r.self_overlapping and bool(r)
    assert r.reason is None
    assert (r.points, r.turning_number, r.simple, r.reversed) == (4, 1, True, False)


def test_no_is_an_answer_not_an_exception():
    r = immerse.check(FIGURE_EIGHT)
    assert not r.self_overlapping and not bool(r)
    assert r.turning_number == 0
    assert r.reason == "turning number is 0, not 1"
    assert not r.simple


def test_clockwise_is_reversed():
    r = immerse.check(SQUARE[::-1])
    assert r.self_overlapping and r.reversed and r.turning_number == -1


def test_lists_tuples_ints_and_arrays_agree():
    forms = [
        SQUARE,
        [tuple(p) for p in SQUARE],
        np.array(SQUARE, dtype=np.int64),
        np.array(SQUARE, dtype=np.float32),
        np.asfortranarray(np.array(SQUARE, dtype=float)),
        np.repeat(np.array(SQUARE, dtype=float), 2, axis=0)[::2],  # a strided view
    ]
    answers = [immerse.check(f).to_dict() for f in forms]
    assert all(a == answers[0] for a in answers)


def test_closing_point_is_dropped():
    r = immerse.check(SQUARE + [SQUARE[0]])
    assert r.points == 4 and r.dropped == 1


@pytest.mark.parametrize(
    "bad, words",
    [
        ([[0, 0], [1, 0]], "only 2 distinct point"),
        ([[0, 0], [1, 0], [2, 0]], "lie on one line"),
        ([[0, 0], [1, 0], [float("nan"), 1]], "finite"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], "shape (3, 3)"),
        ([0, 1, 2], "shape (3,)"),
        ([[0, 0], [1]], "(n, 2) array"),
        ("not-a-file.json", "cannot read not-a-file.json"),
    ],
)
def test_bad_input_raises_value_error_naming_the_problem(bad, words):
    with pytest.raises(ValueError) as e:
        immerse.check(bad)
    assert words in str(e.value)


@pytest.mark.parametrize(
    "name",
    ["degenerate-two-points.json", "degenerate-nan.txt", "degenerate-collinear.json"],
)
def test_messages_are_the_command_lines(immerse_bin, name):
    path = f"curves/{name}"
    cli = subprocess.run(
        [immerse_bin, "check", path], cwd=ROOT, capture_output=True, text=True
    )
    assert cli.returncode == 2
    with pytest.raises(ValueError) as e:
        immerse.check(str(ROOT / path))
    assert cli.stderr.strip() == "immerse: " + str(e.value).replace(str(ROOT) + "/", "")


def test_negative_answer_of_triangulate_is_the_command_lines(immerse_bin):
    path = "curves/figure-eight-n64.json"
    cli = subprocess.run(
        [immerse_bin, "triangulate", path], cwd=ROOT, capture_output=True, text=True
    )
    assert cli.returncode == 1
    with pytest.raises(immerse.NotSelfOverlapping) as e:
        immerse.triangulate(str(ROOT / path))
    assert cli.stderr.strip() == "immerse: " + str(e.value).replace(str(ROOT) + "/", "")
    assert e.value.reason == "turning number is 0, not 1"
    assert not isinstance(e.value, ValueError)


def test_check_agrees_with_the_command_line_on_every_curve(immerse_bin):
    """`immerse check --json` and immerse.check give the same facts."""
    import json

    files = sorted(p for p in CURVES.glob("*.json") if "degenerate" not in p.name)
    files = [p for p in files if p.name not in ("MANIFEST.json",)]
    assert len(files) > 20
    for p in files:
        cli = subprocess.run(
            [immerse_bin, "check", "--json", str(p)], capture_output=True, text=True
        )
        if cli.returncode == 2:
            with pytest.raises(ValueError):
                immerse.check(p)
            continue
        want = json.loads(cli.stdout)
        got = immerse.check(p).to_dict()
        got.pop("dropped")
        assert got == want, p.name


def test_random_stars_are_self_overlapping_and_triangulate(rng):
    for _ in range(40):
        n = int(rng.integers(3, 60))
        pts = star(rng, n)
        assert immerse.check(pts).self_overlapping
        for quality in ("any", "delaunay", "maxmin"):
            t = immerse.triangulate(pts, quality=quality)
            assert t.triangles.shape == (n - 2, 3)
            assert t.points.shape == (n, 2)
            np.testing.assert_array_equal(t.points, pts)
            # Every triangle counter-clockwise (a simple polygon's
            # triangulation is an immersion).
            p = t.points[t.triangles.astype(np.int64)]
            cross = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (
                p[:, 1, 1] - p[:, 0, 1]
            ) * (p[:, 2, 0] - p[:, 0, 0])
            assert (cross > 0).all()


def test_triangulate_facts_and_unknown_quality():
    t = immerse.triangulate(CURVES / "spiral-strip-400deg-n30.json")
    assert t.quality == "delaunay" and len(t.spine) >= 1
    assert 0 <= t.pivot_vertex < 30 and 0 <= t.root_triangle < 28
    assert 0 < t.min_angle < np.pi / 3 + 1e-12
    with pytest.raises(ValueError, match="unknown triangulation quality 'best'"):
        immerse.triangulate(SQUARE, quality="best")
