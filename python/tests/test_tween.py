"""Tween and Sequence: frames are immersions, ends exact, options, threads."""

import threading
import time

import numpy as np
import pytest

import immerse
from conftest import CURVES, star

SPIRAL = CURVES / "spiral-strip-400deg-n30.json"
CURL = CURVES / "curl-strip-n10.json"


def independent_check(points):
    """The exact check of a frame's outline alone (its own triangulation)."""
    return immerse.check(points).self_overlapping


def test_ends_are_the_inputs_exactly():
    tween = immerse.Tween(SPIRAL, CURL)
    a = immerse.triangulate(SPIRAL).points
    n = tween.vertex_count
    assert n == 30
    np.testing.assert_array_equal(tween.at(0.0), a)
    b = tween.at(1.0)
    # Vertex i at t = 1 is target vertex i + shift; the curl's 10 points
    # are among them exactly (counts equalised by insertion).
    curl = immerse.triangulate(CURL).points
    assert all(any((row == p).all() for row in b) for p in curl)


def test_every_frame_is_an_immersion_and_shapes():
    tween = immerse.Tween(SPIRAL, CURL)
    frames = tween.frames(25, easing="ease-in-out")
    assert frames.shape == (25, 30, 2) and frames.dtype == np.float64
    for f in frames:
        assert independent_check(f)
    for t in np.linspace(0, 1, 11):
        fr = tween.frame(t)
        assert fr.is_immersion() and fr.triangles.shape == (28, 3)
        np.testing.assert_array_equal(fr.points, tween.at(t))
        assert independent_check(fr.points)


def test_frames_follow_the_easing():
    tween = immerse.Tween(SPIRAL, CURL)
    eased = tween.frames(5, easing="ease-in")
    # ease-in is cubic-bezier(0.42, 0, 1, 1): its value at 1/4, 1/2, 3/4.
    for f, t in zip(eased[1:-1], [0.25, 0.5, 0.75]):
        assert not np.array_equal(f, tween.at(t))
    linear = tween.frames(5)
    for f, t in zip(linear, [0.0, 0.25, 0.5, 0.75, 1.0]):
        np.testing.assert_array_equal(f, tween.at(t))


def test_random_star_pairs(rng):
    for k in range(8):
        a = star(rng, int(rng.integers(5, 30)))
        b = star(rng, int(rng.integers(5, 30)), centre=(3.0, 1.0), radius=2.0)
        tween = immerse.Tween(a, b)
        for f in tween.frames(9):
            assert independent_check(f), k
        # The source's points are among the first frame's, exactly.
        first = tween.at(0.0)
        assert len(first) == max(len(a), len(b))
        assert all(any((row == p).all() for row in first) for p in a)


def test_experimental_options_are_refused_naming_the_offered_ones():
    with pytest.raises(ValueError, match="'polar' is experimental.*rigid, hybrid, straight"):
        immerse.Tween(SPIRAL, CURL, path="polar")
    with pytest.raises(ValueError, match="'identity' is experimental.*corners, min-flips, best"):
        immerse.Tween(SPIRAL, CURL, correspondence="identity")


def test_report_and_repr():
    tween = immerse.Tween(SPIRAL, CURL, path="hybrid", correspondence="min-flips")
    r = tween.report
    assert r.n == 30 and r.used in ("source", "target")
    assert set(r.paths) <= {"rigid", "hybrid", "straight", "polar", "angle", "rotate-slide", "linear"}
    assert all(isinstance(w, str) and isinstance(y, str) for w, y in r.fallbacks)
    assert "Tween(30 vertices" in repr(tween)
    assert tween.path_length > 0 and tween.reversed == (False, False)


