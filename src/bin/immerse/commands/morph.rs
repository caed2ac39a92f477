//! `immerse morph`: frames from one curve to another.

use super::keyed::Played;
use crate::Outcome;
use crate::args::MorphArgs;
use crate::output;
use anyhow::Context;
use immerse::frames::{Morph, metrics};
use immerse::morph::{
    Correspondence, Counts, CurveMorphError, CurveMorphOptions, Intermediate, Keyframe,
    MorphOptions, ThirdVertexPath, Tween,
};
use immerse::{Curve, Quality};
use immerse_render as render;
use std::path::Path;

/// Most vertex positions (frames × points) one morph keeps in memory.
const MAX_FRAME_POINTS: usize = 50_000_000;

pub(crate) fn run(args: &MorphArgs) -> anyhow::Result<Outcome> {
    let easing: render::Easing = args
        .easing
        .parse()
        .with_context(|| format!("--easing '{}'", args.easing))?;
    super::check_fps("--fps", args.out.image.fps)?;
    let options = options(args)?;
    // Every output is checked before any work: nothing is computed for
    // an output that would then be refused.
    let images = args.out.check_images(
        args.run.force,
        args.frames as usize,
        &super::write::style(args),
    )?;
    if let Some(json) = &args.out.json {
        super::check_output_file(json, args.run.force)?;
    }
    let [json, images_out] = args.out.on_stdout();
    super::one_stdout(&[json, images_out, ("--metrics", args.metrics)])?;
    let mut clock = Timings::new(args.timings);
    let several = |r: &Result<Curve, immerse::curve::CurveError>| {
        matches!(r, Err(immerse::curve::CurveError::SeveralParts { .. }))
    };
    let (src, dst) = (
        Curve::from_path(&args.source),
        Curve::from_path(&args.target),
    );
    if several(&src) || several(&dst) {
        // Drawings: every shape morphs (docs/design.md §2b).
        return super::drawing_morph::run(args, images, &options);
    }
    let (src, dst) = (src?, dst?);
    if !args.run.quiet {
        for (c, path) in [(&src, &args.source), (&dst, &args.target)] {
            // SVG shapes (rect, circle, ellipse) are drawn clockwise on
            // screen, which is clockwise with y up too: the format's
            // convention, not worth a notice.
            if c.reversed && !super::is_svg(path) {
                output::note(&format!(
                    "{} is drawn clockwise; reversed it to counter-clockwise (frames follow the reversed order)",
                    path.display()
                ));
            }
        }
    }
    let n = src.len().max(dst.len());
    if (args.frames as usize).saturating_mul(n) > MAX_FRAME_POINTS {
        anyhow::bail!(
            "{} frames of {n} points is more than {MAX_FRAME_POINTS} points in all; ask for fewer --frames",
            args.frames
        );
    }
    let times = render::frame_times(args.frames as usize, &easing);
    let busy = super::spinner(
        &format!("triangulating, matching and morphing {n} vertices"),
        args.run.quiet || n < 300,
    );
    clock.lap("read");
    let result = Tween::new(&src.points, &dst.points, &options).and_then(|tween| {
        let morph = tween.morph(&times)?;
        let mut report = tween.report().clone();
        report.fallbacks.clone_from(&morph.fallbacks);
        Ok((report, morph, tween))
    });
    clock.lap("morph");
    busy.finish_and_clear();
    let (report, morph, tween) = match result {
        Ok(done) => done,
        Err(CurveMorphError::NotSelfOverlapping { side, reason }) if !reason.is_answer() => {
            let file = match side {
                immerse::morph::Side::Source => &args.source,
                immerse::morph::Side::Target => &args.target,
            };
            anyhow::bail!("{}: {reason}", file.display());
        }
        Err(err @ CurveMorphError::NotSelfOverlapping { .. }) => {
            let file = match err {
                CurveMorphError::NotSelfOverlapping {
                    side: immerse::morph::Side::Source,
                    ..
                } => &args.source,
                _ => &args.target,
            };
            output::note(&format!("{}: {err}", file.display()));
            return Ok(Outcome::Negative);
        }
        Err(err) => return Err(err.into()),
    };
    if !args.run.quiet {
        for f in &morph.fallbacks {
            output::note(&format!("{f} (every frame is an immersion)"));
        }
    }
    let keyframes = tween.keyframes();
    if let Some(json) = &args.out.json {
        super::write_json(
            json,
            &WithKeys::new(&morph, &keyframes),
            false,
            args.run.force,
        )?;
    }
    clock.lap("json");
    if let (Some(out), Some(images)) = (&args.out.output, images) {
        let played = Played::new(
            &keyframes,
            &times,
            super::write::looping(args),
            easing != render::Easing::Linear,
        );
        write_images(args, out, images, &morph, &played)?;
    }
    clock.lap("images");
    clock.report();
    if args.metrics {
        let m = metrics(&morph.frames);
        let opt = |v: Option<f64>| {
            v.map_or("n/a (triangulation changes)".to_string(), |v| {
                format!("{v:.6}")
            })
        };
        output::print(&format!(
            "vertices             {} (shift {}, {} flips on the {} side; {}{})\npath                 {}{}\nframes               {} ({} valid)\narea rank (AR)       {}\narea variance (Var)  {}\nminimum angle        {:.4}° (inputs {:.4}°)\nballooning           {:.4}\nsmallest area share  {}\ndetour               {:.2} (1 = every vertex on a straight line)\nunwind               {:.2} (below 1: overlaps undone and redone)",
            report.n,
            report.shift,
            report.flips,
            report.used,
            match args.intermediate {
                Intermediate::Disk => format!("u* {:.3}, v* {:.3}", report.u_star, report.v_star),
                Intermediate::Target => {
                    let side = |x: f64| {
                        if x.is_nan() {
                            "not finished".to_string()
                        } else {
                            x.to_string()
                        }
                    };
                    format!(
                        "targets: {} from the source side, {} from the target side",
                        side(report.u_star),
                        side(report.v_star)
                    )
                }
            },
            if report.used_disk {
                "; used the disk"
            } else {
                ""
            },
            morph.path_name(),
            if morph.fallback {
                format!(" (fallbacks: {})", morph.fallbacks.len())
            } else {
                String::new()
            },
            m.frames,
            m.valid_frames,
            m.area_rank
                .map_or("n/a (triangulation changes)".to_string(), |r| r.to_string()),
            opt(m.area_variance),
            m.min_angle_deg,
            m.endpoint_min_angle_deg,
            m.ballooning,
            opt(m.smallest_area_share),
            m.detour,
            m.unwind,
        ))?;
    }
    if !args.run.quiet {
        output::note(&format!(
            "{} keyframes ({}), {} frames computed and verified{}",
            keyframes.len(),
            if tween.is_certified() {
                "every segment between them certified"
            } else {
                "some segments not certified: frames there checked one by one"
            },
            morph.frames.len(),
            if args.out.json.is_none() && args.out.output.is_none() && !args.metrics {
                "; pass --json FILE or -o PATH to keep them"
            } else {
                ""
            }
        ));
    }
    Ok(Outcome::Success)
}

