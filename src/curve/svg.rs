//! SVG curves, parsed with `usvg` (which turns `rect`, `circle`, `ellipse`,
//! `polygon` and `path` elements into paths and resolves transforms).
//!
//! The curve is the one closed subpath of the drawing: a subpath that
//! ends with `Z`, or whose last point equals its first. A drawing of
//! several closed subpaths is refused ([`CurveError::SeveralParts`], naming
//! them): it is read as a [`crate::drawing::Drawing`] instead. A drawing written by
//! immerse (`immerse-render`) marks its outline path
//! `id="immerse-outline"`, which is then read first, and its background
//! rectangle `id="immerse-background"`, which is never read. Its control points
//! are mapped by the element's absolute transform, Béziers are flattened
//! to [`SVG_FLATTEN_TOLERANCE`] times the diagonal of the subpath's control
//! polygon bounds, and y is negated (SVG is y down, immerse is y up).

use super::error::one_line;
use super::{CurveError, MAX_POINTS, RawCurve};
use crate::geom::Point;

/// Flattening tolerance for Bézier segments, relative to the diagonal of
/// the shape's bounding box: the flattened polyline stays within this
/// fraction of the diagonal of the true curve (0.1%).
pub(crate) const SVG_FLATTEN_TOLERANCE: f64 = 1e-3;

/// Upper bound on the segments one Bézier is split into, so that a
/// malformed file cannot ask for unbounded work.
const MAX_SEGMENTS_PER_CURVE: usize = 256;

/// Largest magnitude of a number in SVG path data (`d` attributes). The
/// SVG parser turns an elliptical arc into cubic Béziers at a fixed
/// absolute tolerance, so their count grows with the radius: at 1e50 a
/// 300-byte file asked for gigabytes (found by the `curve_svg` fuzz
/// target). At 1e12 an arc needs at most a few hundred segments, and no
/// drawing comes near it.
pub const MAX_SVG_PATH_NUMBER: f64 = 1e12;

/// The `id` immerse-render gives the outline path (the curve) of the SVG it
/// writes (`immerse_render::OUTLINE_ID`): read in preference to any other
/// shape.
const OUTLINE_ID: &str = "immerse-outline";

/// The `id` immerse-render gives the background rectangle of the SVG it
/// writes (`immerse_render::BACKGROUND_ID`): never read as the curve.
const BACKGROUND_ID: &str = "immerse-background";

#[derive(Clone, Copy, Debug, PartialEq)]
enum Seg {
    Line(Point),
    Quad(Point, Point),
    Cubic(Point, Point, Point),
}

pub(crate) fn parse(bytes: &[u8], label: &str) -> Result<RawCurve, CurveError> {
    let tree = load(bytes, label)?;
    let mut found = Vec::new();
    collect_closed(tree.root(), Some(OUTLINE_ID), &mut found, 1);
    if found.is_empty() {
        collect_closed(tree.root(), None, &mut found, MAX_SVG_SHAPES);
        // Copies of one outline (as `<use>` makes to fill and stroke it
        // apart) are one curve.
        found.dedup();
        if found.len() > 1 {
            let parts = closed_part_names(tree.root());
            return Err(CurveError::SeveralParts {
                path: label.to_string(),
                count: parts.len(),
                parts: list_names(&parts),
            });
        }
    }
    let Some((start, segs)) = found.pop() else {
        if transforms_hide_a_shape(bytes) {
            return Err(CurveError::SvgOutOfRange {
                path: label.to_string(),
            });
        }
        return Err(CurveError::NoClosedShape {
            path: label.to_string(),
        });
    };
    flatten(start, &segs, label)
}

/// Which closed shapes of an SVG drawing become curves when one drawing
/// holds several (a sequence of keyframes drawn in one file). With the
/// `cli` feature it is the command line's `--svg-keys` (each variant's
/// first doc paragraph is its help there).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum SvgShapes {
    /// Top-level groups (Inkscape layers) when there are two or more, else each
    /// closed shape.
    ///
    /// The groups count when at least two hold a closed shape.
    #[default]
    Auto,
    /// Each closed shape, in document order.
    ///
    /// Every closed subpath of every shape.
    Shapes,
    /// The closed shape of each top-level group or layer (a group of several
    /// closed shapes is refused, naming them).
    ///
    /// In document order, a closed subpath each. A group that is alone at
    /// its level (such as the one a `viewBox` or a wrapping `<g>` makes)
    /// is looked into.
    Groups,
}

