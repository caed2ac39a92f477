//! `immerse animate`: a keyframe sequence K1 → K2 → K3 … from curve files,
//! one SVG drawing, or a timeline file (docs/timeline.md).

mod drawings;
mod timeline;

use super::keyed::Played;
use super::write::{Writing, write_frames};
use crate::Outcome;
use crate::args::{AnimateArgs, FormatArg};
use crate::output;
use anyhow::Context;
use immerse::curve::SvgShapes;
use immerse::frames::Morph;
use immerse::morph::{CurveMorphOptions, Keyframe};
use immerse::sequence::{
    Ease, Hint, HintAt, Key, KeySpeed, KeyTiming, Schedule, Sequence, SequenceError,
    SequenceOptions, Timing, key_speeds,
};
use immerse::{Curve, Point};
use immerse_render as render;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use timeline::{HintSpec, KeySpec, Timeline};

/// Most vertex positions (frames × points) one sequence keeps in memory.
const MAX_FRAME_POINTS: usize = 50_000_000;

/// A key as read: its name in messages, the curve, and its spec.
struct ReadKey {
    name: String,
    curve: Curve,
    spec: KeySpec,
}

pub(crate) fn run(args: &AnimateArgs) -> anyhow::Result<Outcome> {
    let cli_easing = args
        .easing
        .as_deref()
        .map(|e| {
            e.parse::<render::Easing>()
                .with_context(|| format!("--easing '{e}'"))
        })
        .transpose()?;
    if let Some(h) = args.hold
        && !(h.is_finite() && h >= 0.0)
    {
        anyhow::bail!("--hold {h} is not a number of seconds of at least 0");
    }
    if let Some(fps) = args.fps {
        super::check_fps("--fps", fps)?;
    }
    let svg_mode = args.svg_keys;
    // Where the keys come from, and the prefix of messages about them.
    let (tl, prefix) = match &args.timeline {
        Some(path) => (timeline::read(path)?, format!("{}: ", path.display())),
        None => (positional(&args.keys)?, String::new()),
    };
    if let (None, Some(fps)) = (args.fps, tl.fps) {
        super::check_fps(&format!("{prefix}\"fps\""), fps)?;
    }
    let svg_mode = svg_mode.or(tl.svg_keys).unwrap_or_default();
    if let Some(json) = &args.json {
        super::check_output_file(json, args.force)?;
    }
    let drawing_keys = drawings::read_keys(&tl, svg_mode, &prefix)?;
    let key_count = drawing_keys.as_ref().map(Vec::len);
    let keys = match key_count {
        Some(_) => Vec::new(),
        None => read_keys(&tl, svg_mode, &prefix)?,
    };
    // Every image output is checked before any work (the keys are read
    // first: a contact sheet's size depends on how many there are).
    let fps = args.fps.or(tl.fps).unwrap_or(30.0);
    let style = image_style(args);
    let sheet_frames =
        (key_count.unwrap_or(keys.len()).saturating_sub(1)) * (args.sheet_inbetweens as usize + 2);
    let mut images = Vec::with_capacity(args.output.len());
    for out in &args.output {
        images.push(super::check_images(
            args.format,
            out,
            args.force,
            sheet_frames,
            &style,
            fps,
            None,
        )?);
    }
    let mut on_stdout = vec![(
        "--json",
        args.json.as_deref().is_some_and(render::is_stdout),
    )];
    on_stdout.extend(args.output.iter().map(|o| ("-o", render::is_stdout(o))));
    super::one_stdout(&on_stdout)?;
    if let Some(drawing_keys) = drawing_keys {
        let timing = timing_of(
            args,
            &drawing_keys.iter().map(|k| &k.spec).collect::<Vec<_>>(),
            fps,
            tl.frames,
            cli_easing,
        );
        let looping = looping_of(args, &tl);
        return drawings::run(args, &drawing_keys, &timing, &images, &prefix, looping);
    }
    if !args.quiet {
        for k in &keys {
            if k.curve.reversed {
                output::note(&format!(
                    "{} is drawn clockwise; reversed it to counter-clockwise (frames follow the reversed order)",
                    k.name
                ));
            }
        }
    }
    let hints = pair_hints(&keys).map_err(|e| anyhow::anyhow!("{prefix}{e}"))?;
    let lib_keys: Vec<Key> = keys
        .iter()
        .map(|k| Key::new(k.name.clone(), k.curve.points.clone()))
        .collect();
    let options = SequenceOptions::DEFAULT.with_morph(plan_options(args)?);
    let biggest = keys.iter().map(|k| k.curve.len()).max().unwrap_or(0);
    let busy = super::spinner(
        &format!(
            "planning {} segments of about {biggest} vertices",
            keys.len() - 1
        ),
        args.quiet || biggest < 300,
    );
    let planned = Sequence::new(&lib_keys, &hints, &options);
    busy.finish_and_clear();
    let seq = match planned {
        Ok(s) => s,
        Err(SequenceError::NotSelfOverlapping { key, name, reason }) if reason.is_answer() => {
            output::note(&format!(
                "{prefix}key {key} ({name}) is not self-overlapping: {reason}"
            ));
            return Ok(Outcome::Negative);
        }
        Err(e) => anyhow::bail!("{prefix}{e}"),
    };
    let specs: Vec<&KeySpec> = keys.iter().map(|k| &k.spec).collect();
    let timing = timing_of(args, &specs, fps, tl.frames, cli_easing);
    let schedule = seq
        .schedule(&timing)
        .map_err(|e| anyhow::anyhow!("{prefix}{e}"))?;
    let n = seq.vertex_count();
    if schedule.samples.len().saturating_mul(n) > MAX_FRAME_POINTS {
        anyhow::bail!(
            "{} frames of {n} points is more than {MAX_FRAME_POINTS} points in all; ask for fewer --frames",
            schedule.samples.len()
        );
    }
    let morph = seq.frames(&schedule)?;
    let speeds = key_speeds(&morph.frames, &schedule);
    if !args.quiet {
        for f in &morph.fallbacks {
            output::note(&format!("{f} (every frame is an immersion)"));
        }
    }
    let keyframes = seq.keyframes();
    let eased = timing.keys.iter().any(|k| !k.easing.is_linear());
    if let Some(json) = &args.json {
        let value = SequenceJson {
            morph: &morph,
            key_count: keyframes.len(),
            keyframes: &keyframes,
            fps,
            keys: key_json(&schedule, keys.iter().map(|k| (k.name.as_str(), None))),
            speeds: &speeds,
        };
        super::write_json(json, &value, false, args.force)?;
    }
    let looping = looping_of(args, &tl);
    let played = Played::new(&keyframes, &seq.frame_times(&schedule), looping, eased);
    let writing = writing(args, fps, looping);
    for (out, image) in args.output.iter().zip(&images) {
        write_output(args, out, *image, &morph, &played, &schedule, &writing)?;
    }
    if !writes_stdout(args) {
        output::print(&summary(
            &seq,
            &keys,
            &schedule,
            &speeds,
            &morph,
            keyframes.len(),
        ))?;
    }
    Ok(Outcome::Success)
}

