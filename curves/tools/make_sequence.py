#!/usr/bin/env python3
"""Writes the keyframe sequence in curves/sequence/ (run from curves/:
python3 tools/make_sequence.py).

ribbon-loops.svg holds four keys as Inkscape layers, centred on one
600 x 500 canvas: the curled ribbon, the tail that loops once, the ribbon
that loops twice, and the curled ribbon again (so the animation loops).
The drawings are the ones tools/make_svg.py writes (ribbon-curl.svg,
tail-loop.svg, folded-ribbon.svg), moved by a translation.

ribbon-loops.json is the timeline: the same four keys with two shape
hints, "a" and "b", at the two ends of each stroke (positions in immerse's
coordinates: x, -y of the canvas), an ease-in start, an ease-out end, a
hold on the last key, 6 s at 24 fps. The ribbon's outer end ("a") becomes
the thin tip of the tail and of the two-loop ribbon, so the curl rolls out
into the loop and the two loops roll back into the curl; pairing the
thick ends instead makes both segments unwind into a straight stroke.
"""
import json
import math
import re

CANVAS = (600, 500)


def d_of(name):
    with open(name) as f:
        return re.search(r' d="([^"]+)"', f.read()).group(1)


def bbox(d, tx=0.0, ty=0.0):
    nums = [float(x) for x in re.findall(r"-?\d+\.?\d*", d)]
    xs, ys = nums[0::2], nums[1::2]
    return min(xs) + tx, max(xs) + tx, min(ys) + ty, max(ys) + ty


def ends(centre, width):
    """The tips of a stroke_outline of make_svg.py: the middle of the start
    cap and of the end cap."""
    def tangent(s):
        h = 1e-4
        a, b = centre(max(0, s - h)), centre(min(1, s + h))
        return math.atan2(b[1] - a[1], b[0] - a[0])
    c0, c1 = centre(0), centre(1)
    t0, t1 = tangent(0), tangent(1)
    start = (c0[0] - width(0) * math.cos(t0), c0[1] - width(0) * math.sin(t0))
    tip = (c1[0] + width(1) * math.cos(t1), c1[1] + width(1) * math.sin(t1))
    return start, tip


def ribbon(s):
    a = -math.pi / 2 + s * 2.5 * math.pi
    r = 160 - 30 * s
    return (250 + r * math.cos(a), 250 + r * math.sin(a))


def tail(s):
    t = -3.0 + s * 6.4
    return (260 + 45 * t - 110 * math.sin(t), 240 - 110 * math.cos(t) + 10 * t)


def folded(s):
    t = -0.5 + s * (4 * math.pi + 1.0)
    return (60 + 34 * t - 90 * math.sin(t), 200 - 90 * math.cos(t))


KEYS = [
    # (layer id, source file, its own translation, centre, width)
    ("ribbon", "ribbon-curl.svg", (0, 0), ribbon, lambda s: 22 - 6 * s, "#e07a5f"),
    ("tail", "tail-loop.svg", (10, -20), tail, lambda s: 26 * (1 - 0.75 * s), "#81b29a"),
    ("two-loops", "folded-ribbon.svg", (0, 0), folded, lambda s: 16, "#f2cc8f"),
    ("ribbon-again", "ribbon-curl.svg", (0, 0), ribbon, lambda s: 22 - 6 * s, "#e07a5f"),
]

layers = []
hints = []
for ident, src, (ox, oy), centre, width, colour in KEYS:
    d = d_of(src)
    x0, x1, y0, y1 = bbox(d, ox, oy)
    tx = round(CANVAS[0] / 2 - (x0 + x1) / 2 + ox, 3)
    ty = round(CANVAS[1] / 2 - (y0 + y1) / 2 + oy, 3)
    layers.append(
        '  <g inkscape:groupmode="layer" inkscape:label="%s" id="%s" transform="translate(%s %s)">\n'
        '    <path fill="%s" stroke="#3d405b" stroke-width="2" d="%s"/>\n  </g>\n'
        % (ident, ident, tx, ty, colour, d))
    start, tip = ends(centre, width)
    to_immerse = lambda p: [round(p[0] + tx, 3), round(-(p[1] + ty), 3)]
    if centre is ribbon:
        hints.append({"a": to_immerse(start), "b": to_immerse(tip)})
    else:
        hints.append({"a": to_immerse(tip), "b": to_immerse(start)})

with open("sequence/ribbon-loops.svg", "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg" '
            'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
            'width="%d" height="%d" viewBox="0 0 %d %d">\n' % (CANVAS + CANVAS))
    f.write("".join(layers))
    f.write("</svg>\n")

timeline = {
    "fps": 24,
    "loop": "loop",
    "keys": [
        {"curve": "ribbon-loops.svg", "shape": 1, "easing": "ease-in", "hints": hints[0]},
        {"curve": "ribbon-loops.svg", "shape": 2, "hints": hints[1]},
        {"curve": "ribbon-loops.svg", "shape": 3, "easing": "ease-out", "hints": hints[2]},
        {"curve": "ribbon-loops.svg", "shape": 4, "time": 6, "hold": 0.5, "hints": hints[3]},
    ],
}
with open("sequence/ribbon-loops.json", "w") as f:
    text = json.dumps(timeline, indent=2)
    # One hint per line reads better than one number per line.
    text = re.sub(r"\[\s+(-?[\d.]+),\s+(-?[\d.]+)\s+\]", r"[\1, \2]", text)
    f.write(text + "\n")