/// Most curves one drawing may yield.
pub const MAX_SVG_SHAPES: usize = 1000;

/// Every closed shape of a drawing as chosen by `mode`, each with what
/// names it in the drawing: `shape K` (counting from 1) or `group 'ID'`
/// (`group K` when the group has no id).
pub(crate) fn parse_all(
    bytes: &[u8],
    label: &str,
    mode: SvgShapes,
) -> Result<Vec<(String, RawCurve)>, CurveError> {
    let tree = load(bytes, label)?;
    let shapes = |tree: &usvg::Tree| {
        let mut found = Vec::new();
        collect_closed(tree.root(), None, &mut found, MAX_SVG_SHAPES + 1);
        found
            .into_iter()
            .enumerate()
            .map(|(k, (start, segs))| {
                let name = format!("shape {}", k + 1);
                let raw = flatten(start, &segs, &format!("{label} ({name})"))?;
                Ok((name, raw))
            })
            .collect::<Result<Vec<_>, CurveError>>()
    };
    let groups = |tree: &usvg::Tree| {
        let mut level = tree.root();
        while let [usvg::Node::Group(g)] = level.children() {
            level = g;
        }
        let mut out = Vec::new();
        for (k, node) in level.children().iter().enumerate() {
            let usvg::Node::Group(g) = node else {
                continue;
            };
            let mut found = Vec::new();
            collect_closed(g, None, &mut found, 2);
            let name = if g.id().is_empty() {
                format!("group {}", k + 1)
            } else {
                format!("group '{}'", one_line(g.id()))
            };
            if found.len() > 1 {
                // One key per group: a group of several parts is a
                // drawing, not one curve.
                let parts = closed_part_names(g);
                return Err(CurveError::SeveralParts {
                    path: format!("{label} ({name})"),
                    count: parts.len(),
                    parts: list_names(&parts),
                });
            }
            if let Some((start, segs)) = found.pop() {
                let raw = flatten(start, &segs, &format!("{label} ({name})"))?;
                out.push((name, raw));
            }
        }
        Ok(out)
    };
    let found = match mode {
        SvgShapes::Shapes => shapes(&tree)?,
        SvgShapes::Groups => groups(&tree)?,
        SvgShapes::Auto => {
            if groups_with_shapes(&tree) >= 2 {
                groups(&tree)?
            } else {
                shapes(&tree)?
            }
        }
    };
    if found.is_empty() {
        return Err(CurveError::NoClosedShape {
            path: label.to_string(),
        });
    }
    if found.len() > MAX_SVG_SHAPES {
        return Err(CurveError::TooLarge {
            path: label.to_string(),
            what: format!("more than {MAX_SVG_SHAPES} closed shapes"),
            limit: format!("{MAX_SVG_SHAPES} shapes"),
        });
    }
    Ok(found)
}

/// How many top-level groups (as [`SvgShapes::Groups`] finds them) hold a
/// closed shape.
fn groups_with_shapes(tree: &usvg::Tree) -> usize {
    let mut level = tree.root();
    while let [usvg::Node::Group(g)] = level.children() {
        level = g;
    }
    level
        .children()
        .iter()
        .filter(|node| {
            let usvg::Node::Group(g) = node else {
                return false;
            };
            let mut found = Vec::new();
            collect_closed(g, None, &mut found, 1);
            !found.is_empty()
        })
        .count()
}

/// Screens and parses a drawing.
fn load(bytes: &[u8], label: &str) -> Result<usvg::Tree, CurveError> {
    screen(bytes, label)?;
    usvg::Tree::from_data(bytes, &usvg::Options::default()).map_err(|e| CurveError::Svg {
        path: label.to_string(),
        message: one_line(&e.to_string()),
    })
}

