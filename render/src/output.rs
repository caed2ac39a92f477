//! The writers' options, PNG sequences, GIFs, contact sheets and frame
//! rates. Every file they write goes through the `io` module (atomic
//! writes, staged sequences, the registry of partial outputs).

use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::io::{
    OutputFile, Staging, check_output_dir, check_output_file, frame_file_name, os_error,
    write_atomic,
};
use crate::{Frame, RenderError, Style, View, encode_png, render};

/// Options shared by the file writers.
///
/// # Examples
///
/// ```
/// use immerse_render::Output;
///
/// let opts = Output::DEFAULT.with_force(true);
/// assert!(opts.force);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Output {
    /// Write into a non-empty folder and replace existing files of the same
    /// name. Default: `false`.
    pub force: bool,
    /// GIF colour quantisation speed, 1 (best) to 30 (fastest); clamped.
    /// Default: `10`.
    pub gif_speed: i32,
}

impl Output {
    /// The default options.
    pub const DEFAULT: Output = Output {
        force: false,
        gif_speed: 10,
    };

    /// Sets [`force`](Output::force).
    pub fn with_force(mut self, force: bool) -> Output {
        self.force = force;
        self
    }

    /// Sets [`gif_speed`](Output::gif_speed).
    pub fn with_gif_speed(mut self, speed: i32) -> Output {
        self.gif_speed = speed;
        self
    }
}

impl Default for Output {
    fn default() -> Output {
        Output::DEFAULT
    }
}

/// How an animation repeats. The CLI values are `once`, `loop` and
/// `ping-pong`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Loop {
    /// Play once and stop on the last frame.
    Once,
    /// Repeat forever.
    #[default]
    Loop,
    /// Play forwards, then backwards, forever. The backward run omits both
    /// end frames, so `N ≥ 2` frames become `2N - 2`.
    PingPong,
}

impl Loop {
    /// Every way to repeat, in the order the CLI lists them.
    pub const ALL: [Loop; 3] = [Loop::Loop, Loop::PingPong, Loop::Once];

    /// The frame indices played in one cycle for `n` frames.
    ///
    /// # Examples
    ///
    /// ```
    /// use immerse_render::Loop;
    ///
    /// assert_eq!(Loop::PingPong.sequence(4), vec![0, 1, 2, 3, 2, 1]);
    /// assert_eq!(Loop::Once.sequence(2), vec![0, 1]);
    /// ```
    pub fn sequence(self, n: usize) -> Vec<usize> {
        let mut seq: Vec<usize> = (0..n).collect();
        if self == Loop::PingPong && n > 2 {
            seq.extend((1..n - 1).rev());
        }
        seq
    }
}

/// The CLI value: `once`, `loop` or `ping-pong`.
impl fmt::Display for Loop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Loop::Once => "once",
            Loop::Loop => "loop",
            Loop::PingPong => "ping-pong",
        })
    }
}

/// Parses `once`, `loop` or `ping-pong` (also `pingpong`).
impl FromStr for Loop {
    type Err = RenderError;

    fn from_str(s: &str) -> Result<Loop, RenderError> {
        match s.trim().to_ascii_lowercase().as_str() {
            "once" => Ok(Loop::Once),
            "loop" => Ok(Loop::Loop),
            "ping-pong" | "pingpong" => Ok(Loop::PingPong),
            _ => Err(RenderError::BadLoop { input: s.into() }),
        }
    }
}

/// The frames drawn as onion skin behind every frame: the first and last.
pub(crate) fn onion<'a>(frames: &'a [Frame], style: &Style) -> Vec<&'a Frame> {
    match (style.onion_skin, frames.first(), frames.last()) {
        (true, Some(a), Some(b)) if frames.len() > 1 => vec![a, b],
        _ => Vec::new(),
    }
}