/// How the animation plays: the command line's choice, else the
/// timeline's, else looping.
fn looping_of(args: &AnimateArgs, tl: &Timeline) -> render::Loop {
    args.play
        .looping()
        .or(tl.looping)
        .unwrap_or(render::Loop::Loop)
}

/// The timing of keys with these specs: the timeline's times, holds,
/// durations and easings, else the command line's.
fn timing_of(
    args: &AnimateArgs,
    specs: &[&KeySpec],
    fps: f64,
    frames: Option<usize>,
    cli_easing: Option<render::Easing>,
) -> Timing {
    let m = specs.len();
    Timing {
        fps,
        frames: args.frames.map(|f| f as usize).or(frames),
        keys: specs
            .iter()
            .enumerate()
            .map(|(j, k)| KeyTiming {
                time: k.time,
                hold: k.hold.unwrap_or(if j > 0 && j + 1 < m {
                    args.hold.unwrap_or(0.0)
                } else {
                    0.0
                }),
                duration: k.duration,
                easing: ease(k.easing.or(cli_easing)),
            })
            .collect(),
    }
}

fn ease(e: Option<render::Easing>) -> Ease {
    match e {
        None | Some(render::Easing::Linear) => Ease::LINEAR,
        Some(e) => Ease::new(move |x| e.apply(x)),
    }
}