/// Flattens one closed subpath (already mapped by its transform) and
/// flips y; more than [`MAX_POINTS`] points are refused
/// ([`CurveError::TooLarge`]) before they are made.
fn flatten(start: Point, segs: &[Seg], label: &str) -> Result<RawCurve, CurveError> {
    let (mut lo, mut hi) = (start, start);
    for s in segs {
        let pts: &[Point] = match s {
            Seg::Line(a) => &[*a],
            Seg::Quad(a, b) => &[*a, *b],
            Seg::Cubic(a, b, c) => &[*a, *b, *c],
        };
        for &p in pts {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let tol = (SVG_FLATTEN_TOLERANCE * (hi - lo).length()).max(f64::MIN_POSITIVE);
    // Count the points first: a small file of arcs can ask for millions,
    // refused before any is made.
    let mut count = 1_usize;
    let mut cur = start;
    for &s in segs {
        count += match s {
            Seg::Line(p) => {
                cur = p;
                1
            }
            Seg::Quad(c, p) => {
                let n = segments_for(0.25 * (cur - 2.0 * c + p).length(), tol);
                cur = p;
                n
            }
            Seg::Cubic(c1, c2, p) => {
                let dd = (cur - 2.0 * c1 + c2)
                    .length()
                    .max((c1 - 2.0 * c2 + p).length());
                cur = p;
                segments_for(0.75 * dd, tol)
            }
        };
    }
    if count > MAX_POINTS {
        return Err(CurveError::TooLarge {
            path: label.to_string(),
            what: format!("{count} points once its curves are flattened"),
            limit: format!("{MAX_POINTS} points"),
        });
    }
    let mut points = Vec::with_capacity(count);
    points.push(start);
    let mut cur = start;
    for &s in segs {
        match s {
            Seg::Line(p) => points.push(p),
            Seg::Quad(c, p) => {
                let dd = (cur - 2.0 * c + p).length();
                let n = segments_for(0.25 * dd, tol);
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let u = 1.0 - t;
                    points.push(u * u * cur + 2.0 * u * t * c + t * t * p);
                }
            }
            Seg::Cubic(c1, c2, p) => {
                let dd = (cur - 2.0 * c1 + c2)
                    .length()
                    .max((c1 - 2.0 * c2 + p).length());
                let n = segments_for(0.75 * dd, tol);
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let u = 1.0 - t;
                    points.push(
                        u * u * u * cur
                            + 3.0 * u * u * t * c1
                            + 3.0 * u * t * t * c2
                            + t * t * t * p,
                    );
                }
            }
        }
        cur = *points.last().unwrap_or(&cur);
    }
    // Flip y: SVG is y down.
    let points = points
        .into_iter()
        .enumerate()
        .map(|(i, p)| (Point::new(p.x, -p.y), i))
        .collect();
    Ok(RawCurve {
        name: None,
        points,
        lines: false,
    })
}

/// Refuses, before usvg sees them, inputs that would make it do unbounded
/// work: gzip-compressed data (a decompression bomb) and path data with a
/// number over [`MAX_SVG_PATH_NUMBER`]. Data that is not UTF-8 or not XML
/// is left for usvg to report.
fn screen(bytes: &[u8], label: &str) -> Result<(), CurveError> {
    if bytes.starts_with(&[0x1f, 0x8b]) {
        return Err(CurveError::Svg {
            path: label.to_string(),
            message: "compressed SVG (svgz) is not supported; decompress it first".to_string(),
        });
    }
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Ok(());
    };
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    let Ok(doc) = roxmltree::Document::parse_with_options(text, options) else {
        return Ok(());
    };
    for node in doc.descendants().filter(roxmltree::Node::is_element) {
        for attr in node.attributes() {
            if attr.name() != "d" {
                continue;
            }
            if let Some(value) = largest_number(attr.value())
                && value > MAX_SVG_PATH_NUMBER
            {
                return Err(CurveError::SvgNumberTooLarge {
                    path: label.to_string(),
                    line: doc.text_pos_at(node.range().start).row,
                    value,
                    limit: MAX_SVG_PATH_NUMBER,
                });
            }
        }
    }
    Ok(())
}

/// True when the SVG parser finds a closed shape in the drawing once every
/// `transform` attribute is emptied: the parser drops shapes whose
/// transformed coordinates overflow its 32-bit floats, so the transforms,
/// not the shapes, are the problem. Only called when no shape was found.
fn transforms_hide_a_shape(bytes: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return false;
    };
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    let Ok(doc) = roxmltree::Document::parse_with_options(text, options) else {
        return false;
    };
    let mut values: Vec<std::ops::Range<usize>> = doc
        .descendants()
        .flat_map(|n| n.attributes())
        .filter(|a| a.name() == "transform")
        .map(|a| a.range_value())
        .collect();
    if values.is_empty() {
        return false;
    }
    values.sort_by_key(|r| r.start);
    let mut plain = String::with_capacity(text.len());
    let mut at = 0;
    for r in values {
        if r.start < at || r.end > text.len() {
            return false;
        }
        plain.push_str(&text[at..r.start]);
        at = r.end;
    }
    plain.push_str(&text[at..]);
    let Ok(tree) = usvg::Tree::from_data(plain.as_bytes(), &usvg::Options::default()) else {
        return false;
    };
    let mut found = Vec::new();
    collect_closed(tree.root(), None, &mut found, 1);
    !found.is_empty()
}

