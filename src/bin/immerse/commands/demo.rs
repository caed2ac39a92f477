//! `immerse demo`: morph two curves embedded in the binary and write PNG
//! frames and a GIF. Needs no input and no network.

use super::write::{Writing, write_frames};
use crate::Outcome;
use crate::args::{DemoArgs, FormatArg};
use crate::output;
use anyhow::Context;
use immerse::frames::metrics;
use immerse::morph::{CurveMorphOptions, Tween};
use immerse::{Curve, curve::Format};
use immerse_render as render;
use std::path::Path;

/// The source: a ribbon curling past itself (an SVG drawing).
const SOURCE: &str = include_str!("../../../../curves/ribbon-curl.svg");
/// The target: a tapering tail that loops over itself.
const TARGET: &str = include_str!("../../../../curves/tail-loop.svg");

/// A file the demo writes into its folder, so that a later run knows the
/// folder is its own.
const MARKER: &str = ".immerse-demo";

pub(crate) fn run(args: &DemoArgs) -> anyhow::Result<Outcome> {
    let dir = &args.output;
    check_folder(dir, args.force)?;
    // The folder is ours (or --force), so its own files may be replaced;
    // a folder made now is removed again if the run fails or is
    // interrupted.
    render::check_output_dir(dir, true)?;
    let made = if dir.exists() {
        None
    } else {
        Some(render::NewOutputDir::create(dir)?)
    };
    let src = Curve::from_bytes(SOURCE.as_bytes(), Format::Svg, "ribbon-curl.svg", "ribbon")?;
    let dst = Curve::from_bytes(TARGET.as_bytes(), Format::Svg, "tail-loop.svg", "tail")?;
    let times = render::frame_times(args.frames as usize, &render::Easing::EaseInOut);
    let tween = Tween::new(&src.points, &dst.points, &CurveMorphOptions::DEFAULT)
        .context("the embedded demo curves did not morph; this is a bug in immerse")?;
    let morph = tween
        .morph(&times)
        .context("the embedded demo curves did not morph; this is a bug in immerse")?;
    let report = tween.report();
    render::write_atomic(&dir.join(MARKER), b"written by immerse demo\n", true)?;
    let frames = super::render_frames(&morph.frames);
    let writing = Writing {
        style: render::Style::DEFAULT
            .with_size(args.size.0, args.size.1)
            .with_onion_skin(true),
        fps: 24.0,
        looping: render::Loop::PingPong,
        force: true,
        quiet: args.quiet,
    };
    // The folder is ours (checked above), so replacing our own files is
    // fine; frames of an earlier, longer run are removed.
    let image = |format| super::ImageOutput { format, columns: 0 };
    let gif = dir.join("demo.gif");
    for (out, format) in [
        (dir.as_path(), FormatArg::Png),
        (gif.as_path(), FormatArg::Gif),
    ] {
        write_frames(&frames, None, out, image(format), &writing)?;
    }
    if let Some(made) = made {
        made.keep();
    }
    let m = metrics(&morph.frames);
    output::print(&format!(
        "morphed a curled ribbon ({} points) into a looping tail ({} points): {} frames, all {} verified immersions, {} edge flips, minimum angle {:.2}°\nwrote {} (frame_0000.png … and demo.gif)",
        src.len(),
        dst.len(),
        morph.frames.len(),
        m.valid_frames,
        report.flips,
        m.min_angle_deg,
        dir.display()
    ))?;
    Ok(Outcome::Success)
}

/// Refuses a path that is not a folder, and a folder that holds anything
/// the demo did not write unless `force` is given.
fn check_folder(dir: &Path, force: bool) -> anyhow::Result<()> {
    if !dir.exists() {
        return Ok(());
    }
    if !dir.is_dir() {
        anyhow::bail!(
            "{} exists and is not a folder; choose another -o",
            dir.display()
        );
    }
    if force {
        return Ok(());
    }
    let ours = |name: &str| {
        name == MARKER
            || name == "demo.gif"
            || (name.starts_with("frame_") && name.ends_with(".png"))
    };
    let entries: Vec<String> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read {}", dir.display()))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    if entries.is_empty() {
        return Ok(());
    }
    if !entries.iter().any(|e| e == MARKER) || entries.iter().any(|e| !ours(e)) {
        anyhow::bail!(
            "{} holds files the demo did not write; choose another -o or pass --force",
            dir.display()
        );
    }
    Ok(())
}