/// The keys named on the command line: two or more files, or one SVG
/// drawing holding them all.
fn positional(files: &[PathBuf]) -> anyhow::Result<Timeline> {
    let is_svg = |p: &Path| {
        p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"))
    };
    let (keys, drawing) = match files {
        [one] if is_svg(one) => (Vec::new(), Some(one.clone())),
        [_] | [] => anyhow::bail!(
            "{} key given; a sequence needs at least 2 keys: name two or more curve files, one SVG drawing with a shape per key, or --timeline FILE",
            files.len()
        ),
        many => (
            many.iter()
                .map(|p| KeySpec::plain(p.clone(), None))
                .collect(),
            None,
        ),
    };
    Ok(Timeline {
        fps: None,
        frames: None,
        looping: None,
        svg_keys: None,
        keys,
        drawing,
    })
}

/// Reads every key's curve.
fn read_keys(tl: &Timeline, mode: SvgShapes, prefix: &str) -> anyhow::Result<Vec<ReadKey>> {
    let mut drawings: HashMap<PathBuf, Vec<Curve>> = HashMap::new();
    let what = |file: &Path, c: &Curve| {
        let stem = file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("drawing");
        let part = c
            .name
            .strip_prefix(stem)
            .map_or(c.name.as_str(), str::trim_start);
        format!("{} ({part})", file.display())
    };
    if let Some(file) = &tl.drawing {
        let curves = Curve::all_from_svg_path(file, mode).map_err(|e| {
            let e = anyhow::Error::new(e);
            if prefix.is_empty() {
                e
            } else {
                e.context(prefix.trim_end_matches(": ").to_string())
            }
        })?;
        if curves.len() < 2 {
            anyhow::bail!(
                "{prefix}{}: 1 closed shape found; a sequence needs at least 2 keys: draw each key as its own shape, group or layer",
                file.display()
            );
        }
        return Ok(curves
            .into_iter()
            .map(|c| ReadKey {
                name: what(file, &c),
                spec: KeySpec::plain(file.clone(), None),
                curve: c,
            })
            .collect());
    }
    let mut out = Vec::with_capacity(tl.keys.len());
    for (j, spec) in tl.keys.iter().enumerate() {
        let at = format!("{prefix}key {}", j + 1);
        let (name, curve) = match spec.shape {
            // Named on the command line, the file names itself.
            None if prefix.is_empty() => (spec.curve_text.clone(), Curve::from_path(&spec.curve)?),
            None => {
                let c = Curve::from_path(&spec.curve).with_context(|| at.clone())?;
                (spec.curve_text.clone(), c)
            }
            Some(k) => {
                if !drawings.contains_key(&spec.curve) {
                    let all =
                        Curve::all_from_svg_path(&spec.curve, mode).with_context(|| at.clone())?;
                    drawings.insert(spec.curve.clone(), all);
                }
                let all = &drawings[&spec.curve];
                let c = all.get(k - 1).cloned().ok_or_else(|| {
                    anyhow::anyhow!(
                        "{at}: shape {k} does not exist; {} has {} shape(s) as keys",
                        spec.curve.display(),
                        all.len()
                    )
                })?;
                (format!("{} (shape {k})", spec.curve_text), c)
            }
        };
        out.push(ReadKey {
            name,
            curve,
            spec: spec.clone(),
        });
    }
    Ok(out)
}

