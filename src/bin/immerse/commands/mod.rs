//! One module per subcommand: each turns its arguments into library
//! options, runs, and reports. Shared glue lives here.

mod animate;
mod certify;
mod check;
mod demo;
mod drawing_morph;
pub(crate) mod keyed;
mod mesh_morph;
pub(crate) mod morph;
mod serve;
mod triangulate;
mod write;

use crate::Outcome;
use crate::args::{Cli, Command, FormatArg, OutputArgs};
use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::Path;

/// Runs the parsed command line.
pub(crate) fn run(cli: Cli) -> anyhow::Result<Outcome> {
    match cli.command {
        Command::Check(args) => check::run(&args),
        Command::Triangulate(args) => triangulate::run(&args),
        Command::Morph(args) => morph::run(&args),
        Command::Demo(args) => demo::run(&args),
        Command::MeshMorph(args) => mesh_morph::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Serve(args) => serve::run(&args),
        Command::Certify(args) => certify::run(&args),
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

/// Progress of one long computation that reports the fraction done: a
/// [`progress_bar`] that stays hidden for its first second, so quick runs
/// print nothing, and always when `quiet` or stderr is not a terminal.
pub(crate) struct LateProgress {
    bar: ProgressBar,
    start: std::time::Instant,
    hidden: bool,
}

impl LateProgress {
    /// Delay before the bar appears.
    const DELAY: std::time::Duration = std::time::Duration::from_secs(1);

    pub(crate) fn new(message: &str, quiet: bool) -> Self {
        Self {
            bar: progress_bar(1000, message, true),
            start: std::time::Instant::now(),
            hidden: quiet || !std::io::stderr().is_terminal(),
        }
    }

    /// Report the fraction done, in [0, 1].
    pub(crate) fn update(&self, fraction: f64) {
        if !self.hidden && self.bar.is_hidden() && self.start.elapsed() >= Self::DELAY {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        self.bar
            .set_position((fraction.clamp(0.0, 1.0) * 1000.0) as u64);
    }

    /// Remove the bar.
    pub(crate) fn finish(self) {
        self.bar.finish_and_clear();
    }
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

/// Checks, before any work, that an output file (`--json`, `-o`) can be
/// written: "-" and /dev/stdout are stdout and special files are written
/// through; an existing file needs `force`, and its folder must exist and
/// be writable.
pub(crate) fn check_output_file(path: &Path, force: bool) -> anyhow::Result<()> {
    immerse_render::check_output_file(path, force)?;
    Ok(())
}

/// Refuses two outputs (`what`) that would both go to stdout.
pub(crate) fn one_stdout(outputs: &[(&str, bool)]) -> anyhow::Result<()> {
    let on_stdout: Vec<&str> = outputs
        .iter()
        .filter(|(_, s)| *s)
        .map(|(w, _)| *w)
        .collect();
    match on_stdout[..] {
        [a, b] => anyhow::bail!(
            "{a} and {b} would both print to standard output; send one of them to a file"
        ),
        [ref first @ .., last] if on_stdout.len() > 2 => anyhow::bail!(
            "{} and {last} would all print to standard output; send all but one to a file",
            first.join(", ")
        ),
        _ => {}
    }
    Ok(())
}

/// Serializes `items` as a JSON array whose elements are encoded on every
/// core, a few per core at a time (so that no more than those are held as
/// text at once), then written as the text they were encoded to: the same
/// bytes as serializing the slice itself with the compact formatter, which
/// is what `write_json` uses for every document holding keyframes (a
/// pretty document would keep each element on one line). For
/// `#[serde(serialize_with)]` on a field of keyframes: at 5,000 vertices a
/// morph's 374 keyframes are 107 MB of JSON.
pub(crate) fn on_every_core<T, S>(items: &&[T], s: S) -> Result<S::Ok, S::Error>
where
    T: serde::Serialize + Sync,
    S: serde::Serializer,
{
    use rayon::prelude::*;
    use serde::ser::{Error, SerializeSeq};
    let mut seq = s.serialize_seq(Some(items.len()))?;
    for chunk in items.chunks(encoded_at_once()) {
        let encoded: Vec<Result<Box<serde_json::value::RawValue>, serde_json::Error>> = chunk
            .par_iter()
            .map(serde_json::value::to_raw_value)
            .collect();
        for element in encoded {
            seq.serialize_element(&element.map_err(S::Error::custom)?)?;
        }
    }
    seq.end()
}

/// How many elements [`on_every_core`] holds as text at once: four per
/// core.
fn encoded_at_once() -> usize {
    4 * rayon::current_num_threads().max(1)
}

/// Writes `value` as JSON (pretty when `pretty`) and a newline to `path`
/// ("-" and /dev/stdout: stdout), through the render crate's one output
/// mechanism: never half-written, never overwriting without `force`.
pub(crate) fn write_json<T: serde::Serialize>(
    path: &Path,
    value: &T,
    pretty: bool,
    force: bool,
) -> anyhow::Result<()> {
    let mut out = immerse_render::OutputFile::create(path, force)?;
    let written = {
        let mut w = std::io::BufWriter::with_capacity(1 << 16, &mut out);
        let encoded = if pretty {
            serde_json::to_writer_pretty(&mut w, value)
        } else {
            serde_json::to_writer(&mut w, value)
        };
        encoded
            .map_err(std::io::Error::from)
            .and_then(|()| w.write_all(b"\n"))
            .and_then(|()| w.flush())
    };
    written.with_context(|| format!("cannot write {}", path.display()))?;
    out.finish()?;
    Ok(())
}

/// Where `-o` puts images, and in which format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ImageOutput {
    /// The format.
    pub(crate) format: FormatArg,
    /// Columns of a contact sheet (0: nearly square).
    pub(crate) columns: usize,
}

impl FormatArg {
    /// The file extension of a single-file format.
    fn file_extension(self) -> Option<&'static str> {
        match self {
            FormatArg::Gif => Some("gif"),
            FormatArg::AnimatedSvg => Some("svg"),
            FormatArg::Sheet => Some("png"),
            FormatArg::Lottie => Some("lottie.json"),
            FormatArg::Png | FormatArg::Svg => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            FormatArg::Png => "png",
            FormatArg::Gif => "gif",
            FormatArg::Svg => "svg",
            FormatArg::AnimatedSvg => "animated-svg",
            FormatArg::Sheet => "sheet",
            FormatArg::Lottie => "lottie",
        }
    }
}

/// The image format for `-o out` (one rule for every command): a folder of
/// frames only when the path has no extension or ends in `/` (PNG frames
/// unless `--format svg`); a .gif, .svg (animated) or .png (contact sheet)
/// file; stdout ("-", /dev/stdout) for a single-file `--format`; anything
/// else is refused.
pub(crate) fn image_format(asked: Option<FormatArg>, out: &Path) -> anyhow::Result<FormatArg> {
    let shown = out.display();
    let text = out.to_string_lossy();
    let file_formats = "name a .gif, .svg (animated), .png (contact sheet) or .lottie.json file, or a folder (no extension, or ending in /) for PNG frames";
    if immerse_render::is_stdout(out) {
        return match asked {
            Some(f) if f.file_extension().is_some() => Ok(f),
            Some(f) => anyhow::bail!(
                "-o {shown}: --format {} writes a folder of frames, not standard output; name a folder",
                f.name()
            ),
            None => anyhow::bail!(
                "-o {shown}: standard output takes one file; add --format gif, animated-svg, sheet or lottie"
            ),
        };
    }
    let folder = text.ends_with('/') || text.ends_with(std::path::MAIN_SEPARATOR);
    let lottie = out.file_name().is_some_and(|n| {
        n.to_string_lossy()
            .to_ascii_lowercase()
            .ends_with(".lottie.json")
    });
    let ext = if folder {
        None
    } else if lottie {
        Some("lottie.json".to_string())
    } else {
        out.extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
    };
    match (ext.as_deref(), asked) {
        (None, None) => Ok(FormatArg::Png),
        (None, Some(f @ (FormatArg::Png | FormatArg::Svg))) => Ok(f),
        (None, Some(f)) if folder => anyhow::bail!(
            "-o {shown} names a folder, but --format {} writes one file; name a .{} file",
            f.name(),
            f.file_extension().unwrap_or("gif")
        ),
        // No extension and a single-file format asked for: that file.
        (None, Some(f)) => Ok(f),
        (Some(e), None) => match e {
            "gif" => Ok(FormatArg::Gif),
            "svg" => Ok(FormatArg::AnimatedSvg),
            "png" => Ok(FormatArg::Sheet),
            "lottie.json" => Ok(FormatArg::Lottie),
            _ => anyhow::bail!("-o {shown}: unknown image type '.{e}'; {file_formats}"),
        },
        (Some(e), Some(f)) => match f.file_extension() {
            Some(want) if want == e => Ok(f),
            // A Lottie animation is JSON: --format lottie takes any .json.
            Some(_) if f == FormatArg::Lottie && e == "json" => Ok(f),
            Some(want) => anyhow::bail!(
                "-o {shown}: --format {} writes a .{want} file, not .{e}; name the file .{want}",
                f.name()
            ),
            None => anyhow::bail!(
                "-o {shown}: --format {} writes a folder of frames; name a folder without an extension (or ending in /)",
                f.name()
            ),
        },
    }
}

/// Checks, before any work, everything about an image output that can be
/// known in advance: the format rule ([`image_format`]), that the file or
/// folder can be written (`force`), the GIF frame rate, and the size of a
/// contact sheet of `frames` frames.
impl OutputArgs {
    /// The images `-o` asks for, checked before any work ([`check_images`]);
    /// `None` without `-o`.
    pub(crate) fn check_images(
        &self,
        force: bool,
        frames: usize,
        style: &immerse_render::Style,
    ) -> anyhow::Result<Option<ImageOutput>> {
        self.output
            .as_deref()
            .map(|out| {
                check_images(
                    self.format,
                    out,
                    force,
                    frames,
                    style,
                    self.image.fps,
                    self.image.columns,
                )
            })
            .transpose()
    }

    /// Whether `--json` and `-o` print to standard output, for
    /// [`one_stdout`].
    pub(crate) fn on_stdout(&self) -> [(&'static str, bool); 2] {
        let stdout =
            |p: &Option<std::path::PathBuf>| p.as_deref().is_some_and(immerse_render::is_stdout);
        [("--json", stdout(&self.json)), ("-o", stdout(&self.output))]
    }
}

pub(crate) fn check_images(
    asked: Option<FormatArg>,
    out: &Path,
    force: bool,
    frames: usize,
    style: &immerse_render::Style,
    fps: f64,
    columns: Option<u32>,
) -> anyhow::Result<ImageOutput> {
    let format = image_format(asked, out)?;
    let columns = columns.map_or(0, |c| c as usize);
    if columns != 0 && format != FormatArg::Sheet {
        anyhow::bail!("--columns lays out a contact sheet; add --format sheet or name a .png file");
    }
    match format {
        FormatArg::Png | FormatArg::Svg => immerse_render::check_output_dir(out, force)?,
        FormatArg::Gif => {
            immerse_render::check_gif_fps(fps).with_context(|| format!("--fps {fps}"))?;
            check_output_file(out, force)?;
        }
        FormatArg::AnimatedSvg | FormatArg::Lottie => check_output_file(out, force)?,
        FormatArg::Sheet => {
            immerse_render::contact_sheet_size(frames, style, columns)?;
            check_output_file(out, force)?;
        }
    }
    Ok(ImageOutput { format, columns })
}

/// The message for a frame rate outside the one range of every `--fps`
/// and of the playground ([`immerse_render::fps_in_range`]); `what` names
/// it (`--fps`).
pub(crate) fn fps_error(what: &str, fps: f64) -> Option<String> {
    // A tiny or huge rate in scientific notation, not hundreds of digits.
    let shown = if fps != 0.0 && !(1e-4..1e16).contains(&fps.abs()) {
        format!("{fps:e}")
    } else {
        format!("{fps}")
    };
    (!immerse_render::fps_in_range(fps)).then(|| {
        format!(
            "{what} {shown} is not a rate from {} to {} frames per second",
            immerse_render::MIN_FPS,
            immerse_render::MAX_FPS
        )
    })
}

/// Checks a frame rate given as `what` (see [`fps_error`]).
pub(crate) fn check_fps(what: &str, fps: f64) -> anyhow::Result<()> {
    match fps_error(what, fps) {
        Some(message) => Err(anyhow::anyhow!(message)),
        None => Ok(()),
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

/// True when `path` is read as SVG (by its extension).
pub(crate) fn is_svg(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"))
}

/// Converts library points to the render crate's plain points.
pub(crate) fn plain_points(points: &[immerse::Point]) -> Vec<[f64; 2]> {
    points.iter().map(|p| [p.x, p.y]).collect()
}

#[cfg(test)]
mod tests {
    use immerse::morph::Keyframe;
    use immerse::{Point, Tween};

    /// A document whose keyframes are encoded on every core.
    #[derive(serde::Serialize)]
    struct OnEveryCore<'a> {
        key_count: usize,
        #[serde(serialize_with = "super::on_every_core")]
        keyframes: &'a [Keyframe],
    }

    /// The same document serialized directly.
    #[derive(serde::Serialize)]
    struct Direct<'a> {
        key_count: usize,
        keyframes: &'a [Keyframe],
    }

    /// The keyframes encoded on every core are the same bytes as the
    /// slice serialized directly, for key counts below, at and past a
    /// chunk (and none at all), on a morph's own keys (coordinates with
    /// every digit) and with the floats JSON spells differently.
    #[test]
    fn keyframes_encoded_on_every_core_are_the_same_bytes() {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let wide = [(0.0, 0.0), (3.0, 0.1), (2.9, 1.7), (-0.2, 1.2)];
        let pts =
            |v: &[(f64, f64)]| -> Vec<Point> { v.iter().map(|&(x, y)| Point::new(x, y)).collect() };
        let tween = Tween::new(
            &pts(&square),
            &pts(&wide),
            &immerse::CurveMorphOptions::DEFAULT,
        )
        .expect("a square morphs into a quadrilateral");
        let mut keys = tween.keyframes();
        assert!(keys.len() >= 2);
        let odd = Keyframe {
            t: 0.1 + 0.2,
            points: pts(&[(-0.0, 1e-300), (f64::MAX, 5e-324), (1.0 / 3.0, -2.5e17)]),
            triangles: vec![[0, 1, 2]],
        };
        keys.push(odd);
        let chunk = super::encoded_at_once();
        let many: Vec<Keyframe> = keys.iter().cycle().take(3 * chunk + 1).cloned().collect();
        for count in [0, 1, keys.len(), chunk, chunk + 1, many.len()] {
            let keyframes = &many[..count];
            let ours = serde_json::to_vec(&OnEveryCore {
                key_count: count,
                keyframes,
            })
            .expect("encodes");
            let direct = serde_json::to_vec(&Direct {
                key_count: count,
                keyframes,
            })
            .expect("encodes");
            assert_eq!(
                String::from_utf8(ours).expect("UTF-8"),
                String::from_utf8(direct).expect("UTF-8"),
                "{count} keyframes"
            );
        }
    }
}
