//! `immerse animate` on drawings: every key a drawing (a file of several
//! styled shapes, or one group of an SVG), consecutive keys matched
//! shape by shape and morphed as `immerse morph` morphs two drawings
//! (docs/design.md §2b).

use super::timeline::{KeySpec, Timeline};
use crate::Outcome;
use crate::args::{AnimateArgs, FormatArg};
use crate::commands::ImageOutput;
use crate::commands::drawing_morph::{self, DrawingPlay, render_frame};
use crate::commands::write::Writing;
use crate::output;
use anyhow::Context;
use immerse::curve::SvgShapes;
use immerse::drawing::{
    Drawing, DrawingError, DrawingFrame, DrawingTween, Matching, ShapeKeys, match_shapes,
};
use immerse::sequence::{Schedule, Timing, schedule_lengths};
use immerse_render as render;
use std::path::Path;

/// A key that is a drawing: its name in messages, the drawing, its spec.
pub(super) struct DrawingKey {
    pub(super) name: String,
    pub(super) drawing: Drawing,
    pub(super) spec: KeySpec,
}

/// True for a drawing that is more than one plain curve: several shapes,
/// or a JSON drawing (whose one shape has a style of its own).
fn is_drawing(d: &Drawing) -> bool {
    d.len() > 1 || (!d.single_curve && d.notices.is_empty())
}

/// The keys as drawings when at least one of them is a drawing (else
/// `None`: the keys are curves). One SVG of keys gives a drawing per
/// top-level group when a group holds several shapes. A hole in a key is
/// an error naming it; other read errors leave the keys to the curve
/// reader, which reports them as it does for curves.
pub(super) fn read_keys(
    tl: &Timeline,
    mode: SvgShapes,
    prefix: &str,
) -> anyhow::Result<Option<Vec<DrawingKey>>> {
    let hole = |e: DrawingError| -> anyhow::Result<()> {
        match e {
            e @ DrawingError::Hole { .. } => Err(anyhow::anyhow!("{prefix}{e}")),
            _ => Ok(()),
        }
    };
    let keys: Vec<DrawingKey> = if let Some(file) = &tl.drawing {
        if mode == SvgShapes::Shapes {
            return Ok(None);
        }
        match Drawing::groups_from_path(file) {
            Ok(groups) if groups.len() >= 2 && groups.iter().any(|g| g.len() > 1) => groups
                .into_iter()
                .map(|d| DrawingKey {
                    name: format!("{} ({})", file.display(), d.name),
                    drawing: d,
                    spec: KeySpec::plain(file.clone(), None),
                })
                .collect(),
            Ok(_) => return Ok(None),
            Err(e) => {
                hole(e)?;
                return Ok(None);
            }
        }
    } else {
        let mut out = Vec::with_capacity(tl.keys.len());
        for spec in &tl.keys {
            if spec.shape.is_some() {
                return Ok(None);
            }
            match Drawing::read_path(&spec.curve) {
                Ok(d) => out.push(DrawingKey {
                    name: spec.curve_text.clone(),
                    drawing: d,
                    spec: spec.clone(),
                }),
                Err(e) => {
                    hole(e)?;
                    return Ok(None);
                }
            }
        }
        if !out.iter().any(|k| is_drawing(&k.drawing)) {
            return Ok(None);
        }
        out
    };
    for (j, k) in keys.iter().enumerate() {
        if let Some((name, _)) = k.spec.hints.first() {
            anyhow::bail!(
                "{prefix}key {} ({}): hint '{name}': hints pair points of curves; the keys are drawings, whose shapes are matched with --match",
                j + 1,
                k.name
            );
        }
        k.drawing
            .require_self_overlapping(&k.name)
            .map_err(|e| anyhow::anyhow!("{prefix}key {}: {e}", j + 1))?;
    }
    Ok(Some(keys))
}

/// One segment in the JSON: its matching and its shapes' keys.
#[derive(serde::Serialize)]
struct SegmentJson<'a> {
    from: &'a str,
    to: &'a str,
    matching: &'a Matching,
    shapes: &'a [ShapeKeys],
}

/// `animate --json` on drawings.
#[derive(serde::Serialize)]
struct DrawingSequenceJson<'a> {
    fps: f64,
    keys: Vec<super::KeyJson<'a>>,
    segments: Vec<SegmentJson<'a>>,
    key_count: usize,
    frames: &'a [DrawingFrame],
}