@pytest.mark.parametrize(
    "option, value, message",
    [
        ("path", "wobbly", "unknown path 'wobbly'; use"),
        ("correspondence", "nearest", "unknown correspondence 'nearest'; use corners, min-flips, best"),
        ("counts", "more", "unknown counts 'more'; use insert, resample"),
        ("intermediate", "cube", "unknown intermediate 'cube'; use target, disk"),
        ("quality", "great", "unknown triangulation quality 'great'"),
        ("fan_margin", -1.0, "fan_margin -1"),
    ],
)
def test_unknown_options_are_value_errors(option, value, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(")):
        immerse.Tween(SPIRAL, CURL, **{option: value})


def test_fraction_outside_the_unit_interval():
    tween = immerse.Tween(SPIRAL, CURL)
    for t in (-0.1, 1.5, float("nan")):
        with pytest.raises(ValueError, match="is not a number in \\[0, 1\\]"):
            tween.at(t)
    with pytest.raises(ValueError, match="easing 'bouncy'"):
        tween.frames(3, easing="bouncy")


def test_negative_answer_names_the_side():
    with pytest.raises(immerse.NotSelfOverlapping) as e:
        immerse.Tween(SPIRAL, CURVES / "figure-eight-n64.json")
    assert "the target curve is not self-overlapping: turning number is 0, not 1" in str(e.value)
    with pytest.raises(immerse.NotSelfOverlapping, match="^a: the source curve"):
        immerse.Tween([[0, 0], [2, 2], [2, 0], [0, 2]], CURL)


def test_clockwise_inputs_are_reversed():
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    tween = immerse.Tween(sq[::-1], sq * 2)
    assert tween.reversed == (True, False)


def test_planning_and_morphing_release_the_gil():
    """While a big morph is planned on another thread, this one runs."""
    a, b = CURVES / "spiral-strip-720deg-n200.json", CURVES / "immersed-disk-n80.json"
    start = time.perf_counter()
    immerse.Tween(a, b)
    alone = time.perf_counter() - start
    assert alone > 0.05  # long enough for the gap to show
    done = threading.Event()

    def plan():
        immerse.Tween(a, b).frames(200)
        done.set()

    worker = threading.Thread(target=plan)
    gaps, last = [], time.perf_counter()
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        gaps.append(now - last)
        last = now
    worker.join()
    # Holding the GIL through planning would stall this loop for the
    # whole planning time.
    assert max(gaps) < alone / 2, (max(gaps), alone)


def test_sequence_frames_keys_and_identity():
    keys = [SPIRAL, CURL, CURVES / "annulus-sector-300deg-n40.json"]
    seq = immerse.Sequence(keys)
    assert seq.key_count == 3 and seq.vertex_count == 40
    frames = seq.frames(41)
    assert frames.shape == (41, 40, 2)
    np.testing.assert_array_equal(frames[0], seq.keys[0])
    np.testing.assert_array_equal(frames[-1], seq.keys[-1])
    for f in frames:
        assert independent_check(f)
    # Each key's original points are among its sequence vertices exactly.
    for key, path in zip(seq.keys, keys):
        original = immerse.triangulate(path).points
        assert all(any((row == p).all() for row in key) for p in original)
    fr = seq.frame(1, 0.5)
    assert fr.is_immersion()
    assert seq.tween(0).vertex_count == 40
    with pytest.raises(ValueError, match="segment 2 does not exist"):
        seq.frame(2, 0.5)


def test_sequence_timing_and_hints():
    keys = [SPIRAL, CURL, SPIRAL]
    seq = immerse.Sequence(keys, hints=[(0, 0, 0, "tip")])
    timed = seq.frames(fps=10, durations=[1.0, 2.0], holds=[0.0, 0.5, 0.0])
    # 1 s + 2 s at 10 fps, a 0.5 s hold (5 repeated frames), both ends.
    assert timed.shape[0] == 10 + 20 + 5 + 1
    np.testing.assert_array_equal(timed[10], timed[15])
    with pytest.raises(ValueError, match="durations \\(one per segment\\): 3 given"):
        seq.frames(durations=[1, 1, 1])
    with pytest.raises(ValueError, match="a sequence needs at least 2 keys"):
        immerse.Sequence([SPIRAL])
    with pytest.raises(immerse.NotSelfOverlapping, match="key 2 .* is not self-overlapping"):
        immerse.Sequence([SPIRAL, CURVES / "figure-eight-n64.json"])


def test_keyframes_are_the_motion_and_certified():
    tween = immerse.Tween(SPIRAL, CURL)
    keys = tween.keyframes
    assert len(keys) >= 2
    ts = [k.t for k in keys]
    assert ts[0] == 0.0 and ts[-1] == 1.0
    assert all(a < b for a, b in zip(ts, ts[1:]))
    np.testing.assert_array_equal(keys[0].points, tween.at(0.0))
    np.testing.assert_array_equal(keys[-1].points, tween.at(1.0))
    # A frame between two keys is their straight-line interpolation.
    k = len(keys) // 2
    mid = 0.5 * (ts[k - 1] + ts[k])
    w = (mid - ts[k - 1]) / (ts[k] - ts[k - 1])
    expected = (1 - w) * keys[k - 1].points + w * keys[k].points
    np.testing.assert_allclose(tween.at(mid), expected, rtol=0, atol=1e-9)
    # Every segment certified by the library's certificate, with the
    # keys' own triangulations.
    r = immerse.certify(
        [k.points for k in keys],
        times=ts,
        triangles=[k.triangles for k in keys],
    )
    assert r.certified and r.segments == len(keys) - 1
