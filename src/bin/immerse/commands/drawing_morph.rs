//! `immerse morph` on drawings: every shape morphs, matched shapes in
//! parallel, unmatched ones growing or shrinking (docs/design.md §2b).

use super::ImageOutput;
use super::keyed::{self, Kind, Outline, Written};
use super::write::Writing;
use crate::Outcome;
use crate::args::{FormatArg, MorphArgs};
use crate::output;
use anyhow::Context;
use immerse::drawing::{
    Color, Drawing, DrawingFrame, DrawingTween, MatchMode, Matching, ShapeKeys, Style, match_shapes,
};
use immerse::morph::{CurveMorphOptions, Keyframe, timed_keyframes};
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

/// `immerse morph --json` on drawings: the matching, every shape's
/// certified keys (`shapes`: `id`, `role`, `key_count`, `keyframes`, in
/// painting order) and the frames.
#[derive(Serialize)]
pub(crate) struct DrawingMorphJson<'a> {
    pub(crate) matching: MatchingReport,
    pub(crate) notices: Vec<String>,
    pub(crate) shapes: &'a [ShapeKeys],
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
    if !args.run.quiet {
        for n in &notices {
            output::note(n);
        }
    }
    let matching = match_shapes(&a, &b, args.match_mode);
    let tween = DrawingTween::new(&a, &b, &matching, options)?;
    let keys = tween.shape_keys()?;
    let times = render::frame_times(args.frames as usize, &easing);
    let frames = times
        .iter()
        .map(|&t| tween.frame(t))
        .collect::<Result<Vec<_>, _>>()?;
    let elapsed = start.elapsed();
    if let Some(json) = &args.out.json {
        let report = DrawingMorphJson {
            matching: report(&a, &b, &matching),
            notices,
            shapes: &keys,
            frames: &frames,
        };
        super::write_json(json, &report, false, args.run.force)?;
    }
    if let (Some(out), Some(images)) = (&args.out.output, images) {
        let rendered: Vec<render::Frame> = frames.iter().map(render_frame).collect();
        let samples: Vec<(usize, f64)> = times.iter().map(|&t| (0, t)).collect();
        let writing = super::write::writing(args);
        let play = DrawingPlay::new(
            &[keys.as_slice()],
            &samples,
            writing.looping,
            easing != render::Easing::Linear,
        );
        write_images(&rendered, &play, out, images, &writing)?;
    }
    if !args.run.quiet {
        output::note(&summary(&a, &b, &matching));
        output::note(&format!(
            "{} shapes, {} frames computed and verified (every shape of every frame an immersed disk) in {:.0} ms; keys per shape: {} ({})",
            tween.shape_count(),
            frames.len(),
            elapsed.as_secs_f64() * 1e3,
            keys_per_shape(&keys),
            if tween.is_certified() {
                "every segment between them certified"
            } else {
                "some segments not certified: frames there checked one by one"
            }
        ));
    }
    Ok(Outcome::Success)
}

