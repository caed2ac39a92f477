//! Third-vertex paths of the propagation morph (docs/design.md §6).
//!
//! Everything here works in a triangle's *base frame*: the base edge runs
//! from (0, 0) to (1, 0) and the third vertex sits at (α, β) with β > 0 for
//! a counter-clockwise triangle.

use crate::geom::Point;
use std::f64::consts::PI;

/// Whether the command line hides the experimental paths and
/// correspondences (from its help and its list of values): unless built
/// with the `experimental` feature.
#[cfg(feature = "cli")]
pub(crate) const HIDE_EXPERIMENTAL: bool = !cfg!(feature = "experimental");

/// How each triangle's third vertex travels from its source to its target
/// position relative to its base. With the `cli` feature it is the command
/// line's `--path`, variants in its order (each variant's first doc
/// paragraph is its help there; the experimental paths are hidden, and
/// refused by [`FromStr`](std::str::FromStr), unless built with the
/// `experimental` feature).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum ThirdVertexPath {
    /// As rigid as validity allows: each triangle's rotation and stretch
    /// interpolated, positions by least squares; parts turn instead of
    /// shrinking, spirals wind (guaranteed).
    ///
    /// Every triangle's rotation and stretch interpolated separately
    /// (rotations unwound along the dual tree) and the positions fitted to
    /// them by least squares (Alexa, Cohen-Or & Levin's
    /// as-rigid-as-possible interpolation), projected into the valid angle
    /// set where that is invalid. Spirals wind along their turns, and every
    /// t gives an immersion. The default.
    #[default]
    Rigid,
    /// Rotate-slide angles blended just enough to stay an immersion
    /// (guaranteed).
    ///
    /// Blended toward the angle rule just enough to keep every vertex fan
    /// below 2π: an immersion for every t with little distortion.
    Hybrid,
    /// As straight as validity allows: linear where the linear morph is valid;
    /// on the last leg it competes with hybrid and polar (guaranteed).
    ///
    /// The end shapes interpolated linearly (in a frame turning by their
    /// best-fit rotation), projected into the valid angle set only where
    /// that interpolation is invalid: an immersion for every t.
    Straight,
    /// As straight as validity allows along arcs about the centre: spirals wind
    /// (guaranteed).
    ///
    /// Like `straight`, but the end shapes are interpolated in polar
    /// coordinates about their vertex means (each vertex's angle, unwound
    /// along the curve, and its distance), so a spiral winds up along its
    /// own turns instead of cutting across them. An immersion for every t.
    /// The default path tries it on the last leg where `hybrid` travels
    /// less than `straight`, and keeps the one whose vertices travel least.
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Polar,
    /// Linear interpolation of triangle angles (guaranteed, more distortion).
    ///
    /// The triangles are laid out from their interpolated angles: an
    /// immersion for every t.
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Angle,
    /// The paper's rotate-and-slide path (checked; falls back to hybrid).
    ///
    /// Mukherjee & Gopi's path (their Fig. 7): keep the length of a
    /// propagation edge monotone. Not guaranteed: it may fold the shape
    /// (detected, then `hybrid` is used instead).
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    RotateSlide,
    /// Linear base-relative coordinates (checked; falls back to hybrid).
    ///
    /// Not guaranteed either: it may fold the shape on strong deformations
    /// (detected, then `hybrid` is used instead).
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Linear,
}

impl ThirdVertexPath {
    /// All paths, in the order of the CLI's possible values.
    pub const ALL: [ThirdVertexPath; 7] = [
        ThirdVertexPath::Rigid,
        ThirdVertexPath::Hybrid,
        ThirdVertexPath::Straight,
        ThirdVertexPath::Polar,
        ThirdVertexPath::Angle,
        ThirdVertexPath::RotateSlide,
        ThirdVertexPath::Linear,
    ];

