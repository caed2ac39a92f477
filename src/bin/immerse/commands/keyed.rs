//! Lottie and animated SVG written from the certified keys of a morph or a
//! sequence (docs/design.md §12): exactly the keys, at the frames that pass
//! them, interpolated linearly; then read back with the library's reader
//! and certified as written (`immerse::certify`: Lottie against an `f32`
//! player's margin, SVG against an `f64` player's). Coordinates get the
//! fewest decimals of 2, 3, 4, 6 that certify, else full precision; a
//! document that does not certify even then is refused and nothing is
//! written.

use anyhow::Context;
use immerse::certify::{
    Answer, MotionOptions, Player, Verdict, certify_animation, certify_motion, certify_segment,
    read_animation,
};
use immerse::morph::{Keyframe, timed_keyframes};
use immerse_render as render;
use rayon::prelude::*;

/// The keys an output writes, in played order, `t` in frames.
pub(crate) struct Played {
    /// The keys ([`timed_keyframes`]).
    pub(crate) keys: Vec<Keyframe>,
    /// Frames of the played animation.
    pub(crate) frames: usize,
}

impl Played {
    /// The keys of an animation whose frame `i` shows `keys` at `times[i]`,
    /// played as `looping` says; with `every_frame` (eased timing) every
    /// frame is a key too.
    pub(crate) fn new(
        keys: &[Keyframe],
        times: &[f64],
        looping: render::Loop,
        every_frame: bool,
    ) -> Played {
        let order = looping.sequence(times.len());
        let played: Vec<f64> = order.iter().map(|&i| times[i]).collect();
        Played {
            keys: timed_keyframes(keys, &played, every_frame),
            frames: played.len(),
        }
    }
}

/// Which document.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Lottie, certified for an `f32` player.
    Lottie,
    /// Animated SVG, certified for an `f64` player.
    AnimatedSvg,
}

impl Kind {
    fn player(self) -> Player {
        match self {
            Kind::Lottie => Player::F32,
            Kind::AnimatedSvg => Player::F64,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Kind::Lottie => "Lottie file",
            Kind::AnimatedSvg => "animated SVG",
        }
    }
}

/// Decimals tried in turn; `None` is full precision.
const DIGITS: [Option<u32>; 5] = [Some(2), Some(3), Some(4), Some(6), None];

/// A written document and the decimals it needed.
pub(crate) struct Written {
    /// The document.
    pub(crate) text: String,
    /// Decimals of its coordinates (`None`: full precision).
    pub(crate) digits: Option<u32>,
    /// Keys written.
    pub(crate) keys: usize,
    /// Keys written of each shape (one entry for a curve).
    pub(crate) per_shape: Vec<usize>,
    /// Whether `immerse certify`, which reads no triangulation from the
    /// document and triangulates on its own, certifies it too.
    pub(crate) alone: bool,
}

/// One animated outline a document writes: its name in messages (empty
/// for the one curve of a morph) and its keys as played (`t` in frames).
pub(crate) struct Outline<'a> {
    pub(crate) name: &'a str,
    pub(crate) keys: &'a [Keyframe],
}

/// What a document is and how it draws and plays: its kind, the pixels
/// of its view, its style, its frame rate and how it loops.
#[derive(Clone, Copy)]
pub(crate) struct Document<'a> {
    pub(crate) kind: Kind,
    pub(crate) view: render::View,
    pub(crate) style: &'a render::Style,
    pub(crate) fps: f64,
    pub(crate) looping: render::Loop,
}

/// The document `doc` for `played`, with the fewest decimals that
/// certify as written.
///
/// # Errors
///
/// A render error, or none of the precisions certified (the message names
/// the segment and why).
pub(crate) fn write(doc: Document<'_>, played: &Played) -> anyhow::Result<Written> {
    let shapes: Vec<render::Frame> = played
        .keys
        .iter()
        .map(|k| render::Frame::from_triangles(super::plain_points(&k.points), Vec::new()))
        .collect();
    let times: Vec<f64> = played.keys.iter().map(|k| k.t).collect();
    let outline = [Outline {
        name: "",
        keys: &played.keys,
    }];
    write_certified(doc, &outline, |digits| render::Keys {
        shapes: &shapes,
        times: &times,
        frames: played.frames,
        view: doc.view,
        digits,
    })
}