/// Pairs the keys' named hints into hints between consecutive keys.
fn pair_hints(keys: &[ReadKey]) -> Result<Vec<Hint>, String> {
    let mut out = Vec::new();
    for (j, k) in keys.iter().enumerate() {
        for (name, spec) in &k.spec.hints {
            let on = |i: usize| -> Option<&HintSpec> {
                keys.get(i)?
                    .spec
                    .hints
                    .iter()
                    .find(|(n, _)| n == name)
                    .map(|(_, s)| s)
            };
            let before = j > 0 && on(j - 1).is_some();
            if let Some(next) = on(j + 1) {
                out.push(Hint {
                    name: name.clone(),
                    segment: j,
                    from: hint_at(k, j, name, *spec)?,
                    to: hint_at(&keys[j + 1], j + 1, name, *next)?,
                });
            } else if !before {
                return Err(format!(
                    "key {} ({}): hint '{name}' has no partner; name it on {} too (hints pair points of consecutive keys by name)",
                    j + 1,
                    k.name,
                    match (j > 0, j + 1 < keys.len()) {
                        (true, true) => format!("key {} or key {}", j, j + 2),
                        (true, false) => format!("key {j}"),
                        _ => format!("key {}", j + 2),
                    }
                ));
            }
        }
    }
    Ok(out)
}

/// A hint as the library takes it: file indices become cleaned vertices,
/// fractions follow the oriented curve.
fn hint_at(k: &ReadKey, j: usize, name: &str, spec: HintSpec) -> Result<HintAt, String> {
    match spec {
        HintSpec::Index(r) => {
            let count = k.curve.source_vertex.len();
            k.curve
                .source_vertex
                .get(r)
                .map(|&v| HintAt::Vertex(v))
                .ok_or_else(|| {
                    format!(
                        "key {} ({}): hint '{name}': point {r} does not exist; the file has {count} points (0 to {})",
                        j + 1,
                        k.name,
                        count - 1
                    )
                })
        }
        HintSpec::Position(x, y) => Ok(HintAt::Point(Point::new(x, y))),
        HintSpec::Fraction(f) => Ok(HintAt::Fraction(if k.curve.reversed {
            (1.0 - f).rem_euclid(1.0)
        } else {
            f
        })),
    }
}

/// A key in `animate --json`: its name, the frame it falls on, the
/// frames it holds and, for a drawing, its shapes.
#[derive(serde::Serialize)]
struct KeyJson<'a> {
    name: &'a str,
    frame: usize,
    hold: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    shapes: Option<usize>,
}

/// The [`KeyJson`] of each key, given by its name and shapes, in order.
fn key_json<'a>(
    schedule: &Schedule,
    keys: impl Iterator<Item = (&'a str, Option<usize>)>,
) -> Vec<KeyJson<'a>> {
    keys.enumerate()
        .map(|(j, (name, shapes))| KeyJson {
            name,
            frame: schedule.key_frames[j],
            hold: schedule.holds[j],
            shapes,
        })
        .collect()
}

/// Whether --json or an -o writes to stdout (which then holds nothing else).
fn writes_stdout(args: &AnimateArgs) -> bool {
    args.json.as_deref().is_some_and(render::is_stdout)
        || args.output.iter().any(|o| render::is_stdout(o))
}

/// `morph --json`'s format plus the keys and the speeds at them.
#[derive(serde::Serialize)]
struct SequenceJson<'a> {
    #[serde(flatten)]
    morph: &'a Morph,
    fps: f64,
    keys: Vec<KeyJson<'a>>,
    speeds: &'a [KeySpeed],
    key_count: usize,
    #[serde(serialize_with = "super::on_every_core")]
    keyframes: &'a [Keyframe],
}

/// The image style of `animate`'s options.
fn image_style(args: &AnimateArgs) -> render::Style {
    args.play.style(args.size)
}