    /// The CLI name: `hybrid`, `straight`, `polar`, `angle`,
    /// `rotate-slide` or `linear`.
    pub fn as_str(self) -> &'static str {
        match self {
            ThirdVertexPath::Linear => "linear",
            ThirdVertexPath::RotateSlide => "rotate-slide",
            ThirdVertexPath::Angle => "angle",
            ThirdVertexPath::Hybrid => "hybrid",
            ThirdVertexPath::Straight => "straight",
            ThirdVertexPath::Polar => "polar",
            ThirdVertexPath::Rigid => "rigid",
        }
    }

    /// True for the paths offered only with the `experimental` cargo
    /// feature: `polar`, `angle`, `rotate-slide` and `linear`. Each is
    /// dominated on the motion measures of docs/design.md §7c by `rigid`,
    /// `straight` or `hybrid` (docs/motion-by-option.md). The planner
    /// still uses `polar` and `angle` inside: on the last leg and to
    /// recover a leg.
    pub fn is_experimental(self) -> bool {
        matches!(
            self,
            ThirdVertexPath::Polar
                | ThirdVertexPath::Angle
                | ThirdVertexPath::RotateSlide
                | ThirdVertexPath::Linear
        )
    }

    /// The paths a user may ask for in this build: `rigid`, `hybrid` and
    /// `straight`, and the experimental ones with the `experimental`
    /// feature.
    pub fn offered() -> Vec<ThirdVertexPath> {
        offered(&ThirdVertexPath::ALL, ThirdVertexPath::is_experimental)
    }

    /// True for the paths that guarantee an immersion for every t.
    pub(crate) fn is_guaranteed(self) -> bool {
        matches!(
            self,
            ThirdVertexPath::Angle
                | ThirdVertexPath::Hybrid
                | ThirdVertexPath::Straight
                | ThirdVertexPath::Polar
                | ThirdVertexPath::Rigid
        )
    }
}

impl std::fmt::Display for ThirdVertexPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for ThirdVertexPath {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_offered(
            "path",
            s,
            &ThirdVertexPath::ALL,
            ThirdVertexPath::as_str,
            ThirdVertexPath::is_experimental,
        )
    }
}

/// The values of `all` a user may ask for in this build: the experimental
/// ones only with the `experimental` feature.
pub(crate) fn offered<T: Copy>(all: &[T], is_experimental: fn(T) -> bool) -> Vec<T> {
    all.iter()
        .copied()
        .filter(|&v| cfg!(feature = "experimental") || !is_experimental(v))
        .collect()
}

/// The value of `all` that `name` calls `s`, if this build offers it
/// ([`offered`]). An unknown name, or an experimental one in a build
/// without the `experimental` feature, is refused naming `what` (a path, a
/// correspondence) and the values offered instead.
pub(crate) fn parse_offered<T: Copy + PartialEq>(
    what: &str,
    s: &str,
    all: &[T],
    name: fn(T) -> &'static str,
    is_experimental: fn(T) -> bool,
) -> Result<T, String> {
    let offered = offered(all, is_experimental);
    let names: Vec<&str> = offered.iter().map(|&v| name(v)).collect();
    let names = names.join(", ");
    match all.iter().copied().find(|&v| name(v) == s) {
        Some(v) if offered.contains(&v) => Ok(v),
        Some(v) => Err(format!(
            "the {what} '{}' is experimental: it does worse than {names} on the motion measures \
             (docs/motion-by-option.md); use one of those, or build immerse with \
             `--features experimental` to keep it",
            name(v)
        )),
        None => Err(format!("unknown {what} '{s}'; use {names}")),
    }
}

/// Base-frame coordinates of `w` relative to the base `x → y`.
pub(crate) fn to_base_frame(x: Point, y: Point, w: Point) -> Point {
    let e = y - x;
    let d = w - x;
    let l2 = e.length_squared();
    Point::new(e.dot(d) / l2, e.perp_dot(d) / l2)
}

/// World position of base-frame coordinates `c` on the base `x → y`.
pub(crate) fn from_base_frame(x: Point, y: Point, c: Point) -> Point {
    let e = y - x;
    x + e * c.x + e.perp() * c.y
}