/// The largest magnitude among the numbers in SVG path data (NaN-free;
/// `None` when there are none). Reads a number as greedily as SVG's
/// grammar allows, so it never under-reads: flags written without
/// separators may be read together with what follows, which can only
/// over-estimate.
fn largest_number(data: &str) -> Option<f64> {
    let b = data.as_bytes();
    let digits = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut best: Option<f64> = None;
    let mut i = 0;
    while i < b.len() {
        let start = i;
        if b[i] == b'+' || b[i] == b'-' {
            i += 1;
        }
        let int_end = digits(i);
        let mut end = int_end;
        let mut frac_digits = false;
        if end < b.len() && b[end] == b'.' {
            end = digits(end + 1);
            frac_digits = end > int_end + 1;
        }
        if int_end == i && !frac_digits {
            // No digits: not a number; move on.
            i = start + 1;
            continue;
        }
        if end < b.len() && (b[end] == b'e' || b[end] == b'E') {
            let mut e = end + 1;
            if e < b.len() && (b[e] == b'+' || b[e] == b'-') {
                e += 1;
            }
            let e_end = digits(e);
            if e_end > e {
                end = e_end;
            }
        }
        if let Ok(v) = data[start..end].parse::<f64>() {
            let v = v.abs();
            if !v.is_nan() {
                best = Some(best.map_or(v, |m: f64| m.max(v)));
            }
        }
        i = end.max(start + 1);
    }
    best
}

/// Segments needed so that a Bézier whose second differences are bounded
/// by `m / (scale factor already applied)` deviates by at most `tol` from
/// its chords: n = ⌈√(m / tol)⌉ (Wang's bound).
fn segments_for(m: f64, tol: f64) -> usize {
    let n = (m / tol).sqrt().ceil();
    if n.is_finite() {
        (n as usize).clamp(1, MAX_SEGMENTS_PER_CURVE)
    } else {
        MAX_SEGMENTS_PER_CURVE
    }
}

/// Collects closed subpaths in document order, at most `limit`, of the
/// paths whose id is `only` (of every path but the background when
/// `None`): a subpath that ends with `Z`, or whose last point equals its
/// first.
fn collect_closed(
    group: &usvg::Group,
    only: Option<&str>,
    found: &mut Vec<(Point, Vec<Seg>)>,
    limit: usize,
) {
    for node in group.children() {
        if found.len() >= limit {
            return;
        }
        match node {
            usvg::Node::Group(g) => collect_closed(g, only, found, limit),
            usvg::Node::Path(path)
                if only.map_or(path.id() != BACKGROUND_ID, |id| path.id() == id) =>
            {
                for sub in subpaths(path) {
                    if sub.closed {
                        found.push((sub.start, sub.segs));
                        if found.len() >= limit {
                            return;
                        }
                    }
                }
            }
            _ => {}
        }
    }
}

/// One subpath of a path element, mapped by the element's absolute
/// transform (y still down).
#[derive(Clone, Debug)]
pub(crate) struct Subpath {
    /// Its first point.
    pub(crate) start: Point,
    /// Its segments, from `start`.
    segs: Vec<Seg>,
    /// True when it ends with `Z` or returns to its first point.
    pub(crate) closed: bool,
}

impl Subpath {
    /// The flattened points, y flipped up, as [`parse`] reads a curve;
    /// an open subpath is closed by its implicit closing edge.
    pub(crate) fn flatten(&self, label: &str) -> Result<RawCurve, CurveError> {
        flatten(self.start, &self.segs, label)
    }
}

