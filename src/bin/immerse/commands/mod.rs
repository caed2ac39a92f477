//! One module per subcommand: each turns its arguments into library
//! options, runs, and reports. Shared glue lives here.

mod check;
mod demo;
mod mesh_morph;
mod morph;
mod serve;
mod triangulate;

use crate::Outcome;
use crate::args::{Cli, Command, QualityArg};
use immerse::Quality;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Runs the parsed command line.
pub(crate) fn run(cli: Cli) -> anyhow::Result<Outcome> {
    match cli.command {
        Command::Check(args) => check::run(&args),
        Command::Triangulate(args) => triangulate::run(&args),
        Command::Morph(args) => morph::run(&args),
        Command::Demo(args) => demo::run(&args),
        Command::MeshMorph(args) => mesh_morph::run(&args),
        Command::Serve(args) => serve::run(&args),
    }
}

impl From<QualityArg> for Quality {
    fn from(q: QualityArg) -> Quality {
        match q {
            QualityArg::Any => Quality::Any,
            QualityArg::Delaunay => Quality::Delaunay,
            QualityArg::Maxmin => Quality::MaxMin,
        }
    }
}

/// A progress bar on stderr, hidden when stderr is not a terminal or when
/// `quiet` is set.
pub(crate) fn progress_bar(len: u64, message: &str, quiet: bool) -> ProgressBar {
    let bar = ProgressBar::new(len);
    if quiet || !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    bar.set_style(
        ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} ({eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(message.to_string());
    bar
}

/// A spinner on stderr for work of unknown length, ticking on its own;
/// hidden like [`progress_bar`].
pub(crate) fn spinner(message: &str, quiet: bool) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    if quiet || !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    } else {
        bar.enable_steady_tick(std::time::Duration::from_millis(100));
    }
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.set_message(message.to_string());
    bar
}

/// Refuses, before any work, an output file that exists unless `force`
/// ("-" is stdout and never refused).
pub(crate) fn refuse_existing(path: Option<&std::path::Path>, force: bool) -> anyhow::Result<()> {
    if let Some(p) = path
        && p.as_os_str() != "-"
        && !force
        && p.exists()
    {
        anyhow::bail!("{} exists; pass --force to replace it", p.display());
    }
    Ok(())
}

/// Writes `text` to `path` atomically, or to stdout when `path` is "-".
pub(crate) fn write_text(path: &std::path::Path, text: &str, force: bool) -> anyhow::Result<()> {
    if path.as_os_str() == "-" {
        crate::output::print(text)
    } else {
        immerse_render::write_atomic(path, text.as_bytes(), force)?;
        Ok(())
    }
}

/// The render crate's frames for a morph's frames (outline = all points).
pub(crate) fn render_frames(frames: &[immerse::frames::Frame]) -> Vec<immerse_render::Frame> {
    frames
        .iter()
        .map(|f| {
            immerse_render::Frame::from_triangles(plain_points(&f.points), f.triangles.clone())
        })
        .collect()
}

/// The image format: the one asked for, else from `out`'s extension
/// (.gif, .svg animated, .png contact sheet), else PNG frames in a folder.
pub(crate) fn image_format(
    asked: Option<crate::args::FormatArg>,
    out: &std::path::Path,
) -> crate::args::FormatArg {
    use crate::args::FormatArg;
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let lottie = out
        .file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.to_ascii_lowercase().ends_with(".lottie.json"));
    if asked.is_none() && lottie {
        return FormatArg::Lottie;
    }
    asked.unwrap_or(match ext.as_deref() {
        Some("gif") => FormatArg::Gif,
        Some("svg") => FormatArg::AnimatedSvg,
        Some("png") => FormatArg::Sheet,
        _ => FormatArg::Png,
    })
}

/// Converts library points to the render crate's plain points.
pub(crate) fn plain_points(points: &[immerse::Point]) -> Vec<[f64; 2]> {
    points.iter().map(|p| [p.x, p.y]).collect()
}
