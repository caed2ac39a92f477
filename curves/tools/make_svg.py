#!/usr/bin/env python3
"""Writes the SVG drawings in curves/ (run from curves/: python3 tools/make_svg.py).

Each drawing is what an animator might draw: a ribbon or tail is a stroke of
varying width along a centreline, outlined as one closed path made of cubic
Beziers (Catmull-Rom through samples of the outline); letters use arcs,
groups and transforms so the reader's transform handling is exercised.
"""
import math

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">\n'


def catmull_rom_path(pts):
    n = len(pts)
    d = ["M %.3f %.3f" % pts[0]]
    for i in range(n):
        p0, p1, p2, p3 = pts[i - 1], pts[i], pts[(i + 1) % n], pts[(i + 2) % n]
        c1 = (p1[0] + (p2[0] - p0[0]) / 6, p1[1] + (p2[1] - p0[1]) / 6)
        c2 = (p2[0] - (p3[0] - p1[0]) / 6, p2[1] - (p3[1] - p1[1]) / 6)
        d.append("C %.3f %.3f %.3f %.3f %.3f %.3f" % (c1 + c2 + p2))
    return " ".join(d) + " Z"


def stroke_outline(centre, width, samples, cap=8):
    """Outline of a stroke along centre(s), s in [0, 1], half-width width(s)."""
    left, right = [], []
    for i in range(samples + 1):
        s = i / samples
        h = 1e-4
        a, b = centre(max(0, s - h)), centre(min(1, s + h))
        tx, ty = b[0] - a[0], b[1] - a[1]
        l = math.hypot(tx, ty)
        nx, ny = -ty / l, tx / l
        c, w = centre(s), width(s)
        left.append((c[0] + nx * w, c[1] + ny * w))
        right.append((c[0] - nx * w, c[1] - ny * w))

    def cap_pts(c, w, ang_from):
        # Half circle from ang_from, turning clockwise (toward the tangent
        # at the end, away from it at the start).
        return [(c[0] + w * math.cos(ang_from - math.pi * k / cap),
                 c[1] + w * math.sin(ang_from - math.pi * k / cap)) for k in range(1, cap)]

    def normal_angle(s):
        h = 1e-4
        a, b = centre(max(0, s - h)), centre(min(1, s + h))
        return math.atan2(b[1] - a[1], b[0] - a[0]) + math.pi / 2

    end = cap_pts(centre(1), width(1), normal_angle(1))
    start = cap_pts(centre(0), width(0), normal_angle(0) + math.pi)
    # left edge forward, round cap at the end, right edge back, cap at start
    return left + end + right[::-1] + start


def write(name, w, h, body):
    with open(name, "w") as f:
        f.write(HEAD.format(w=w, h=h))
        f.write(body)
        f.write("</svg>\n")


def ribbon_curl():
    # A ribbon curling 450 degrees inward, like a rolled party streamer.
    def centre(s):
        a = -math.pi / 2 + s * 2.5 * math.pi
        r = 160 - 30 * s
        return (250 + r * math.cos(a), 250 + r * math.sin(a))
    pts = stroke_outline(centre, lambda s: 22 - 6 * s, 40)
    write("ribbon-curl.svg", 500, 500,
          '  <path fill="#e07a5f" stroke="#3d405b" stroke-width="2" d="%s"/>\n' % catmull_rom_path(pts))


def tail_loop():
    # A tapering tail that loops over itself once (a prolate cycloid).
    def centre(s):
        t = -3.0 + s * 6.4
        return (260 + 45 * t - 110 * math.sin(t), 240 - 110 * math.cos(t) + 10 * t)
    pts = stroke_outline(centre, lambda s: 26 * (1 - 0.75 * s), 60)
    write("tail-loop.svg", 520, 420,
          '  <g transform="translate(10 -20)">\n    <path fill="#81b29a" d="%s"/>\n  </g>\n'
          % catmull_rom_path(pts))


def folded_ribbon():
    # A ribbon that loops twice, as if folded over itself on the way.
    def centre(s):
        t = -0.5 + s * (4 * math.pi + 1.0)
        return (60 + 34 * t - 90 * math.sin(t), 200 - 90 * math.cos(t))
    pts = stroke_outline(centre, lambda s: 16, 90)
    write("folded-ribbon.svg", 620, 340,
          '  <path fill="#f2cc8f" stroke="#3d405b" d="%s"/>\n' % catmull_rom_path(pts))


def ring_wrap():
    # A ring that wraps 400 degrees, drawn with SVG arc commands and round caps.
    cx, cy, R, w = 200, 200, 120, 18
    def pt(r, deg):
        a = math.radians(deg)
        return (cx + r * math.cos(a), cy + r * math.sin(a))
    p0o, p1o = pt(R + w, 0), pt(R + w, 200)
    p2o = pt(R + w, 400)
    p2i, p1i, p0i = pt(R - w, 400), pt(R - w, 200), pt(R - w, 0)
    d = ("M %.3f %.3f A %d %d 0 0 1 %.3f %.3f A %d %d 0 0 1 %.3f %.3f "
         "A %d %d 0 0 1 %.3f %.3f A %d %d 0 0 0 %.3f %.3f A %d %d 0 0 0 %.3f %.3f "
         "A %d %d 0 0 1 %.3f %.3f Z") % (
        p0o + (R + w, R + w) + p1o + (R + w, R + w) + p2o + (w, w) + p2i
        + (R - w, R - w) + p1i + (R - w, R - w) + p0i + (w, w) + p0o)
    write("ring-wrap-400deg.svg", 400, 400,
          '  <path fill="#3d405b" fill-opacity="0.6" d="%s"/>\n' % d)


def letter_c():
    # The letter C from arcs, placed by a group transform (scale + rotate).
    d = ("M 80 -60 A 100 100 0 1 0 80 60 L 50 40 A 64 64 0 1 1 50 -40 Z")
    write("letter-C.svg", 300, 300,
          '  <g transform="translate(150 150) rotate(10) scale(1.1)">\n'
          '    <path fill="#222" d="%s"/>\n  </g>\n' % d)


def letter_l():
    write("letter-L.svg", 200, 240,
          '  <polygon points="40,20 80,20 80,180 170,180 170,220 40,220" fill="#222"/>\n')


def rotated_card():
    write("card-rotated.svg", 200, 200,
          '  <rect x="50" y="70" width="100" height="60" rx="12" transform="rotate(-25 100 100)" fill="#4a7"/>\n')


def figure_eight():
    # Not self-overlapping: a figure eight turns zero times.
    d = "M 150 100 C 150 40 250 40 250 100 C 250 160 150 160 150 100 C 150 40 50 40 50 100 C 50 160 150 160 150 100 Z"
    write("figure-eight.svg", 300, 200, '  <path fill="none" stroke="#000" d="%s"/>\n' % d)


for f in (ribbon_curl, tail_loop, folded_ribbon, ring_wrap, letter_c, letter_l, rotated_card, figure_eight):
    f()