/// The subpaths of one path element, in order (open ones included),
/// mapped by its absolute transform.
fn subpaths(path: &usvg::Path) -> Vec<Subpath> {
    let ts = path.abs_transform();
    let map = |p: usvg::tiny_skia_path::Point| {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        Point::new(
            f64::from(ts.sx) * x + f64::from(ts.kx) * y + f64::from(ts.tx),
            f64::from(ts.ky) * x + f64::from(ts.sy) * y + f64::from(ts.ty),
        )
    };
    let mut out = Vec::new();
    let mut start: Option<Point> = None;
    let mut segs: Vec<Seg> = Vec::new();
    let mut last = Point::ZERO;
    let mut finish = |start: Option<Point>, segs: &mut Vec<Seg>, closed: bool| {
        if let Some(s) = start
            && !segs.is_empty()
        {
            out.push(Subpath {
                start: s,
                segs: std::mem::take(segs),
                closed,
            });
        }
        segs.clear();
    };
    for seg in path.data().segments() {
        use usvg::tiny_skia_path::PathSegment as S;
        match seg {
            S::MoveTo(p) => {
                // A subpath that returned to its start is closed.
                finish(start, &mut segs, Some(last) == start);
                start = Some(map(p));
                last = map(p);
            }
            S::LineTo(p) => {
                last = map(p);
                segs.push(Seg::Line(last));
            }
            S::QuadTo(c, p) => {
                last = map(p);
                segs.push(Seg::Quad(map(c), last));
            }
            S::CubicTo(c1, c2, p) => {
                last = map(p);
                segs.push(Seg::Cubic(map(c1), map(c2), last));
            }
            S::Close => {
                finish(start, &mut segs, true);
                if let Some(s) = start {
                    last = s;
                }
            }
        }
    }
    finish(start, &mut segs, Some(last) == start);
    out
}

/// A path element of a drawing with its subpaths, in document order.
#[derive(Clone, Debug)]
pub(crate) struct Element {
    /// The element as the SVG parser gives it (style, id).
    pub(crate) path: usvg::Path,
    /// The product of the opacities of the groups it is in.
    pub(crate) group_opacity: f64,
    /// Its subpaths, open ones included.
    pub(crate) subpaths: Vec<Subpath>,
}

/// Appends the visible path elements under `group` (but immerse's own
/// background), in painting order, with `opacity` the product of the
/// group opacities above them.
fn walk(group: &usvg::Group, opacity: f64, out: &mut Vec<Element>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => walk(g, opacity * f64::from(g.opacity().get()), out),
            usvg::Node::Path(path) if path.id() != BACKGROUND_ID && path.is_visible() => {
                let subpaths = subpaths(path);
                if !subpaths.is_empty() {
                    out.push(Element {
                        path: (**path).clone(),
                        group_opacity: opacity,
                        subpaths,
                    });
                }
            }
            _ => {}
        }
    }
}

/// Every visible path element of a drawing but immerse's own background,
/// in document (painting) order.
pub(crate) fn elements(bytes: &[u8], label: &str) -> Result<Vec<Element>, CurveError> {
    let tree = load(bytes, label)?;
    let mut out = Vec::new();
    walk(tree.root(), 1.0, &mut out);
    if out.is_empty() && transforms_hide_a_shape(bytes) {
        return Err(CurveError::SvgOutOfRange {
            path: label.to_string(),
        });
    }
    Ok(out)
}

/// The visible path elements of each top-level group of a drawing (as
/// [`SvgShapes::Groups`] finds the groups: a group alone at its level is
/// looked into), each with what names it (`group 'ID'` or `group K`), in
/// document order; groups without a path element are left out.
pub(crate) fn group_elements(
    bytes: &[u8],
    label: &str,
) -> Result<Vec<(String, Vec<Element>)>, CurveError> {
    let tree = load(bytes, label)?;
    let mut level = tree.root();
    let mut opacity = 1.0;
    while let [usvg::Node::Group(g)] = level.children() {
        level = g;
        opacity *= f64::from(g.opacity().get());
    }
    let mut out = Vec::new();
    for (k, node) in level.children().iter().enumerate() {
        let usvg::Node::Group(g) = node else {
            continue;
        };
        let mut elements = Vec::new();
        walk(g, opacity * f64::from(g.opacity().get()), &mut elements);
        if elements.is_empty() {
            continue;
        }
        let name = if g.id().is_empty() {
            format!("group {}", k + 1)
        } else {
            format!("group '{}'", one_line(g.id()))
        };
        out.push((name, elements));
    }
    Ok(out)
}

/// What names closed subpath `sub` (counting from 0) of element number
/// `element` (counting from 0) with id `id` that has `count` closed
/// subpaths: `path 'ID'` or `path K`, followed by `subpath J` when the
/// element has several.
pub(crate) fn part_name(element: usize, id: &str, sub: usize, count: usize) -> String {
    let path = if id.is_empty() {
        format!("path {}", element + 1)
    } else {
        format!("path '{}'", one_line(id))
    };
    if count > 1 {
        format!("{path} subpath {}", sub + 1)
    } else {
        path
    }
}