pub(super) fn run(
    args: &AnimateArgs,
    keys: &[DrawingKey],
    timing: &Timing,
    images: &[ImageOutput],
    prefix: &str,
    looping: render::Loop,
) -> anyhow::Result<Outcome> {
    let start = std::time::Instant::now();
    if !args.quiet {
        for k in keys {
            for n in &k.drawing.notices {
                output::note(&format!("{}: {n}", k.name));
            }
        }
    }
    let options = super::plan_options(args)?;
    let mut matchings = Vec::with_capacity(keys.len() - 1);
    let mut tweens = Vec::with_capacity(keys.len() - 1);
    for (s, w) in keys.windows(2).enumerate() {
        let m = match_shapes(&w[0].drawing, &w[1].drawing, args.match_mode);
        let tween = DrawingTween::new(&w[0].drawing, &w[1].drawing, &m, &options)
            .with_context(|| format!("{prefix}segment {} → {}", s + 1, s + 2))?;
        matchings.push(m);
        tweens.push(tween);
    }
    let shape_keys = tweens
        .iter()
        .map(DrawingTween::shape_keys)
        .collect::<Result<Vec<_>, _>>()?;
    let lengths: Vec<f64> = tweens.iter().map(DrawingTween::path_length).collect();
    let names: Vec<String> = keys.iter().map(|k| k.name.clone()).collect();
    let schedule =
        schedule_lengths(&lengths, timing, &names).map_err(|e| anyhow::anyhow!("{prefix}{e}"))?;
    let frames = schedule
        .samples
        .iter()
        .map(|s| {
            tweens[s.segment]
                .frame(s.t)
                .with_context(|| format!("segment {} → {}", s.segment + 1, s.segment + 2))
        })
        .collect::<anyhow::Result<Vec<DrawingFrame>>>()?;
    let elapsed = start.elapsed();
    let key_total: usize = shape_keys.iter().flatten().map(|k| k.key_count).sum();
    if let Some(json) = &args.json {
        let value = DrawingSequenceJson {
            fps: timing.fps,
            keys: super::key_json(
                &schedule,
                keys.iter()
                    .map(|k| (k.name.as_str(), Some(k.drawing.len()))),
            ),
            segments: (0..tweens.len())
                .map(|s| SegmentJson {
                    from: &keys[s].name,
                    to: &keys[s + 1].name,
                    matching: &matchings[s],
                    shapes: &shape_keys[s],
                })
                .collect(),
            key_count: key_total,
            frames: &frames,
        };
        crate::commands::write_json(json, &value, false, args.force)?;
    }
    let rendered: Vec<render::Frame> = frames.iter().map(render_frame).collect();
    let samples: Vec<(usize, f64)> = schedule.samples.iter().map(|s| (s.segment, s.t)).collect();
    let eased = timing.keys.iter().any(|k| !k.easing.is_linear());
    let segments: Vec<&[ShapeKeys]> = shape_keys.iter().map(Vec::as_slice).collect();
    let play = DrawingPlay::new(&segments, &samples, looping, eased);
    let writing = super::writing(args, schedule.fps, looping);
    for (out, image) in args.output.iter().zip(images) {
        write_output(args, out, *image, &rendered, &play, &schedule, &writing)?;
    }
    if !super::writes_stdout(args) {
        let mut lines = vec![format!(
            "{} keys (drawings of {} shapes), {} frames at {} fps ({:.2} s), every shape of every frame a verified immersed disk, in {:.0} ms; {key_total} keyframes ({})",
            keys.len(),
            keys.iter()
                .map(|k| k.drawing.len().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            frames.len(),
            schedule.fps,
            (frames.len().max(1) - 1) as f64 / schedule.fps,
            elapsed.as_secs_f64() * 1e3,
            if tweens.iter().all(DrawingTween::is_certified) {
                "every segment between them certified"
            } else {
                "some segments not certified: frames there checked one by one"
            }
        )];
        for s in 0..tweens.len() {
            lines.push(format!(
                "segment {} → {}: {}; keys per shape: {}",
                s + 1,
                s + 2,
                drawing_morph::summary(&keys[s].drawing, &keys[s + 1].drawing, &matchings[s]),
                drawing_morph::keys_per_shape(&shape_keys[s])
            ));
        }
        output::print(&lines.join("\n"))?;
    }
    Ok(Outcome::Success)
}

fn write_output(
    args: &AnimateArgs,
    out: &Path,
    image: ImageOutput,
    frames: &[render::Frame],
    play: &DrawingPlay,
    schedule: &Schedule,
    writing: &Writing,
) -> anyhow::Result<()> {
    if image.format == FormatArg::Sheet {
        let (picked, sheet) = super::sheet_rows(frames, schedule, args.sheet_inbetweens);
        return crate::commands::write::write_frames(&picked, None, out, sheet, writing);
    }
    drawing_morph::write_images(frames, play, out, image, writing)
}