/// `'body' 3, 'shell' 5, shape 3 2`: every shape's key count.
pub(crate) fn keys_per_shape(keys: &[ShapeKeys]) -> String {
    keys.iter()
        .enumerate()
        .map(|(k, s)| {
            if s.id.is_empty() {
                format!("shape {} {}", k + 1, s.key_count)
            } else {
                format!("'{}' {}", s.id, s.key_count)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// One shape of a keyed drawing document, as played: its keys (`t` in
/// frames, from 0 to the last frame) and its paint at every frame.
struct ShapeTrack {
    name: String,
    keys: Vec<Keyframe>,
    paints: Vec<render::Paint>,
    paint_times: Vec<f64>,
    evenodd: bool,
}

/// A stretch of the played frames that one segment's shapes show.
struct SceneTracks {
    start: f64,
    tracks: Vec<ShapeTrack>,
}

/// The certified keys of a drawing animation as its frames play them:
/// one scene per run of played frames in one segment (a morph has one
/// segment; a sequence of drawings one per pair of keys), each shape's
/// keys placed at the frames that pass them ([`timed_keyframes`]) and
/// held before and after its scene.
pub(crate) struct DrawingPlay {
    scenes: Vec<SceneTracks>,
    frames: usize,
}

impl DrawingPlay {
    /// `segments[s]` are the shapes' keys of segment `s`; frame `i`
    /// shows segment `samples[i].0` at its `t` of `samples[i].1`, played
    /// as `looping` says; with `every_frame` (eased timing) every frame
    /// is a key too.
    pub(crate) fn new(
        segments: &[&[ShapeKeys]],
        samples: &[(usize, f64)],
        looping: render::Loop,
        every_frame: bool,
    ) -> DrawingPlay {
        let played: Vec<(usize, f64)> = looping
            .sequence(samples.len())
            .into_iter()
            .map(|i| samples[i])
            .collect();
        let frames = played.len();
        // A frame at a key between two segments shows both: the end of
        // the one and the start of the other.
        let in_segment = |(s, t): (usize, f64), g: usize| -> Option<f64> {
            if s == g {
                Some(t)
            } else if g + 1 == s && t == 0.0 {
                Some(1.0)
            } else if s + 1 == g && t == 1.0 && g < segments.len() {
                Some(0.0)
            } else {
                None
            }
        };
        let mut runs: Vec<(usize, Vec<(usize, f64)>)> = Vec::new();
        for (x, &sample) in played.iter().enumerate() {
            if let Some((g, run)) = runs.last_mut()
                && let Some(t) = in_segment(sample, *g)
            {
                run.push((x, t));
                continue;
            }
            let g = sample.0;
            let mut run = Vec::new();
            if x > 0
                && let Some(t) = in_segment(played[x - 1], g)
            {
                run.push((x - 1, t));
            }
            run.push((x, sample.1));
            if runs.last().is_some_and(|r| r.1[0].0 == run[0].0) {
                runs.pop();
            }
            runs.push((g, run));
        }
        let last = frames.saturating_sub(1) as f64;
        let scenes = runs
            .into_iter()
            .map(|(g, run)| {
                let x0 = run[0].0 as f64;
                let ts: Vec<f64> = run.iter().map(|r| r.1).collect();
                let tracks = segments[g]
                    .iter()
                    .map(|shape| {
                        let mut keys = timed_keyframes(&shape.keyframes, &ts, every_frame);
                        for k in &mut keys {
                            k.t += x0;
                        }
                        hold_to_ends(&mut keys, last);
                        let mut paint_times: Vec<f64> = run.iter().map(|r| r.0 as f64).collect();
                        let mut paints: Vec<render::Paint> =
                            ts.iter().map(|&t| paint(&shape.style_at(t))).collect();
                        if paint_times[0] > 0.0 {
                            paint_times.insert(0, 0.0);
                            paints.insert(0, paints[0]);
                        }
                        if paint_times[paint_times.len() - 1] < last {
                            paint_times.push(last);
                            paints.push(paints[paints.len() - 1]);
                        }
                        ShapeTrack {
                            name: if segments.len() > 1 {
                                format!("segment {} → {}, {}", g + 1, g + 2, shape.label)
                            } else {
                                shape.label.clone()
                            },
                            keys,
                            paints,
                            paint_times,
                            evenodd: shape.from.fill_rule == immerse::drawing::FillRule::Evenodd,
                        }
                    })
                    .collect();
                SceneTracks { start: x0, tracks }
            })
            .collect();
        DrawingPlay { scenes, frames }
    }
}

/// Copies of the first and last key at frame 0 and at `last`, so the keys
/// span the whole animation (the shape holds outside its scene, where it
/// is not shown).
fn hold_to_ends(keys: &mut Vec<Keyframe>, last: f64) {
    if let Some(first) = keys.first()
        && first.t > 0.0
    {
        let hold = Keyframe {
            t: 0.0,
            ..first.clone()
        };
        keys.insert(0, hold);
    }
    if let Some(end) = keys.last()
        && end.t < last
    {
        let hold = Keyframe {
            t: last,
            ..end.clone()
        };
        keys.push(hold);
    }
}

/// A shape's paint for the renderer.
fn paint(s: &Style) -> render::Paint {
    let rgba = |c: Color| render::Rgba {
        r: c.r,
        g: c.g,
        b: c.b,
        a: 255,
    };
    render::Paint {
        fill: s.fill.map(rgba),
        stroke: s.stroke.map(rgba),
        stroke_width: s.stroke_width,
        opacity: s.opacity,
    }
}

/// The Lottie or animated SVG of a drawing animation from its shapes'
/// certified keys, certified as written ([`keyed::write_certified`]).
///
/// # Errors
///
/// As [`keyed::write_certified`].
pub(crate) fn write_keyed(doc: keyed::Document<'_>, play: &DrawingPlay) -> anyhow::Result<Written> {
    let shapes: Vec<Vec<Vec<render::Frame>>> = per_track(play, |t| {
        t.keys
            .iter()
            .map(|k| render::Frame::from_triangles(super::plain_points(&k.points), Vec::new()))
            .collect()
    });
    let times: Vec<Vec<Vec<f64>>> = per_track(play, |t| t.keys.iter().map(|k| k.t).collect());
    let tracks: Vec<Vec<render::Track<'_>>> = play
        .scenes
        .iter()
        .enumerate()
        .map(|(s, scene)| {
            scene
                .tracks
                .iter()
                .enumerate()
                .map(|(k, t)| render::Track {
                    shapes: &shapes[s][k],
                    times: &times[s][k],
                    paints: &t.paints,
                    paint_times: &t.paint_times,
                    evenodd: t.evenodd,
                })
                .collect()
        })
        .collect();
    let scenes: Vec<render::Scene<'_>> = play
        .scenes
        .iter()
        .zip(&tracks)
        .map(|(scene, tracks)| render::Scene {
            start: scene.start,
            tracks,
        })
        .collect();
    // The animated outlines in the document's order: scene by scene;
    // Lottie lists a scene's shapes top first, SVG bottom first.
    let mut outlines = Vec::new();
    for scene in &play.scenes {
        let mut tracks: Vec<&ShapeTrack> = scene.tracks.iter().collect();
        if doc.kind == Kind::Lottie {
            tracks.reverse();
        }
        outlines.extend(tracks.into_iter().map(|t| Outline {
            name: &t.name,
            keys: &t.keys,
        }));
    }
    let mut written = keyed::write_certified(doc, &outlines, |digits| render::DrawingKeys {
        scenes: &scenes,
        frames: play.frames,
        view: doc.view,
        digits,
    })?;
    // Keys per shape in painting order.
    written.per_shape = play
        .scenes
        .iter()
        .flat_map(|s| s.tracks.iter().map(|t| t.keys.len()))
        .collect();
    Ok(written)
}

/// `f` of every track of `play`, scene by scene.
fn per_track<T>(play: &DrawingPlay, f: impl Fn(&ShapeTrack) -> T) -> Vec<Vec<T>> {
    play.scenes
        .iter()
        .map(|scene| scene.tracks.iter().map(&f).collect())
        .collect()
}

/// Writes a drawing animation's outputs: Lottie and animated SVG from
/// the certified keys ([`write_keyed`]), every other format from the
/// rendered frames.
pub(crate) fn write_images(
    frames: &[render::Frame],
    play: &DrawingPlay,
    out: &std::path::Path,
    images: ImageOutput,
    writing: &Writing,
) -> anyhow::Result<()> {
    let kind = match images.format {
        FormatArg::Lottie => Kind::Lottie,
        FormatArg::AnimatedSvg => Kind::AnimatedSvg,
        _ => return super::write::write_frames(frames, None, out, images, writing),
    };
    super::write::write_document(kind, frames, out, writing, |doc| write_keyed(doc, play))
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
