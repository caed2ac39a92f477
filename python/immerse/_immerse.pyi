"""Type stubs of the compiled module ``immerse._immerse`` (docs/python.md)."""

import os
from typing import Any, Dict, Iterable, List, Optional, Sequence as _Seq, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: Points: an (n, 2) array of x, y (y up), a list of (x, y) pairs, or a
#: curve file (JSON, text or SVG) read as the command line reads it.
CurveLike = Union[npt.ArrayLike, str, "os.PathLike[str]"]
#: An (n, 2) float64 array.
Points = npt.NDArray[np.float64]

class NotSelfOverlapping(Exception):
    """The negative answer: a curve does not bound an immersed disk.

    Raised by :func:`triangulate`, :class:`Tween` and :class:`Sequence`
    (never by :func:`check`). ``str(e)`` is the command line's message.
    """

    #: The reason alone, e.g. ``"turning number is 0, not 1"``.
    reason: str

class CheckResult:
    """The answer of :func:`check` (the fields of ``immerse check --json``)."""

    #: True when the curve bounds an immersed disk.
    self_overlapping: bool
    #: Why it does not; ``None`` when it does.
    reason: Optional[str]
    #: Points after cleaning.
    points: int
    #: Repeated points cleaning dropped.
    dropped: int
    #: Turning number as given (before any reversal); ``None`` at a cusp.
    turning_number: Optional[int]
    #: True when no two edges touch except neighbours at their vertex.
    simple: bool
    #: True when the curve was clockwise and has been reversed.
    reversed: bool
    def __bool__(self) -> bool: ...
    def to_dict(self) -> Dict[str, Any]: ...

def check(points: CurveLike) -> CheckResult:
    """Is a closed curve self-overlapping? Decided exactly; returns the
    answer and never raises for "no".

    Raises:
        ValueError: bad input (fewer than 3 distinct points, a coordinate
            that is not finite or out of range, an unreadable file).
    """

class Triangulation:
    """The immersion triangulation of a curve (``immerse triangulate --json``)."""

    #: Vertices in oriented order (turning number +1), an (n, 2) array.
    points: Points
    #: Counter-clockwise triangles, an (n - 2, 3) uint32 array.
    triangles: npt.NDArray[np.uint32]
    reversed: bool
    #: Triangle indices from the pivot triangle to the other end.
    spine: List[int]
    pivot_vertex: int
    root_triangle: int
    #: Smallest triangle angle, radians.
    min_angle: float
    #: ``"any"``, ``"delaunay"`` or ``"maxmin"``.
    quality: str

def triangulate(points: CurveLike, *, quality: Optional[str] = None) -> Triangulation:
    """Triangulate a self-overlapping curve (``quality``: ``"any"``,
    ``"delaunay"`` (default) or ``"maxmin"``).

    Raises:
        NotSelfOverlapping: the curve does not bound an immersed disk.
        ValueError: bad input.
    """

class Frame:
    """One in-between with the triangulation that shows it is an immersion."""

    #: The morph parameter, in [0, 1].
    t: float
    #: Vertex positions, an (n, 2) array.
    points: Points
    #: Counter-clockwise triangles, an (n - 2, 3) uint32 array.
    triangles: npt.NDArray[np.uint32]
    def is_immersion(self) -> bool:
        """Checks again, exactly, that the triangles show an immersion."""

class MorphReport:
    """What planning a morph did."""

    #: Vertices after equalising counts.
    n: int
    #: Target vertex ``i + shift`` matches source vertex ``i``.
    shift: int
    flips: int
    #: ``"source"`` or ``"target"``: the side whose path was used.
    used: str
    #: Third-vertex paths used, e.g. ``["rigid"]``.
    paths: List[str]
    #: (what, why) of everything done instead of what was asked.
    fallbacks: List[Tuple[str, str]]
    unblocks: int
    used_disk: bool
    repairs: int