/// Writes a per-frame sequence: `encode(frame, view)` in parallel into
/// `dir/frame_NNNN.ext`, staged in a temporary folder and moved into
/// place once every frame is written.
pub(crate) fn write_sequence(
    frames: &[Frame],
    dir: &Path,
    style: &Style,
    opts: &Output,
    progress: &(dyn Fn(usize) + Sync),
    ext: &str,
    encode: impl Fn(&Frame, &View) -> Result<Vec<u8>, RenderError> + Sync,
) -> Result<Vec<PathBuf>, RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    style.check_size()?;
    check_output_dir(dir, opts.force)?;
    let staging = Staging::create(dir)?;
    let view = View::fit(frames, style);
    let done = AtomicUsize::new(0);
    let names: Vec<String> = (0..frames.len())
        .map(|i| frame_file_name(i, frames.len(), ext))
        .collect();
    frames
        .par_iter()
        .zip(&names)
        .enumerate()
        .try_for_each(|(i, (frame, name))| {
            let bytes = encode(frame, &view).map_err(|e| e.in_frame(i))?;
            std::fs::write(staging.path().join(name), &bytes)
                .map_err(|e| RenderError::io(dir.join(name), os_error(e)))?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok::<(), RenderError>(())
        })?;
    staging.commit(dir, &names, ext)?;
    Ok(names.iter().map(|n| dir.join(n)).collect())
}

