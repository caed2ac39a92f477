//! `immerse morph` on drawings: every shape morphs, matched shapes in
//! parallel, unmatched ones growing or shrinking (docs/design.md §2b).

use super::ImageOutput;
use crate::Outcome;
use crate::args::{MatchArg, MorphArgs};
use crate::output;
use anyhow::Context;
use immerse::drawing::{
    Color, Drawing, DrawingFrame, DrawingTween, MatchMode, Matching, match_shapes,
};
use immerse::morph::CurveMorphOptions;
use immerse_render as render;
use serde::Serialize;

/// One pair of the matching, as the JSON and the summary give it.
#[derive(Serialize)]
struct Pair {
    /// Source shape index (from 0) and id.
    source: usize,
    source_id: String,
    /// Target shape index (from 0) and id.
    target: usize,
    target_id: String,
    /// The pair's cost (docs/design.md §2b).
    cost: f64,
}

/// The matching in the JSON.
#[derive(Serialize)]
pub(crate) struct MatchingReport {
    mode: MatchMode,
    pairs: Vec<Pair>,
    /// Source shapes that vanish (indices).
    vanishing: Vec<usize>,
    /// Target shapes that appear (indices).
    appearing: Vec<usize>,
}

/// `immerse morph --json` on drawings.
#[derive(Serialize)]
pub(crate) struct DrawingMorphJson<'a> {
    pub(crate) matching: MatchingReport,
    pub(crate) notices: Vec<String>,
    pub(crate) frames: &'a [DrawingFrame],
}

fn shape_name(d: &Drawing, i: usize) -> String {
    let s = &d.shapes[i];
    if s.id.is_empty() {
        format!("shape {}", i + 1)
    } else {
        format!("'{}'", s.id)
    }
}

pub(crate) fn run(
    args: &MorphArgs,
    images: Option<ImageOutput>,
    options: &CurveMorphOptions,
) -> anyhow::Result<Outcome> {
    let easing: render::Easing = args
        .easing
        .parse()
        .with_context(|| format!("--easing '{}'", args.easing))?;
    let start = std::time::Instant::now();
    let a = Drawing::from_path(&args.source)?;
    let b = Drawing::from_path(&args.target)?;
    let mut notices = Vec::new();
    for (d, path) in [(&a, &args.source), (&b, &args.target)] {
        for n in &d.notices {
            notices.push(format!("{}: {n}", path.display()));
        }
    }
    if !args.quiet {
        for n in &notices {
            output::note(n);
        }
    }
    let mode = match args.match_mode {
        MatchArg::Id => MatchMode::Id,
        MatchArg::Order => MatchMode::Order,
        MatchArg::Auto => MatchMode::Auto,
    };
    let matching = match_shapes(&a, &b, mode);
    let tween = DrawingTween::new(&a, &b, &matching, options)?;
    let times = render::frame_times(args.frames as usize, &easing);
    let frames = times
        .iter()
        .map(|&t| tween.frame(t))
        .collect::<Result<Vec<_>, _>>()?;
    let elapsed = start.elapsed();
    if let Some(json) = &args.json {
        let report = DrawingMorphJson {
            matching: report(&a, &b, &matching),
            notices,
            frames: &frames,
        };
        super::write_json(json, &report, false, args.force)?;
    }
    if let (Some(out), Some(images)) = (&args.output, images) {
        let rendered: Vec<render::Frame> = frames.iter().map(render_frame).collect();
        super::morph::write_frames(
            &rendered,
            None,
            out,
            images,
            &super::morph::style(args),
            args.fps,
            super::morph::looping(args),
            args.force,
            args.quiet,
        )?;
    }
    if !args.quiet {
        output::note(&summary(&a, &b, &matching));
        output::note(&format!(
            "{} shapes, {} frames computed and verified (every shape of every frame an immersed disk) in {:.0} ms",
            tween.shape_count(),
            frames.len(),
            elapsed.as_secs_f64() * 1e3
        ));
    }
    Ok(Outcome::Success)
}

pub(crate) fn report(a: &Drawing, b: &Drawing, m: &Matching) -> MatchingReport {
    MatchingReport {
        mode: m.mode,
        pairs: m
            .pairs
            .iter()
            .zip(&m.costs)
            .map(|(&(i, j), &cost)| Pair {
                source: i,
                source_id: a.shapes[i].id.clone(),
                target: j,
                target_id: b.shapes[j].id.clone(),
                cost,
            })
            .collect(),
        vanishing: m.vanishing.clone(),
        appearing: m.appearing.clone(),
    }
}

/// `matching (auto): 'body' → 'body', …; 'horn' vanishes; 'hat' appears`.
pub(crate) fn summary(a: &Drawing, b: &Drawing, m: &Matching) -> String {
    let mut parts: Vec<String> = m
        .pairs
        .iter()
        .map(|&(i, j)| format!("{} → {}", shape_name(a, i), shape_name(b, j)))
        .collect();
    parts.extend(
        m.vanishing
            .iter()
            .map(|&i| format!("{} vanishes", shape_name(a, i))),
    );
    parts.extend(
        m.appearing
            .iter()
            .map(|&j| format!("{} appears", shape_name(b, j))),
    );
    let mode = match m.mode {
        MatchMode::Id => "id",
        MatchMode::Order => "order",
        _ => "auto",
    };
    format!("matching ({mode}): {}", parts.join(", "))
}

/// A drawing frame for the renderer: every shape's points in one list,
/// one styled layer per shape.
pub(crate) fn render_frame(f: &DrawingFrame) -> render::Frame {
    let rgba = |c: Color| render::Rgba {
        r: c.r,
        g: c.g,
        b: c.b,
        a: 255,
    };
    let mut frame = render::Frame::default();
    for s in &f.shapes {
        let first = frame.points.len() as u32;
        frame.points.extend(s.points.iter().map(|p| [p.x, p.y]));
        frame.layers.push(render::Layer {
            outline: (first..frame.points.len() as u32).collect(),
            fill: s.style.fill.map(rgba),
            stroke: s.style.stroke.map(rgba),
            stroke_width: s.style.stroke_width,
            opacity: s.style.opacity,
            evenodd: s.style.fill_rule == immerse::drawing::FillRule::Evenodd,
        });
    }
    frame
}
