"""Tween closed curves that cross themselves.

Every in-between is the boundary of an immersed disk, checked exactly.
The Python face of the immerse library (docs/python.md in the repository):

- ``check(points)``: is a curve self-overlapping, with the reason and facts;
- ``triangulate(points, quality=...)``: its immersion triangulation;
- ``Tween(a, b, **options)``: a morph planned once, ``.at(t)``,
  ``.frames(count, easing=...)``, ``.report``;
- ``Sequence(keys, ...)``: keyframes K1 → K2 → …;
- ``certify(animation, ...)``: is an animation valid at every moment.

Points are numpy arrays of shape (n, 2) or lists of (x, y) pairs, y up; a
``str`` or path names a curve file (JSON, text or SVG) as on the command
line. Bad input raises ``ValueError``, a curve that is not self-overlapping
raises ``NotSelfOverlapping`` (``check`` returns that answer instead), both
with the command line's messages. Planning, morphing, triangulating and
certifying release the GIL.
"""

from ._immerse import (
    CertifyReport,
    CheckResult,
    Frame,
    MorphReport,
    NotSelfOverlapping,
    Sequence,
    Triangulation,
    Tween,
    __version__,
    certify,
    check,
    triangulate,
)

__all__ = [
    "CertifyReport",
    "CheckResult",
    "Frame",
    "MorphReport",
    "NotSelfOverlapping",
    "Sequence",
    "Triangulation",
    "Tween",
    "__version__",
    "certify",
    "check",
    "triangulate",
]