/// Writes a Lottie file from keys `K`.
type LottieWriter<K> = fn(&K, &render::Style, f64) -> Result<String, render::RenderError>;

/// Writes an animated SVG from keys `K`.
type SvgWriter<K> =
    fn(&K, &render::Style, f64, render::Loop) -> Result<String, render::RenderError>;

/// The keys a document is written from, a curve's or a drawing's, with
/// their writers.
pub(crate) trait DocumentKeys: Sized {
    /// The Lottie writer.
    const LOTTIE: LottieWriter<Self>;
    /// The animated SVG writer.
    const ANIMATED_SVG: SvgWriter<Self>;
}

impl DocumentKeys for render::Keys<'_> {
    const LOTTIE: LottieWriter<Self> = render::lottie_keys;
    const ANIMATED_SVG: SvgWriter<Self> = render::animated_svg_keys;
}

impl DocumentKeys for render::DrawingKeys<'_> {
    const LOTTIE: LottieWriter<Self> = render::lottie_drawing;
    const ANIMATED_SVG: SvgWriter<Self> = render::animated_svg_drawing;
}

/// The document `doc` of the keys `keys` gives (at the decimals asked)
/// with the fewest decimals that certify as written: read back with the library's reader, its animated outlines
/// (in the order of `outlines`, which is the document's) certified
/// segment by segment with the keys' triangulations.
///
/// # Errors
///
/// A render error, or none of the precisions certified (the message names
/// the shape, the segment and why).
pub(crate) fn write_certified<K: DocumentKeys>(
    doc: Document<'_>,
    outlines: &[Outline<'_>],
    keys: impl Fn(Option<u32>) -> K,
) -> anyhow::Result<Written> {
    let Document {
        kind,
        style,
        fps,
        looping,
        ..
    } = doc;
    let render = |digits| match kind {
        Kind::Lottie => K::LOTTIE(&keys(digits), style, fps),
        Kind::AnimatedSvg => K::ANIMATED_SVG(&keys(digits), style, fps, looping),
    };
    let mut why = String::new();
    // The fewest decimals that certify with the keys' triangulations,
    // where no precision certifies as `immerse certify` reads the file.
    let mut with_keys: Option<Written> = None;
    for digits in DIGITS {
        let text = render(digits)?;
        match certify_written(kind, &text, outlines) {
            Ok(()) => {
                let per_shape: Vec<usize> = outlines.iter().map(|o| o.keys.len()).collect();
                let alone = certifies_alone(kind, &text);
                let written = Written {
                    text,
                    digits,
                    keys: per_shape.iter().sum(),
                    per_shape,
                    alone,
                };
                if alone {
                    return Ok(written);
                }
                with_keys.get_or_insert(written);
            }
            Err(e) => why = e,
        }
    }
    if let Some(written) = with_keys {
        return Ok(written);
    }
    anyhow::bail!(
        "the {} is not certified as written, even in full precision, for {} player: {why}; nothing was written (the shapes there are thinner than that player's rounding; an animated SVG, -o NAME.svg, is certified for f64 players)",
        kind.name(),
        match kind.player() {
            Player::F32 => "an f32",
            _ => "an f64",
        }
    )
}

/// Whether `immerse certify` certifies `text` as it reads it: with no
/// triangulation (the document carries none), triangulating where a piece
/// starts. Coordinates rounded to few decimals can make three vertices
/// exactly collinear inside a segment, where the triangulation it finds
/// must flip and cannot; more decimals avoid that.
fn certifies_alone(kind: Kind, text: &str) -> bool {
    read_animation(text.as_bytes(), kind.name()).is_ok_and(|anim| {
        certify_animation(&anim, kind.player(), MotionOptions::default()).answer
            == Answer::Certified
    })
}

/// Reads `text` back and certifies every segment of its animated outlines
/// with the keys' triangulations (re-triangulating where one fails).
fn certify_written(kind: Kind, text: &str, outlines: &[Outline<'_>]) -> Result<(), String> {
    let anim = read_animation(text.as_bytes(), kind.name()).map_err(|e| e.to_string())?;
    // Outlines of one key are written static: nothing moves to certify.
    let moving: Vec<&Outline<'_>> = outlines.iter().filter(|o| o.keys.len() > 1).collect();
    if anim.paths.len() != moving.len()
        || anim
            .paths
            .iter()
            .zip(&moving)
            .any(|(p, o)| p.keys.len() != o.keys.len())
    {
        return Err(format!(
            "the animated outline{} {} not read back as written ({} read, {} written)",
            if moving.len() == 1 { "" } else { "s" },
            if moving.len() == 1 { "was" } else { "were" },
            anim.paths.len(),
            moving.len()
        ));
    }
    let player = kind.player();
    let segments: Vec<(usize, usize)> = moving
        .iter()
        .enumerate()
        .flat_map(|(o, m)| (0..m.keys.len() - 1).map(move |i| (o, i)))
        .collect();
    let failures: Vec<String> = segments
        .into_par_iter()
        .filter_map(|(o, i)| {
            let path = &anim.paths[o];
            let keys = moving[o].keys;
            let points = |i: usize| {
                let mut p = path.keys[i].points.clone();
                if path.reversed {
                    p.reverse();
                }
                p
            };
            let (a, b) = (points(i), points(i + 1));
            let tris = &keys[i].triangles;
            let direct = certify_segment(&a, &b, tris, player)
                .ok()
                .filter(|r| r.is_certified());
            if direct.is_some() {
                return None;
            }
            let next = &keys[i + 1].triangles;
            let again = certify_motion(
                &a,
                &b,
                &[tris.as_slice(), next.as_slice()],
                player,
                MotionOptions::default(),
            );
            let shape = if moving[o].name.is_empty() {
                String::new()
            } else {
                format!("{}: ", moving[o].name)
            };
            match again.verdict {
                Verdict::Certified => None,
                Verdict::Invalid { at } => Some(format!(
                    "{shape}segment {i} (frames {} to {}) is not an immersed disk at s = {at}",
                    keys[i].t,
                    keys[i + 1].t
                )),
                Verdict::Undecided { reached, reason } => Some(format!(
                    "{shape}segment {i} (frames {} to {}) is certified only up to s = {reached} ({reason})",
                    keys[i].t,
                    keys[i + 1].t
                )),
            }
        })
        .collect();
    match failures.into_iter().next() {
        None => Ok(()),
        Some(f) => Err(f),
    }
}

/// Writes `written` to `out` through the render crate's one output
/// mechanism (never half-written).
pub(crate) fn save(written: &Written, out: &std::path::Path, force: bool) -> anyhow::Result<()> {
    render::write_atomic(out, written.text.as_bytes(), force)
        .with_context(|| format!("cannot write {}", out.display()))
}

/// What a note says about a written document.
pub(crate) fn describe(kind: Kind, written: &Written, bytes: usize) -> String {
    let keys = if written.per_shape.len() > 1 {
        let each: Vec<String> = written.per_shape.iter().map(usize::to_string).collect();
        format!(
            "{} keys ({} shapes: {})",
            written.keys,
            written.per_shape.len(),
            each.join(", ")
        )
    } else {
        format!("{} keys", written.keys)
    };
    format!(
        "{}: {keys}, coordinates {}, certified as written for an {} player ({bytes} bytes){}",
        kind.name(),
        match written.digits {
            Some(d) => format!("to {d} decimals"),
            None => "in full precision".to_string(),
        },
        kind.player(),
        if written.alone {
            ""
        } else {
            "; with the keys' triangulations: `immerse certify`, which finds its own, leaves a segment undecided"
        }
    )
}
