//! Drawings from SVG: every closed subpath of every visible path element,
//! in document order, with its element's style.

use super::style::{Color, FillRule, Style};
use super::{Drawing, DrawingError, Shape, holes};
use crate::curve::svg::{Element, elements, group_elements, list_names, part_name};
use crate::curve::{Curve, CurveError};

pub(super) fn read(bytes: &[u8], label: &str, name: &str) -> Result<Drawing, DrawingError> {
    let elements = elements(bytes, label)?;
    from_elements(&elements, label, name)
}

/// Every top-level group as a drawing of its own, named as the group
/// (`group 'ID'` or `group K`); errors name the file and the group.
pub(super) fn read_groups(bytes: &[u8], label: &str) -> Result<Vec<Drawing>, DrawingError> {
    group_elements(bytes, label)?
        .into_iter()
        .map(|(name, elements)| from_elements(&elements, &format!("{label} ({name})"), &name))
        .collect()
}

fn from_elements(elements: &[Element], label: &str, name: &str) -> Result<Drawing, DrawingError> {
    let mut shapes = Vec::new();
    let mut notices = Vec::new();
    let mut left_out = Vec::new();
    for (e, element) in elements.iter().enumerate() {
        let style = style_of(element, e, &mut notices);
        // A filled subpath left open is closed (SVG fills it so); an open
        // stroke-only one is a line, not a shape.
        let kept: Vec<_> = element
            .subpaths
            .iter()
            .enumerate()
            .filter(|(_, s)| s.closed || style.fill.is_some())
            .collect();
        for (k, s) in element.subpaths.iter().enumerate() {
            if !s.closed && style.fill.is_none() {
                let what = part_name(e, element.path.id(), k, element.subpaths.len());
                notices.push(format!(
                    "{what}: an open stroke-only path is a line, not a shape; left out"
                ));
                left_out.push(what);
            }
        }
        let first = shapes.len();
        for (j, (_, sub)) in kept.iter().enumerate() {
            let part = part_name(e, element.path.id(), j, kept.len());
            let position = shapes.len() + 1;
            let shape_label = format!("shape {position} ({part})");
            let raw = sub.flatten(&format!("{label} ({shape_label})"))?;
            let curve =
                Curve::from_raw(name.to_string(), raw, &format!("{label} ({shape_label})"))?;
            // A copy of the shape just read (as `<use>` makes to fill and
            // stroke one outline apart) paints the same shape: its paint
            // completes that shape's.
            if let Some(prev) = shapes
                .last_mut()
                .filter(|p: &&mut Shape| p.points == curve.points)
            {
                if prev.style.fill.is_none() {
                    prev.style.fill = style.fill;
                    prev.style.fill_rule = style.fill_rule;
                }
                if prev.style.stroke.is_none() && style.stroke.is_some() {
                    prev.style.stroke = style.stroke;
                    prev.style.stroke_width = style.stroke_width;
                }
                continue;
            }
            let id = match (element.path.id(), kept.len()) {
                ("", _) => String::new(),
                (id, 1) => id.to_string(),
                (id, _) => format!("{id}.{}", j + 1),
            };
            shapes.push(Shape::new(id, shape_label, curve, style));
        }
        if kept.len() > 1 {
            let polys: Vec<&[crate::geom::Point]> = shapes[first..]
                .iter()
                .map(|s| s.points.as_slice())
                .collect();
            let reversed: Vec<bool> = shapes[first..].iter().map(|s| s.reversed).collect();
            if let Some((hole, outer)) = holes::find(&polys, &reversed, style.fill_rule) {
                return Err(DrawingError::Hole {
                    path: label.to_string(),
                    hole: shapes[first + hole].label.clone(),
                    outer: shapes[first + outer].label.clone(),
                    rule: style.fill_rule,
                });
            }
        }
    }
    if shapes.is_empty() {
        if left_out.is_empty() {
            return Err(CurveError::NoClosedShape {
                path: label.to_string(),
            }
            .into());
        }
        return Err(DrawingError::Empty {
            path: label.to_string(),
            why: format!("open stroke-only paths left out: {}", list_names(&left_out)),
        });
    }
    Ok(Drawing {
        name: name.to_string(),
        single_curve: shapes.len() == 1 && notices.is_empty(),
        shapes,
        notices,
    })
}

/// The element's paint; a gradient or pattern becomes one colour, with a
/// notice.
fn style_of(element: &Element, e: usize, notices: &mut Vec<String>) -> Style {
    let path = &element.path;
    let what = part_name(e, path.id(), 0, 1);
    let mut colour = |paint: &usvg::Paint, role: &str| match paint {
        usvg::Paint::Color(c) => Color {
            r: c.red,
            g: c.green,
            b: c.blue,
        },
        usvg::Paint::LinearGradient(g) => flat(g.stops(), &what, role, notices),
        usvg::Paint::RadialGradient(g) => flat(g.stops(), &what, role, notices),
        usvg::Paint::Pattern(_) => {
            let grey = Color {
                r: 128,
                g: 128,
                b: 128,
            };
            notices.push(format!(
                "{what}: {role} pattern replaced by the solid colour {}",
                grey.hex()
            ));
            grey
        }
    };
    let fill = path.fill().map(|f| (colour(f.paint(), "fill"), f));
    let stroke = path.stroke().map(|s| (colour(s.paint(), "stroke"), s));
    let paint_opacity = match (&fill, &stroke) {
        (Some((_, f)), _) => f64::from(f.opacity().get()),
        (None, Some((_, s))) => f64::from(s.opacity().get()),
        (None, None) => 1.0,
    };
    Style {
        fill: fill.as_ref().map(|(c, _)| *c),
        stroke: stroke.as_ref().map(|(c, _)| *c),
        stroke_width: stroke
            .as_ref()
            .map_or(1.0, |(_, s)| f64::from(s.width().get())),
        opacity: element.group_opacity * paint_opacity,
        fill_rule: match fill.as_ref().map(|(_, f)| f.rule()) {
            Some(usvg::FillRule::EvenOdd) => FillRule::Evenodd,
            _ => FillRule::Nonzero,
        },
    }
}

/// A gradient flattened to the mean of its stops' colours (in OKLab,
/// weighted by each stop's opacity), with a notice.
fn flat(stops: &[usvg::Stop], what: &str, role: &str, notices: &mut Vec<String>) -> Color {
    let mut sum = [0.0; 3];
    let mut weight = 0.0;
    for s in stops {
        let c = s.color();
        let lab = Color {
            r: c.red,
            g: c.green,
            b: c.blue,
        }
        .to_oklab();
        let w = f64::from(s.opacity().get()).max(1e-3);
        for (acc, v) in sum.iter_mut().zip(lab) {
            *acc += w * v;
        }
        weight += w;
    }
    let c = if weight > 0.0 {
        Color::from_oklab(sum.map(|v| v / weight))
    } else {
        Color::BLACK
    };
    notices.push(format!(
        "{what}: {role} gradient flattened to the solid colour {}",
        c.hex()
    ));
    c
}
