"""The Inkscape command-line run of scripts/python-test.sh.

    inkscape_cli.py make IN.svg          two sample curves as paths a and b
    inkscape_cli.py verify OUT.svg N     N in-betweens, each passing the exact check
"""

import json
import pathlib
import sys

import inkex

import immerse

CURVES = pathlib.Path(__file__).resolve().parents[2] / "curves"


def make(path):
    shapes = []
    for k, (name, colour) in enumerate([("spiral-strip-400deg-n30.json", "#d62728"), ("curl-strip-n10.json", "#1f77b4")]):
        points = json.loads((CURVES / name).read_text())["points"]
        d = "M " + " L ".join(f"{300 * k + 40 * x!r},{-40 * y!r}" for x, y in points) + " Z"
        shapes.append(f'<path id="{"ab"[k]}" d="{d}" style="fill:{colour};fill-opacity:0.5;stroke:#000000;stroke-width:{1 + 2 * k}"/>')
    pathlib.Path(path).write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="700" height="320" viewBox="-100 -160 700 320">'
        + "".join(shapes) + "</svg>"
    )


def verify(path, count):
    root = inkex.load_svg(path).getroot()
    groups = [g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("{http://www.inkscape.org/namespaces/inkscape}label") == "immerse in-betweens"]
    if len(groups) != 1:
        sys.exit(f"{path}: expected one group of in-betweens, found {len(groups)}")
    made = list(groups[0])
    if len(made) != count:
        sys.exit(f"{path}: expected {count} in-betweens, found {len(made)}")
    for p in made:
        points = [(q.x, q.y) for q in inkex.Path(p.get("d")).end_points][:-1]
        if not immerse.check(points).self_overlapping:
            sys.exit(f"{path}: {p.get('id')} is not self-overlapping")
    print(f"{path}: {count} in-betweens, each self-overlapping (exact check)")


if __name__ == "__main__":
    if sys.argv[1] == "make":
        make(sys.argv[2])
    else:
        verify(sys.argv[2], int(sys.argv[3]))
