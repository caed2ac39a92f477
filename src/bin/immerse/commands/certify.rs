//! `immerse certify`: is an animation an immersed disk at every moment.

use crate::Outcome;
use crate::args::CertifyArgs;
use crate::output;
use anyhow::Context;
use immerse::certify::{Answer, SegmentOutcome};
use immerse::certify::{Format, MAX_ANIMATION_BYTES};
use immerse::certify::{MotionOptions, certify_animation, read_animation};
use std::io::Read;

/// Failing segments listed in the text report.
const LISTED: usize = 20;

#[derive(serde::Serialize)]
struct Report<'a> {
    file: String,
    #[serde(flatten)]
    report: &'a immerse::certify::AnimationReport,
}

pub(crate) fn run(args: &CertifyArgs) -> anyhow::Result<Outcome> {
    if let Some(json) = &args.json {
        super::check_output_file(json, args.force)?;
    }
    let shown = args.file.display().to_string();
    let bytes = read_bounded(&args.file).with_context(|| format!("cannot read {shown}"))?;
    let anim = read_animation(&bytes, &shown)?;
    let options = MotionOptions {
        max_pieces: args.max_pieces as usize,
    };
    let player = args.player;
    let report = certify_animation(&anim, player, options);
    let outcome = if report.answer == Answer::Certified {
        Outcome::Success
    } else {
        Outcome::Negative
    };
    if let Some(json) = &args.json {
        super::write_json(
            json,
            &Report {
                file: shown.clone(),
                report: &report,
            },
            true,
            args.force,
        )?;
        if immerse_render::is_stdout(json) {
            return Ok(outcome);
        }
    }
    let format = match report.format {
        Format::ImmerseKeyframes => "immerse keyframes",
        Format::ImmerseFrames => "immerse frames",
        Format::Lottie => "Lottie",
        Format::AnimatedSvg => "animated SVG",
    };
    let mut lines = vec![format!(
        "{shown}: {} (player {player})",
        match report.answer {
            Answer::Certified => "certified: an immersed disk at every moment",
            Answer::Invalid => "not certified: invalid",
            Answer::Undecided => "not certified: undecided",
        }
    )];
    let keys: usize = report.paths.iter().map(|p| p.keys).sum();
    lines.push(format!(
        "  {} segment(s) between {keys} keys of {} animated outline(s) ({format}): {} certified ({} by the keys' own triangulations), {} invalid, {} undecided",
        report.segments,
        report.paths.len(),
        report.certified,
        report.certified_as_given,
        report.invalid,
        report.undecided
    ));
    let mut listed = 0;
    let mut unlisted = 0;
    for path in &report.paths {
        let prefix = if report.paths.len() > 1 {
            format!("{}: ", path.name)
        } else {
            String::new()
        };
        if path.reversed {
            lines.push(format!(
                "  {prefix}clockwise as given; read in reverse order"
            ));
        }
        for seg in path
            .segments
            .iter()
            .filter(|s| s.answer != Answer::Certified)
        {
            if listed == LISTED {
                unlisted += 1;
                continue;
            }
            listed += 1;
            lines.push(format!("  {prefix}{}", describe(seg)));
        }
        if let Some(why) = &path.last_key {
            lines.push(format!("  {prefix}the last key is {why}"));
        }
    }
    if unlisted > 0 {
        lines.push(format!("  … and {unlisted} more (--json lists them all)"));
    }
    for s in &report.skipped {
        lines.push(format!("  not certified: {s}"));
    }
    output::print(&lines.join("\n"))?;
    Ok(outcome)
}

/// One line about a segment that is not certified.
fn describe(seg: &SegmentOutcome) -> String {
    let at_t = |s: f64| seg.t0 + s * (seg.t1 - seg.t0);
    let head = format!(
        "segment {} (keys {} → {}, t {} → {})",
        seg.index,
        seg.index,
        seg.index + 1,
        seg.t0,
        seg.t1
    );
    let first = seg
        .failure
        .as_ref()
        .map(|f| format!("; first certificate failure: {}", f.message))
        .unwrap_or_default();
    match (seg.answer, &seg.invalid_at) {
        (Answer::Invalid, Some(s)) if s.lo == 0.0 && seg.play != "hold" => format!(
            "{head}: invalid: key {} itself is not self-overlapping",
            seg.index
        ),
        (Answer::Invalid, Some(s)) => format!(
            "{head}: invalid: not self-overlapping at {s} (t = {}){}{first}",
            at_t(s.lo),
            seg.reason
                .as_deref()
                .map(|r| format!(" ({r})"))
                .unwrap_or_default()
        ),
        _ => format!(
            "{head}: undecided: {}{}{first}",
            seg.reason.as_deref().unwrap_or("not certified"),
            seg.certified_up_to
                .map(|s| format!("; certified up to s = {s}"))
                .unwrap_or_default()
        ),
    }
}

/// The file's bytes, refusing folders and files over the limit before
/// reading them (and while reading, should the file grow).
fn read_bounded(path: &std::path::Path) -> anyhow::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if meta.is_dir() {
        anyhow::bail!("it is a folder; give an animation file");
    }
    let limit = MAX_ANIMATION_BYTES as u64;
    if meta.len() > limit {
        anyhow::bail!(
            "too large ({} bytes; the limit is {limit} bytes)",
            meta.len()
        );
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        anyhow::bail!("too large (over {limit} bytes)");
    }
    Ok(bytes)
}