/// How `animate` writes its frames at `fps`, playing as `looping` says.
fn writing(args: &AnimateArgs, fps: f64, looping: render::Loop) -> Writing {
    Writing {
        style: image_style(args),
        fps,
        looping,
        force: args.force,
        quiet: args.quiet,
    }
}

/// A contact sheet of `frames` with one row per segment: the key,
/// `in_betweens` frames evenly between its hold's end and the next key,
/// and that key; with the sheet's layout.
fn sheet_rows<T: Clone>(
    frames: &[T],
    schedule: &Schedule,
    in_betweens: u32,
) -> (Vec<T>, super::ImageOutput) {
    let k = in_betweens as usize;
    let mut picked = Vec::new();
    for s in 0..schedule.steps.len() {
        let start = schedule.key_frames[s] + schedule.holds[s];
        let end = schedule.key_frames[s + 1];
        for i in 0..=k + 1 {
            let f = start as f64 + (end - start) as f64 * i as f64 / (k + 1) as f64;
            picked.push(frames[f.round() as usize].clone());
        }
    }
    let sheet = super::ImageOutput {
        format: FormatArg::Sheet,
        columns: k + 2,
    };
    (picked, sheet)
}

fn write_output(
    args: &AnimateArgs,
    out: &Path,
    image: super::ImageOutput,
    morph: &Morph,
    played: &Played,
    schedule: &Schedule,
    writing: &Writing,
) -> anyhow::Result<()> {
    if image.format == FormatArg::Sheet {
        let (picked, sheet) = sheet_rows(&morph.frames, schedule, args.sheet_inbetweens);
        let frames = super::render_frames(&picked);
        return write_frames(&frames, None, out, sheet, writing);
    }
    let frames = super::render_frames(&morph.frames);
    write_frames(&frames, Some(played), out, image, writing)
}

fn summary(
    seq: &Sequence,
    keys: &[ReadKey],
    schedule: &Schedule,
    speeds: &[KeySpeed],
    morph: &Morph,
    keyframes: usize,
) -> String {
    let frames = morph.frames.len();
    let valid = morph.frames.iter().filter(|f| f.is_immersion()).count();
    let certified = (0..seq.key_count() - 1).all(|s| seq.tween(s).is_certified());
    let mut lines = vec![format!(
        "{} keys, {} vertices each, {} frames at {} fps ({:.2} s), {} of them verified immersions; {keyframes} keyframes ({})",
        keys.len(),
        seq.vertex_count(),
        frames,
        schedule.fps,
        (frames.max(1) - 1) as f64 / schedule.fps,
        valid,
        if certified {
            "every segment between them certified"
        } else {
            "some segments not certified: frames there checked one by one"
        }
    )];
    for s in speeds {
        let k = &keys[s.key - 1];
        lines.push(format!(
            "key {} ({}) at frame {}: speed {:.4} before, {:.4} after, ratio {:.3}{}",
            s.key,
            k.name,
            s.frame,
            s.before,
            s.after,
            s.ratio,
            s.not_continuous.as_ref().map_or(String::new(), |w| format!(
                " (not meant to be continuous: {w})"
            ))
        ));
    }
    let worst = speeds
        .iter()
        .filter(|s| s.not_continuous.is_none())
        .map(|s| s.ratio)
        .fold(f64::NAN, f64::max);
    if worst.is_finite() {
        lines.push(format!(
            "largest speed ratio at keys meant to be continuous: {worst:.3}"
        ));
    }
    lines.join("\n")
}

/// The library options `immerse animate`'s arguments ask for (the one
/// builder the morph command and the server use too).
pub(crate) fn plan_options(args: &AnimateArgs) -> anyhow::Result<CurveMorphOptions> {
    crate::commands::morph::PlanFlags {
        path: args.motion.path,
        correspondence: args.correspondence,
        quality: args.quality,
        counts: immerse::morph::Counts::Insert,
        intermediate: args.intermediate,
        key_tolerance: args.motion.key_tolerance,
    }
    .options()
    .map_err(anyhow::Error::msg)
}