/// The rotate-and-slide path of one third vertex in the base frame.
///
/// `pivot` is the base end whose propagation edge (pivot → third vertex)
/// should change length monotonically. The linear path already does so
/// unless the foot of the perpendicular from the pivot to the segment
/// C1–C2 falls strictly inside it; then part of the path is replaced by an
/// arc of radius min(l1, l2) about the pivot (Mukherjee & Gopi §5, Fig. 7): hold
/// the length on the arc, then slide along a tangent (or slide first, then
/// hold), so the length stays between l1 and l2 throughout.
#[derive(Clone, Copy, Debug)]
pub(crate) enum RotateSlide {
    /// Straight from C1 to C2.
    Line { c1: Point, c2: Point },
    /// Arc about `pivot` of radius `r` from angle `a0` by `da`, joined to a
    /// line segment; `arc_first` says which comes first.
    ArcLine {
        pivot: Point,
        r: f64,
        a0: f64,
        da: f64,
        line_from: Point,
        line_to: Point,
        arc_first: bool,
    },
}

impl RotateSlide {
    /// Plans the path for one triangle; `pivot` is `None` when the triangle
    /// has no propagation edge whose length the linear path breaks.
    pub(crate) fn plan(c1: Point, c2: Point, pivots: &[Point]) -> RotateSlide {
        for &p in pivots {
            let d = c2 - c1;
            let len2 = d.length_squared();
            if len2 == 0.0 {
                break;
            }
            let s = (p - c1).dot(d) / len2;
            if s <= 0.0 || s >= 1.0 {
                continue;
            }
            let (l1, l2) = ((c1 - p).length(), (c2 - p).length());
            // Near endpoint on the circle, far endpoint outside it.
            let (near, far, arc_first) = if l1 <= l2 {
                (c1, c2, true)
            } else {
                (c2, c1, false)
            };
            let r = l1.min(l2);
            let q = far - p;
            let dq = q.length();
            if r <= 0.0 || dq <= r {
                continue;
            }
            let phi = (r / dq).clamp(-1.0, 1.0).acos();
            let base = q.to_angle();
            let a_near = (near - p).to_angle();
            // Two tangent points; take the one with the shorter total path.
            let mut best: Option<(f64, f64, f64, Point)> = None;
            for sgn in [-1.0, 1.0] {
                let a_t = base + sgn * phi;
                let tp = p + Point::from_angle(a_t) * r;
                let da = wrap_pi(a_t - a_near);
                let total = r * da.abs() + (far - tp).length();
                if best.is_none_or(|b| total < b.0) {
                    best = Some((total, a_near, da, tp));
                }
            }
            let Some((_, a_near, da, tp)) = best else {
                continue;
            };
            return if arc_first {
                RotateSlide::ArcLine {
                    pivot: p,
                    r,
                    a0: a_near,
                    da,
                    line_from: tp,
                    line_to: far,
                    arc_first: true,
                }
            } else {
                // Slide from C1 (far) to the tangent point, then the arc
                // from the tangent point to C2 (near).
                RotateSlide::ArcLine {
                    pivot: p,
                    r,
                    a0: a_near + da,
                    da: -da,
                    line_from: far,
                    line_to: tp,
                    arc_first: false,
                }
            };
        }
        RotateSlide::Line { c1, c2 }
    }

    /// The position at `t` ∈ [0, 1], moving at constant speed along the
    /// path.
    pub(crate) fn at(&self, t: f64) -> Point {
        match *self {
            RotateSlide::Line { c1, c2 } => c1.lerp(c2, t),
            RotateSlide::ArcLine {
                pivot,
                r,
                a0,
                da,
                line_from,
                line_to,
                arc_first,
            } => {
                let arc = r * da.abs();
                let line = (line_to - line_from).length();
                let total = arc + line;
                if total <= 0.0 {
                    return line_from;
                }
                let s = t * total;
                let on_arc = |u: f64| pivot + Point::from_angle(a0 + da * u) * r;
                if arc_first {
                    if s <= arc && arc > 0.0 {
                        on_arc(s / arc)
                    } else {
                        line_from.lerp(line_to, ((s - arc) / line.max(f64::MIN_POSITIVE)).min(1.0))
                    }
                } else if s <= line && line > 0.0 {
                    line_from.lerp(line_to, s / line)
                } else {
                    on_arc(((s - line) / arc.max(f64::MIN_POSITIVE)).min(1.0))
                }
            }
        }
    }
}

fn wrap_pi(a: f64) -> f64 {
    let mut a = a.rem_euclid(2.0 * PI);
    if a > PI {
        a -= 2.0 * PI;
    }
    a
}

