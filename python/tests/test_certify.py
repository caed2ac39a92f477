"""certify: key shapes, files and bytes; answers and errors."""

import json

import numpy as np
import pytest

import immerse
from conftest import CURVES

SQUARE = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)


def test_moved_square_is_certified_and_half_turn_is_invalid():
    moved = SQUARE * 2 + [3, 0]
    r = immerse.certify([SQUARE, moved])
    assert r.certified and bool(r) and r.answer == "certified"
    assert (r.segments, r.certified_segments, r.invalid) == (1, 1, 0)
    # Turned by 180° in one straight segment: every vertex passes the centre.
    turned = 1.0 - SQUARE
    r = immerse.certify([SQUARE, turned], triangles=[[[0, 1, 2], [0, 2, 3]], None])
    assert r.answer == "invalid" and not r
    seg = r.to_dict()["paths"][0]["segments"][0]
    assert seg["invalid_at"]["exact"] == "1/2"


def test_sequence_frames_are_certified_for_every_player():
    seq = immerse.Sequence(
        [CURVES / "spiral-strip-400deg-n30.json", CURVES / "curl-strip-n10.json"]
    )
    frames = seq.frames(21)
    for player in ("exact", "f64"):
        r = immerse.certify(list(frames), player=player)
        assert r.player == player and r.segments == 20
        assert r.certified_segments + r.invalid + r.undecided == 20
        assert r.invalid == 0


def test_files_and_bytes_read_as_the_command_line(tmp_path):
    keys = {"keyframes": [{"t": 0, "points": SQUARE.tolist()},
                          {"t": 1, "points": (SQUARE * 3).tolist()}]}
    path = tmp_path / "anim.json"
    path.write_text(json.dumps(keys))
    by_path = immerse.certify(path)
    by_bytes = immerse.certify(path.read_bytes())
    assert by_path.certified and by_bytes.certified
    assert by_path.file == str(path) and by_bytes.file == "<bytes>"
    d = by_path.to_dict()
    assert d["format"] == "immerse-keyframes" and d["answer"] == "certified"


def test_bad_input():
    with pytest.raises(ValueError, match="no keys to certify"):
        immerse.certify([])
    with pytest.raises(ValueError, match="key 1: the two shapes have 4 and 3 points"):
        immerse.certify([SQUARE, SQUARE[:3]])
    with pytest.raises(ValueError, match="key 1 has time 0, not finite and after the key before it"):
        immerse.certify([SQUARE, SQUARE], times=[0.0, 0.0])
    with pytest.raises(ValueError, match="unknown player 'f16'; use exact, f64, f32"):
        immerse.certify([SQUARE, SQUARE], player="f16")
    with pytest.raises(ValueError, match="triangles\\[0\\]: vertex 7 does not exist"):
        immerse.certify([SQUARE, SQUARE], triangles=[[[0, 1, 7]], None])
    with pytest.raises(ValueError, match="not valid JSON"):
        immerse.certify(b"{nope")