/// Renders `frames` in parallel and writes them as `dir/frame_0000.png`, ...
/// (zero-padded to at least four digits), with one shared [`View`].
///
/// `dir` is checked with [`check_output_dir`] (with `opts.force`); the
/// frames are written into a temporary folder (beside a new `dir`, inside
/// an existing one) and moved in once all are written, so an interrupted
/// or failed run leaves the folder as it was. Into an existing folder the frames replace their namesakes, and
/// `frame_N.png` files of an earlier, longer run are removed (a shorter
/// sequence never leaves stale frames behind). When
/// [`Style::onion_skin`] is on, the first and last frames are drawn as
/// ghosts behind every frame. `progress` is called from worker threads with
/// the number of frames finished so far.
///
/// # Errors
///
/// [`RenderError::NoFrames`], a size error, an output-safety error, or a
/// [`RenderError::InFrame`] wrapping a frame's error. Returns the written
/// paths in frame order.
pub fn write_png_sequence(
    frames: &[Frame],
    dir: &Path,
    style: &Style,
    opts: &Output,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<PathBuf>, RenderError> {
    let ghosts = onion(frames, style);
    write_sequence(frames, dir, style, opts, progress, "png", |f, view| {
        encode_png(&render(f, view, style, &ghosts)?)
    })
}

/// How many frames are rendered and quantised at once by [`write_gif`];
/// bounds memory to a few dozen RGBA images.
const GIF_BATCH: usize = 16;

/// The highest frame rate a GIF plays: its frame delays are whole
/// hundredths of a second, and browsers slow down delays under 2.
pub const GIF_MAX_FPS: f64 = 50.0;

/// Checks that a GIF can play `fps` frames per second: a rate from
/// [`MIN_FPS`] to [`GIF_MAX_FPS`].
///
/// # Errors
///
/// [`RenderError::BadFps`] or [`RenderError::GifFpsTooHigh`].
pub fn check_gif_fps(fps: f64) -> Result<(), RenderError> {
    check_fps(fps)?;
    if fps > GIF_MAX_FPS {
        return Err(RenderError::GifFpsTooHigh { fps });
    }
    Ok(())
}

/// The delay of the `k`-th played GIF frame in hundredths of a second:
/// delays alternate (3, 3, 4, ... at 30 fps) so that frame `k` starts at
/// `k / fps` seconds, rounded to the hundredth.
fn gif_delay(k: usize, fps: f64) -> u16 {
    let at = |k: usize| (100.0 * k as f64 / fps).round();
    (at(k + 1) - at(k)).clamp(2.0, f64::from(u16::MAX)) as u16
}

/// Renders `frames` and writes them as one animated GIF at `path` (an
/// [`OutputFile`]: standard output for `-`).
///
/// The file is streamed: frames are rendered and quantised (per-frame
/// palettes, speed [`Output::gif_speed`]) and LZW-compressed in parallel
/// batches, then written in order to the temporary file, which is renamed
/// into place at the end. GIF frame delays are whole hundredths of a
/// second, so they alternate (at 30 fps: 3, 3, 4, ...) to keep the average
/// rate exact; rates above [`GIF_MAX_FPS`] are refused. [`Loop::Once`]
/// plays once, [`Loop::Loop`] repeats forever, [`Loop::PingPong`] appends
/// the frames reversed without repeating the ends and repeats forever.
/// `progress` gets the number of frames finished so far (of the played
/// sequence).
///
/// # Errors
///
/// [`RenderError::NoFrames`], [`RenderError::BadFps`],
/// [`RenderError::GifFpsTooHigh`], [`RenderError::ImageTooLarge`] beyond
/// 65535 pixels a side, an output-safety error for `path`, a frame's error,
/// or [`RenderError::Gif`].
pub fn write_gif(
    frames: &[Frame],
    path: &Path,
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<(), RenderError> {
    check_gif(frames, style, fps)?;
    let out = OutputFile::create(path, opts.force)?;
    let gif_error = |e: gif::EncodingError| match e {
        gif::EncodingError::Io(io) => RenderError::io(path, os_error(io)),
        other => RenderError::Gif(other),
    };
    let report = |done: usize| {
        progress(done);
        true
    };
    encode_gif_into(out, frames, style, fps, looping, opts, &report, &gif_error)?.finish()
}

/// The GIF that [`write_gif`] writes, in memory (for a server; `opts.force`
/// is not used). `keep_going` is asked before each frame is rendered, with
/// the number of frames finished so far: when it answers false the work
/// stops with [`RenderError::Cancelled`] (a server stops a GIF whose client
/// has left or whose time is up).
///
/// # Errors
///
/// As [`write_gif`], without the output-safety errors, and
/// [`RenderError::Cancelled`].
pub fn encode_gif(
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
    keep_going: &(dyn Fn(usize) -> bool + Sync),
) -> Result<Vec<u8>, RenderError> {
    check_gif(frames, style, fps)?;
    encode_gif_into(
        Vec::new(),
        frames,
        style,
        fps,
        looping,
        opts,
        keep_going,
        &RenderError::Gif,
    )
}

/// What can be known about a GIF before rendering a frame.
fn check_gif(frames: &[Frame], style: &Style, fps: f64) -> Result<(), RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    check_gif_fps(fps)?;
    style.check_size()
}

/// The one GIF encoder: renders and quantises the frames in parallel
/// batches and writes them to `out` in order (ping-pong plays the frames
/// back without repeating the ends), with delays that keep the average
/// rate exact; returns `out`. `keep_going` gets the number of frames
/// finished before each frame is rendered and after the last; false stops
/// the work ([`RenderError::Cancelled`]).
#[allow(
    clippy::too_many_arguments,
    reason = "the frames, their style and timing, and where they go"
)]
fn encode_gif_into<W: Write>(
    out: W,
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
    keep_going: &(dyn Fn(usize) -> bool + Sync),
    gif_error: &dyn Fn(gif::EncodingError) -> RenderError,
) -> Result<W, RenderError> {
    let too_large = || RenderError::ImageTooLarge {
        width: style.width,
        height: style.height,
        reason: "gif images are at most 65535 pixels a side",
    };
    let w = u16::try_from(style.width).map_err(|_| too_large())?;
    let h = u16::try_from(style.height).map_err(|_| too_large())?;
    let speed = opts.gif_speed.clamp(1, 30);
    let view = View::fit(frames, style);
    let ghosts = onion(frames, style);
    let mut encoder = gif::Encoder::new(out, w, h, &[]).map_err(gif_error)?;
    if looping != Loop::Once {
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(gif_error)?;
    }
    let mut encoded: Vec<gif::Frame<'static>> = Vec::new();
    let done = AtomicUsize::new(0);
    let mut played = 0;
    for (b, batch) in frames.chunks(GIF_BATCH).enumerate() {
        let mut quantised = batch
            .par_iter()
            .enumerate()
            .map(|(k, frame)| {
                if !keep_going(done.load(Ordering::Relaxed)) {
                    return Err(RenderError::Cancelled);
                }
                let i = b * GIF_BATCH + k;
                let pixmap = render(frame, &view, style, &ghosts).map_err(|e| e.in_frame(i))?;
                let mut rgba = pixmap.take_demultiplied();
                let mut gf = gif::Frame::from_rgba_speed(w, h, &mut rgba, speed);
                gf.make_lzw_pre_encoded();
                done.fetch_add(1, Ordering::Relaxed);
                Ok(gf)
            })
            .collect::<Result<Vec<_>, RenderError>>()?;
        for gf in &mut quantised {
            gf.delay = gif_delay(played, fps);
            played += 1;
            encoder.write_lzw_pre_encoded_frame(gf).map_err(gif_error)?;
        }
        if looping == Loop::PingPong {
            encoded.append(&mut quantised);
        }
    }
    if looping == Loop::PingPong && encoded.len() > 2 {
        let last = encoded.len() - 1;
        for gf in encoded[1..last].iter_mut().rev() {
            gf.delay = gif_delay(played, fps);
            played += 1;
            encoder.write_lzw_pre_encoded_frame(gf).map_err(gif_error)?;
            done.fetch_add(1, Ordering::Relaxed);
        }
    }
    if !keep_going(done.load(Ordering::Relaxed)) {
        return Err(RenderError::Cancelled);
    }
    encoder.into_inner().map_err(gif_error)
}

