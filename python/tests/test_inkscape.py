"""The Inkscape extension, headless with inkex from PyPI (docs/inkscape.md)."""

import importlib.util
import io
import json
import re

import inkex
import pytest

import immerse
from conftest import CURVES, ROOT, binary

SCRIPT = ROOT / "inkscape" / "immerse_inbetween.py"


def load():
    spec = importlib.util.spec_from_file_location("immerse_inbetween", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def d_of(points, scale=10.0, dx=0.0):
    # SVG is y down: mirror, so the drawing looks like the curve.
    return "M " + " L ".join(f"{dx + scale * x!r},{-scale * y!r}" for x, y in points) + " Z"


def document(tmp_path, shapes):
    """An SVG with one path per (id, points, style), inside a translated layer."""
    paths = "\n".join(
        f'<path id="{i}" d="{d_of(p, dx=300.0 * k)}" style="{style}"/>'
        for k, (i, p, style) in enumerate(shapes)
    )
    svg = (
        '<svg xmlns="http://www.w3.org/2000/svg" width="1000" height="400">'
        f'<g id="layer" transform="translate(20,200)">{paths}</g></svg>'
    )
    path = tmp_path / "in.svg"
    path.write_text(svg)
    return path


def curve(name):
    return json.loads((CURVES / name).read_text())["points"]


SPIRAL = curve("spiral-strip-400deg-n30.json")
CURL = curve("curl-strip-n10.json")
ANNULUS = curve("annulus-sector-300deg-n40.json")


def run(module, svg, *args):
    out = io.BytesIO()
    module.Inbetween().run([*args, str(svg)], output=out)
    return inkex.load_svg(io.BytesIO(out.getvalue())).getroot()


def inbetweens(root):
    groups = [g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.label == "immerse in-betweens"]
    assert len(groups) == 1
    return list(groups[0])


def outline(element):
    """The points an in-between's path data holds (straight segments only)."""
    d = element.get("d")
    assert re.fullmatch(r"M [^MCQASHVTZ]* Z", d)
    return [(p.x, p.y) for p in element.path.end_points][:-1]


def test_two_paths_give_steps_paths_each_an_immersion(tmp_path):
    module = load()
    svg = document(tmp_path, [("a", SPIRAL, "fill:#ff0000;stroke-width:1"), ("b", CURL, "fill:#0000ff;stroke-width:3")])
    root = run(module, svg, "--id=a", "--id=b", "--steps=6")
    made = inbetweens(root)
    assert len(made) == 6
    for p in made:
        pts = outline(p)
        assert len(pts) == 30
        assert immerse.check(pts).self_overlapping
    # The style runs from the first key's to the second's.
    fills = [p.style("fill") for p in made]
    reds = [int(str(f)[1:3], 16) for f in fills]
    assert reds == sorted(reds, reverse=True) and 0 < reds[-1] < reds[0] < 255
    widths = [float(str(p.style("stroke-width")).rstrip("px")) for p in made]
    assert widths == sorted(widths) and 1 < widths[0] < widths[-1] < 3
    # The group undoes the layer's transform: points are document coordinates.
    group = made[0].getparent()
    assert group.getparent().get_id() == "layer"
    assert str(group.transform) == "translate(-20, -200)"


def test_order_of_keys_selection_and_stacking(tmp_path):
    module = load()
    svg = document(tmp_path, [("a", SPIRAL, "fill:red"), ("b", CURL, "fill:blue"), ("c", ANNULUS, "fill:green")])
    by_selection = inbetweens(run(module, svg, "--id=c", "--id=a", "--id=b", "--steps=2"))
    by_stacking = inbetweens(run(module, svg, "--id=c", "--id=a", "--id=b", "--steps=2", "--order=stacking"))
    assert len(by_selection) == len(by_stacking) == 4
    assert by_selection[0].label.startswith("c → a") and by_selection[2].label.startswith("a → b")
    assert by_stacking[0].label.startswith("a → b") and by_stacking[2].label.startswith("b → c")
    for p in by_selection + by_stacking:
        assert immerse.check(outline(p)).self_overlapping


def test_the_binary_fallback_gives_the_same_paths(tmp_path):
    module = load()
    svg = document(tmp_path, [("a", SPIRAL, "fill:red"), ("b", CURL, "fill:blue")])
    package = inbetweens(run(module, svg, "--id=a", "--id=b", "--steps=3"))
    module.immerse = None  # as in a Python without the package
    fallback = inbetweens(run(module, svg, "--id=a", "--id=b", "--steps=3", f"--binary={binary()}"))
    assert [p.get("d") for p in package] == [p.get("d") for p in fallback]


def test_errors_reach_the_user_through_inkex(tmp_path, capsys):
    module = load()
    eight = [[0, 0], [2, 2], [2, 0], [0, 2]]
    svg = document(tmp_path, [("a", SPIRAL, "fill:red"), ("eight", eight, "fill:blue")])
    for engine in ("package", "binary"):
        with pytest.raises(SystemExit):
            run(module, svg, "--id=a", "--id=eight", f"--engine={engine}", f"--binary={binary()}")
        err = capsys.readouterr().err
        assert "eight: the target curve is not self-overlapping: turning number is 0, not 1" in err, err
    with pytest.raises(SystemExit):
        run(module, svg, "--id=a")
    assert "select two or more closed paths (found 1)" in capsys.readouterr().err
    module.immerse = None
    with pytest.raises(SystemExit):
        run(module, svg, "--id=a", "--id=eight", "--binary=/nonexistent/immerse")
    err = capsys.readouterr().err
    assert "immerse is not available" in err and "pip install ./python" in err