/// The names of the closed parts of a drawing (see [`part_name`]), for the
/// message that refuses a drawing where one curve is expected.
fn closed_part_names(group: &usvg::Group) -> Vec<String> {
    fn walk(group: &usvg::Group, element: &mut usize, out: &mut Vec<String>) {
        for node in group.children() {
            match node {
                usvg::Node::Group(g) => walk(g, element, out),
                usvg::Node::Path(path) if path.id() != BACKGROUND_ID => {
                    let closed = subpaths(path).into_iter().filter(|s| s.closed).count();
                    for k in 0..closed {
                        out.push(part_name(*element, path.id(), k, closed));
                    }
                    *element += 1;
                }
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    walk(group, &mut 0, &mut out);
    out
}

/// `names` listed for a message: all of them up to 6, else the first 5
/// and how many more.
pub(crate) fn list_names(names: &[String]) -> String {
    if names.len() <= 6 {
        names.join(", ")
    } else {
        format!("{}, and {} more", names[..5].join(", "), names.len() - 5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (fuzz target `curve_svg`, seed
    /// `fuzz/seeds/curve_svg/regression-newline-in-parser-message.svg`):
    /// the XML parser quotes the offending character, here a line break,
    /// which split the CLI's one-line error in two.
    #[test]
    fn parser_messages_stay_on_one_line() {
        let data =
            b"<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0 L1 0 L0 1 Z\"/\n</svg>";
        let e = parse(data, "s.svg").unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, CurveError::Svg { .. }), "{msg}");
        assert!(!msg.contains('\n'), "{msg:?}");
        assert!(msg.contains("\\n"), "the character is shown escaped: {msg}");
        let crash =
            include_bytes!("../../fuzz/seeds/curve_svg/regression-newline-in-parser-message.svg");
        let msg = parse(crash, "c.svg").unwrap_err().to_string();
        assert!(!msg.chars().any(char::is_control), "{msg:?}");
    }

    #[test]
    fn largest_number_reads_path_data_greedily() {
        assert_eq!(largest_number("M0 0 L5 5 Z"), Some(5.0));
        assert_eq!(largest_number("M-7.5-2e3.5 .25"), Some(2e3));
        assert_eq!(largest_number("M1e 2E+2"), Some(200.0));
        assert_eq!(largest_number("A10 10 0 1120 20"), Some(1120.0));
        assert_eq!(largest_number("M . - + e"), None);
        assert_eq!(largest_number("M0 1e999"), Some(f64::INFINITY));
        assert_eq!(largest_number(""), None);
    }

    /// Regression (fuzz target `curve_svg`, seed
    /// `fuzz/seeds/curve_svg/regression-oom-huge-arc-radius.svg`): an arc
    /// of radius 5e47 in a 327-byte file made the SVG parser allocate
    /// gigabytes. It is refused up front, naming the line.
    #[test]
    fn huge_arc_radius_is_refused_before_parsing() {
        let crash = include_bytes!("../../fuzz/seeds/curve_svg/regression-oom-huge-arc-radius.svg");
        let e = parse(crash, "arc.svg").unwrap_err();
        assert!(
            matches!(e, CurveError::SvgNumberTooLarge { line: 3, .. }),
            "{e}"
        );
        let small = br#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 80 -60 A 100 100 0 1 0 80 60 Z"/></svg>"#;
        let raw = parse(small, "arc.svg").unwrap();
        assert!(raw.points.len() > 8, "an arc is flattened");
        let big = br#"<svg xmlns="http://www.w3.org/2000/svg">
<path d="M 80 -60 A 100 2e12 0 1 0 80 60 Z"/></svg>"#;
        assert_eq!(
            parse(big, "arc.svg").unwrap_err().to_string(),
            "arc.svg:2: path data has a number of magnitude 2e12, over the limit 1e12 for SVG path data; rescale the drawing"
        );
    }

    #[test]
    fn compressed_svg_is_refused() {
        let e = parse(&[0x1f, 0x8b, 8, 0, 0, 0], "z.svg").unwrap_err();
        assert_eq!(
            e.to_string(),
            "z.svg: not a readable SVG: compressed SVG (svgz) is not supported; decompress it first"
        );
    }
}