/// The slowest frame rate an animation may have, in frames per second:
/// every duration written (an animated SVG's `dur`, a Lottie's `fr`,
/// which it rounds to hundredths, a GIF's delays) stays finite and
/// nonzero.
pub const MIN_FPS: f64 = 0.1;

/// The fastest frame rate an animation may have, in frames per second.
pub const MAX_FPS: f64 = 1000.0;

/// True when `fps` is a frame rate from [`MIN_FPS`] to [`MAX_FPS`]: the
/// one range of every command's `--fps` and of the playground's `fps`.
pub fn fps_in_range(fps: f64) -> bool {
    (MIN_FPS..=MAX_FPS).contains(&fps)
}

/// Checks that `fps` is a frame rate from [`MIN_FPS`] to [`MAX_FPS`].
///
/// # Errors
///
/// [`RenderError::BadFps`].
pub fn check_fps(fps: f64) -> Result<(), RenderError> {
    if fps_in_range(fps) {
        Ok(())
    } else {
        Err(RenderError::BadFps { fps })
    }
}

/// The columns of a contact sheet of `frames` frames when `columns` are
/// asked for: `columns` (at most `frames`), or for 0 the nearly square grid
/// of ⌈√frames⌉ columns.
pub fn contact_sheet_columns(frames: usize, columns: usize) -> usize {
    let cols = if columns == 0 {
        (1..=frames.max(1)).find(|c| c * c >= frames).unwrap_or(1)
    } else {
        columns
    };
    cols.clamp(1, frames.max(1))
}