/// Per-stage wall times for `--timings`, printed to stderr.
struct Timings {
    on: bool,
    last: std::time::Instant,
    laps: Vec<(&'static str, std::time::Duration)>,
}

impl Timings {
    fn new(on: bool) -> Timings {
        Timings {
            on,
            last: std::time::Instant::now(),
            laps: Vec::new(),
        }
    }

    fn lap(&mut self, stage: &'static str) {
        let now = std::time::Instant::now();
        self.laps.push((stage, now - self.last));
        self.last = now;
    }

    fn report(&self) {
        if self.on {
            let parts: Vec<String> = self
                .laps
                .iter()
                .map(|(s, d)| format!("{s} {:.1} ms", d.as_secs_f64() * 1e3))
                .collect();
            output::note(&format!("timings: {}", parts.join(", ")));
        }
    }
}

/// A morph's JSON (`frames` and the rest, [`Morph`]) with its keys:
/// `"key_count"` and `"keyframes": [{"t", "points", "triangles"}, …]`.
#[derive(serde::Serialize)]
pub(crate) struct WithKeys<'a, T: serde::Serialize> {
    #[serde(flatten)]
    morph: &'a T,
    key_count: usize,
    #[serde(serialize_with = "super::on_every_core")]
    keyframes: &'a [Keyframe],
}

impl<'a, T: serde::Serialize> WithKeys<'a, T> {
    pub(crate) fn new(morph: &'a T, keyframes: &'a [Keyframe]) -> Self {
        WithKeys {
            morph,
            key_count: keyframes.len(),
            keyframes,
        }
    }
}

/// Renders the frames to `out` in the chosen format.
fn write_images(
    args: &MorphArgs,
    out: &Path,
    images: super::ImageOutput,
    morph: &Morph,
    played: &Played,
) -> anyhow::Result<()> {
    let frames = super::render_frames(&morph.frames);
    super::write::write_frames(
        &frames,
        Some(played),
        out,
        images,
        &super::write::writing(args),
    )
}

/// The flags that choose how a morph is planned, shared by `morph`,
/// `animate` and the server.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlanFlags {
    pub(crate) path: ThirdVertexPath,
    pub(crate) correspondence: Correspondence,
    pub(crate) quality: Quality,
    pub(crate) counts: Counts,
    pub(crate) intermediate: Intermediate,
    pub(crate) key_tolerance: f64,
}

impl PlanFlags {
    /// The library options these flags ask for, built in this one place.
    /// A path or correspondence that this build offers only with the
    /// `experimental` feature is refused with the library's own message
    /// (its parser decides), naming the values offered instead: the
    /// command line accepts the hidden values so that this message, not
    /// clap's, answers them.
    pub(crate) fn options(self) -> Result<CurveMorphOptions, String> {
        let path: ThirdVertexPath = self
            .path
            .as_str()
            .parse()
            .map_err(|e| format!("--path: {e}"))?;
        let correspondence: Correspondence = self
            .correspondence
            .as_str()
            .parse()
            .map_err(|e| format!("--correspondence: {e}"))?;
        Ok(CurveMorphOptions::DEFAULT
            .with_quality(self.quality)
            .with_counts(self.counts)
            .with_correspondence(correspondence)
            .with_intermediate(self.intermediate)
            .with_morph(MorphOptions::DEFAULT.with_path(path))
            .with_key_tolerance(self.key_tolerance))
    }
}

/// The library options `immerse morph`'s arguments ask for.
pub(crate) fn options(args: &MorphArgs) -> anyhow::Result<CurveMorphOptions> {
    PlanFlags {
        path: args.motion.path,
        correspondence: args.correspondence,
        quality: args.quality,
        counts: args.counts,
        intermediate: args.intermediate,
        key_tolerance: args.motion.key_tolerance,
    }
    .options()
    .map_err(anyhow::Error::msg)
}