class Tween:
    """A morph from curve ``a`` to curve ``b``, planned once: a verified
    frame at any ``t``.

    Options (``None``: the library's default), with the command line's values:
    ``quality`` (``any``, ``delaunay``, ``maxmin``), ``path`` (``rigid``,
    ``hybrid``, ``straight``, ``polar``, ``angle``, ``rotate-slide``,
    ``linear``), ``correspondence`` (``best``, ``outline``, ``corners``,
    ``min-flips``, ``pivot``, ``shape``, ``identity``), ``counts``
    (``insert``, ``resample``), ``intermediate`` (``target``, ``disk``),
    ``fan_margin`` (radians).

    Raises:
        NotSelfOverlapping: ``a`` or ``b`` does not bound an immersed disk.
        ValueError: bad input or an unknown option value.
    """

    def __init__(
        self,
        a: CurveLike,
        b: CurveLike,
        *,
        quality: Optional[str] = None,
        path: Optional[str] = None,
        correspondence: Optional[str] = None,
        counts: Optional[str] = None,
        intermediate: Optional[str] = None,
        fan_margin: Optional[float] = None,
    ) -> None: ...
    def at(self, t: float) -> Points:
        """Points of the frame at fraction ``t`` in [0, 1] of the vertex
        travel (0 = ``a``, 1 = ``b``, exactly); ValueError outside [0, 1]."""
    def frame(self, t: float) -> Frame:
        """The frame at ``t`` with its triangulation."""
    def frames(self, count: int, easing: Optional[str] = None) -> npt.NDArray[np.float64]:
        """``count`` frames from ``a`` to ``b``, a (count, n, 2) array; ``easing``
        as ``--easing``: ``linear``, ``ease``, ``ease-in``, ``ease-out``,
        ``ease-in-out`` or ``cubic-bezier(x1,y1,x2,y2)``."""
    #: The keyframes (``t`` strictly increasing from 0 to 1, the
    #: triangulation of the segment that follows each key): the animation
    #: is their piecewise-linear interpolation, every segment certified.
    keyframes: List[Frame]
    #: What planning did.
    report: MorphReport
    #: Vertices of every frame.
    vertex_count: int
    #: Total vertex travel (the unit of the frame timing).
    path_length: float
    #: Whether ``a`` and ``b`` were clockwise and reversed.
    reversed: Tuple[bool, bool]

HintPlace = Union[int, float, Tuple[float, float]]

class Sequence:
    """Keyframes K1 → K2 → …, planned once: equal vertex counts, hints
    honoured, one verified tween per segment, vertex identity kept.

    ``hints``: (segment, from, to) or (segment, from, to, name) where a
    place is a vertex index (int), a fraction of the arc length (float) or a
    point (x, y). Options as :class:`Tween` (counts are always equalised by
    insertion); ``hint_tolerance`` as a fraction of the key's size.
    """

    def __init__(
        self,
        keys: Iterable[CurveLike],
        *,
        hints: Optional[Iterable[_Seq[Any]]] = None,
        quality: Optional[str] = None,
        path: Optional[str] = None,
        correspondence: Optional[str] = None,
        intermediate: Optional[str] = None,
        fan_margin: Optional[float] = None,
        hint_tolerance: Optional[float] = None,
    ) -> None: ...
    def frames(
        self,
        count: Optional[int] = None,
        *,
        fps: float = 30.0,
        easing: Optional[str] = None,
        times: Optional[List[Optional[float]]] = None,
        durations: Optional[List[Optional[float]]] = None,
        holds: Optional[List[float]] = None,
    ) -> npt.NDArray[np.float64]:
        """Every frame, a (frames, n, 2) array (timing as ``immerse animate``)."""
    def frame(self, segment: int, t: float) -> Frame:
        """The frame at fraction ``t`` of segment ``segment``."""
    def tween(self, segment: int) -> Tween:
        """The tween of one segment, in its own vertex numbering."""
    #: The keys in the sequence's vertex numbering.
    keys: List[Points]
    vertex_count: int
    key_count: int
    key_names: List[str]

class CertifyReport:
    """The certificate of an animation (``immerse certify``)."""

    #: ``"certified"``, ``"invalid"`` or ``"undecided"``.
    answer: str
    #: True when every segment is certified.
    certified: bool
    #: ``"exact"``, ``"f64"`` or ``"f32"``.
    player: str
    segments: int
    certified_segments: int
    certified_as_given: int
    invalid: int
    undecided: int
    #: The input's name.
    file: str
    def __bool__(self) -> bool: ...
    def to_dict(self) -> Dict[str, Any]:
        """The JSON of ``immerse certify --json`` as a dict."""

def certify(
    animation: Union[Iterable[npt.ArrayLike], bytes, str, "os.PathLike[str]"],
    *,
    times: Optional[List[float]] = None,
    triangles: Optional[Iterable[Optional[npt.ArrayLike]]] = None,
    player: str = "exact",
    max_pieces: int = 24,
) -> CertifyReport:
    """Certify that an animation is an immersed disk at every moment for a
    player moving every vertex on a straight line between keys.

    ``animation``: key shapes (each (n, 2)), or a file (path or bytes) as
    ``immerse certify`` reads it (immerse JSON, Lottie, animated SVG).
    ``times`` and ``triangles`` (per key, ``None`` to triangulate) go with
    key shapes. Returns the answer; never raises for "invalid".
    """