/// The size in pixels of a contact sheet of `frames` frames, `columns` per
/// row (0: a nearly square grid, see [`contact_sheet_columns`]); cheap, so
/// callers can check it before computing the frames.
///
/// # Errors
///
/// A size error for `style`, or [`RenderError::SheetTooLarge`] when the
/// sheet has more than [`Style::MAX_PIXELS`] pixels.
pub fn contact_sheet_size(
    frames: usize,
    style: &Style,
    columns: usize,
) -> Result<(u32, u32), RenderError> {
    style.check_size()?;
    let cols = contact_sheet_columns(frames, columns);
    let rows = frames.max(1).div_ceil(cols);
    let (w, h) = (u64::from(style.width), u64::from(style.height));
    let (sw, sh) = (w * cols as u64, h * rows as u64);
    let too_large = || RenderError::SheetTooLarge {
        frames,
        columns: cols,
        width: sw,
        height: sh,
        limit: Style::MAX_PIXELS,
    };
    if sw.saturating_mul(sh) > Style::MAX_PIXELS {
        return Err(too_large());
    }
    Ok((
        u32::try_from(sw).map_err(|_| too_large())?,
        u32::try_from(sh).map_err(|_| too_large())?,
    ))
}

/// Renders `frames` into one image, `columns` per row (0: a nearly square
/// grid, see [`contact_sheet_columns`]), each cell `style.width` ×
/// `style.height`, all with one shared [`View`]: a contact sheet for
/// comparing in-betweens at a glance.
///
/// # Errors
///
/// [`RenderError::NoFrames`], a size error ([`contact_sheet_size`]), or a
/// frame's error.
pub fn contact_sheet(
    frames: &[Frame],
    style: &Style,
    columns: usize,
) -> Result<tiny_skia::Pixmap, RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    let (sw, sh) = contact_sheet_size(frames.len(), style, columns)?;
    let cols = contact_sheet_columns(frames.len(), columns);
    let (w, h) = (style.width, style.height);
    let mut sheet = tiny_skia::Pixmap::new(sw, sh).ok_or(RenderError::SheetTooLarge {
        frames: frames.len(),
        columns: cols,
        width: u64::from(sw),
        height: u64::from(sh),
        limit: Style::MAX_PIXELS,
    })?;
    let view = View::fit(frames, style);
    let ghosts = onion(frames, style);
    let cells: Vec<tiny_skia::Pixmap> = frames
        .par_iter()
        .enumerate()
        .map(|(i, f)| render(f, &view, style, &ghosts).map_err(|e| e.in_frame(i)))
        .collect::<Result<_, _>>()?;
    for (i, cell) in cells.iter().enumerate() {
        let (x, y) = ((i % cols) as u32 * w, (i / cols) as u32 * h);
        sheet.draw_pixmap(
            x as i32,
            y as i32,
            cell.as_ref(),
            &tiny_skia::PixmapPaint::default(),
            tiny_skia::Transform::identity(),
            None,
        );
    }
    Ok(sheet)
}

/// Writes [`contact_sheet`] as a PNG with [`write_atomic`]; the file and
/// the sheet's size are checked before anything is rendered.
///
/// # Errors
///
/// As [`contact_sheet`] and [`write_atomic`].
pub fn write_contact_sheet(
    frames: &[Frame],
    path: &Path,
    style: &Style,
    columns: usize,
    opts: &Output,
) -> Result<(), RenderError> {
    check_output_file(path, opts.force)?;
    contact_sheet_size(frames.len(), style, columns)?;
    let sheet = contact_sheet(frames, style, columns)?;
    write_atomic(path, &encode_png(&sheet)?, opts.force)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequences() {
        assert_eq!(Loop::PingPong.sequence(1), vec![0]);
        assert_eq!(Loop::PingPong.sequence(2), vec![0, 1]);
        assert_eq!(Loop::PingPong.sequence(3), vec![0, 1, 2, 1]);
        assert_eq!(Loop::Loop.sequence(3), vec![0, 1, 2]);
        for l in [Loop::Once, Loop::Loop, Loop::PingPong] {
            assert_eq!(l.to_string().parse::<Loop>().unwrap(), l);
        }
        assert!("bounce".parse::<Loop>().is_err());
    }
}