/// Angles at the base start, base end and third vertex of the base-frame
/// triangle (0,0), (1,0), c; `None` unless strictly counter-clockwise.
pub(crate) fn base_frame_angles(c: Point) -> Option<[f64; 3]> {
    if c.y <= 0.0 || !c.is_finite() {
        return None;
    }
    let ax = c.y.atan2(c.x);
    let ay = c.y.atan2(1.0 - c.x);
    let aw = PI - ax - ay;
    (ax > 0.0 && ay > 0.0 && aw > 0.0).then_some([ax, ay, aw])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::points;

    #[test]
    fn base_frame_round_trip() {
        let [x, y, w] = points([(1.0, 2.0), (4.0, 6.0), (-1.0, 5.0)]);
        let c = to_base_frame(x, y, w);
        assert!((from_base_frame(x, y, c) - w).length() < 1e-12);
        assert!(c.y > 0.0);
    }

    #[test]
    fn rotate_slide_keeps_the_edge_length_monotone() {
        // The linear path from C1 to C2 passes close to the pivot (1, 0):
        // its distance dips; rotate-slide must keep it between l1 and l2.
        let c1 = Point::new(0.2, 0.9);
        let c2 = Point::new(2.6, 1.4);
        let pivot = Point::new(1.0, 0.0);
        let plan = RotateSlide::plan(c1, c2, &[pivot]);
        assert!(matches!(plan, RotateSlide::ArcLine { .. }));
        assert!((plan.at(0.0) - c1).length() < 1e-12);
        assert!((plan.at(1.0) - c2).length() < 1e-12);
        let mut last = (c1 - pivot).length();
        for i in 1..=200 {
            let l = (plan.at(i as f64 / 200.0) - pivot).length();
            assert!(l >= last - 1e-12, "length fell at step {i}: {last} -> {l}");
            last = l;
        }
        // Reversed: monotone decreasing.
        let back = RotateSlide::plan(c2, c1, &[pivot]);
        assert!((back.at(0.0) - c2).length() < 1e-12);
        assert!((back.at(1.0) - c1).length() < 1e-12);
        let mut last = (c2 - pivot).length();
        for i in 1..=200 {
            let l = (back.at(i as f64 / 200.0) - pivot).length();
            assert!(l <= last + 1e-12);
            last = l;
        }
    }

    #[test]
    fn monotone_linear_path_stays_linear() {
        let plan = RotateSlide::plan(Point::new(0.5, 0.5), Point::new(0.5, 2.0), &[Point::ZERO]);
        assert!(matches!(plan, RotateSlide::Line { .. }));
    }

    /// Every value of `all` parses back from its name when this build
    /// offers it (`offered`: 3 values, all 7 with the `experimental`
    /// feature), else is refused naming `names`, the values offered;
    /// `unknown` is refused.
    fn names_round_trip<T>(
        all: &[T],
        name: fn(T) -> &'static str,
        is_experimental: fn(T) -> bool,
        offered: &[T],
        names: &str,
        unknown: &str,
    ) where
        T: Copy + PartialEq + std::fmt::Debug + std::str::FromStr<Err = String>,
    {
        for &v in all {
            let parsed = name(v).parse::<T>();
            if cfg!(feature = "experimental") || !is_experimental(v) {
                assert_eq!(parsed, Ok(v));
            } else {
                // Refused, naming the offered values.
                let e = parsed.unwrap_err();
                assert!(e.contains("experimental") && e.contains(names), "{e}");
            }
        }
        assert_eq!(
            offered.len(),
            if cfg!(feature = "experimental") { 7 } else { 3 }
        );
        assert!(unknown.parse::<T>().is_err());
    }

    #[test]
    fn path_names_round_trip() {
        names_round_trip(
            &ThirdVertexPath::ALL,
            ThirdVertexPath::as_str,
            ThirdVertexPath::is_experimental,
            &ThirdVertexPath::offered(),
            "rigid, hybrid, straight",
            "spline",
        );
    }

    #[test]
    fn correspondence_names_round_trip() {
        use crate::morph::Correspondence;
        names_round_trip(
            &Correspondence::ALL,
            Correspondence::as_str,
            Correspondence::is_experimental,
            &Correspondence::offered(),
            "corners, min-flips, best",
            "nearest",
        );
    }
}
