//! Safe file output, PNG sequences and GIFs.
//!
//! Nothing is overwritten silently: [`prepare_output_dir`] refuses a
//! non-empty folder and [`write_atomic`] an existing file unless `force` is
//! set, and every file is written to a temporary file in the same folder
//! and renamed into place, so an interrupted run leaves no half-written
//! file behind.

use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

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

/// Creates the output folder `dir` (with its parents) or checks that an
/// existing one may be written into.
///
/// An existing non-empty folder is refused unless `force` is set. With
/// `force` the writers put their files into it, replacing files of the same
/// name (`frame_0000.png`, ...); nothing else is deleted, so frames left
/// over from an earlier, longer run stay.
///
/// # Errors
///
/// [`RenderError::DirNotEmpty`], [`RenderError::NotADir`], or
/// [`RenderError::Io`] when the folder cannot be read or created.
pub fn prepare_output_dir(dir: &Path, force: bool) -> Result<(), RenderError> {
    match std::fs::metadata(dir) {
        Ok(meta) if !meta.is_dir() => Err(RenderError::NotADir { path: dir.into() }),
        Ok(_) => {
            let mut entries = std::fs::read_dir(dir).map_err(|e| RenderError::io(dir, e))?;
            if !force && entries.next().is_some() {
                return Err(RenderError::DirNotEmpty { path: dir.into() });
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            std::fs::create_dir_all(dir).map_err(|e| RenderError::io(dir, e))
        }
        Err(e) => Err(RenderError::io(dir, e)),
    }
}

/// Writes `bytes` to `path` atomically: into a temporary file in the same
/// folder, which is then renamed to `path`. Without `force` an existing
/// `path` is refused (and left untouched, even if it appears meanwhile).
///
/// # Errors
///
/// [`RenderError::FileExists`], or [`RenderError::Io`] when the folder is
/// not writable. On error no temporary file is left behind.
pub fn write_atomic(path: &Path, bytes: &[u8], force: bool) -> Result<(), RenderError> {
    if !force && std::fs::symlink_metadata(path).is_ok() {
        return Err(RenderError::FileExists { path: path.into() });
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".immerse-").suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // Ordinary file permissions (subject to the umask), not the private
        // 0600 of temporary files, since the file is renamed into place.
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder
        .tempfile_in(parent)
        .map_err(|e| RenderError::io(parent, e))?;
    tmp.write_all(bytes)
        .and_then(|()| tmp.flush())
        .map_err(|e| RenderError::io(path, e))?;
    let persisted = if force {
        tmp.persist(path)
    } else {
        tmp.persist_noclobber(path)
    };
    // On failure the returned temporary file is dropped, which deletes it.
    persisted.map(drop).map_err(|e| {
        if e.error.kind() == std::io::ErrorKind::AlreadyExists {
            RenderError::FileExists { path: path.into() }
        } else {
            RenderError::io(path, e.error)
        }
    })
}

/// The file name of frame `i` of `n`: `frame_0000.ext`, zero-padded to at
/// least four digits (more when `n` needs them).
pub fn frame_file_name(i: usize, n: usize, ext: &str) -> String {
    let digits = n.saturating_sub(1).to_string().len().max(4);
    format!("frame_{i:0digits$}.{ext}")
}

/// The frames drawn as onion skin behind every frame: the first and last.
pub(crate) fn onion<'a>(frames: &'a [Frame], style: &Style) -> Vec<&'a Frame> {
    match (style.onion_skin, frames.first(), frames.last()) {
        (true, Some(a), Some(b)) if frames.len() > 1 => vec![a, b],
        _ => Vec::new(),
    }
}

/// Writes a per-frame sequence: `encode(frame, view)` in parallel into
/// `dir/frame_NNNN.ext`.
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
    prepare_output_dir(dir, opts.force)?;
    let view = View::fit(frames, style);
    let done = AtomicUsize::new(0);
    frames
        .par_iter()
        .enumerate()
        .map(|(i, frame)| {
            let bytes = encode(frame, &view).map_err(|e| e.in_frame(i))?;
            let path = dir.join(frame_file_name(i, frames.len(), ext));
            write_atomic(&path, &bytes, opts.force)?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok(path)
        })
        .collect()
}

/// Renders `frames` in parallel and writes them as `dir/frame_0000.png`, ...
/// (zero-padded to at least four digits), with one shared [`View`].
///
/// `dir` is prepared with [`prepare_output_dir`] and every file written
/// with [`write_atomic`], both with `opts.force`. When
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

/// Renders `frames` and writes them as one animated GIF at `path`.
///
/// Frames are rendered and quantised (per-frame palettes, speed
/// [`Output::gif_speed`]) and LZW-compressed in parallel batches, then
/// written in order. The frame delay is `100 / fps` hundredths of a second,
/// at least 2 (browsers slow down shorter delays). [`Loop::Once`] plays once,
/// [`Loop::Loop`] repeats forever, [`Loop::PingPong`] appends the frames
/// reversed without repeating the ends and repeats forever. `progress` gets
/// the number of frames finished so far (of the played sequence).
///
/// # Errors
///
/// [`RenderError::NoFrames`], [`RenderError::BadFps`],
/// [`RenderError::ImageTooLarge`] beyond 65535 pixels a side, an
/// output-safety error for `path`, a frame's error, or [`RenderError::Gif`].
pub fn write_gif(
    frames: &[Frame],
    path: &Path,
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<(), RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    check_fps(fps)?;
    style.check_size()?;
    let too_large = || RenderError::ImageTooLarge {
        width: style.width,
        height: style.height,
        reason: "gif images are at most 65535 pixels a side",
    };
    u16::try_from(style.width).map_err(|_| too_large())?;
    u16::try_from(style.height).map_err(|_| too_large())?;
    if !opts.force && std::fs::symlink_metadata(path).is_ok() {
        return Err(RenderError::FileExists { path: path.into() });
    }
    let out = encode_gif(frames, style, fps, looping, opts, progress)?;
    write_atomic(path, &out, opts.force)
}

/// The GIF that [`write_gif`] writes, in memory (for a server; `opts.force`
/// is not used).
///
/// # Errors
///
/// As [`write_gif`], without the output-safety errors.
pub fn encode_gif(
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<u8>, RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    check_fps(fps)?;
    style.check_size()?;
    let too_large = || RenderError::ImageTooLarge {
        width: style.width,
        height: style.height,
        reason: "gif images are at most 65535 pixels a side",
    };
    let w = u16::try_from(style.width).map_err(|_| too_large())?;
    let h = u16::try_from(style.height).map_err(|_| too_large())?;
    let delay = (100.0 / fps).round().clamp(2.0, f64::from(u16::MAX)) as u16;
    let speed = opts.gif_speed.clamp(1, 30);
    let view = View::fit(frames, style);
    let ghosts = onion(frames, style);

    let mut out = Vec::new();
    let mut encoder = gif::Encoder::new(&mut out, w, h, &[]).map_err(RenderError::Gif)?;
    if looping != Loop::Once {
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(RenderError::Gif)?;
    }
    let mut encoded: Vec<gif::Frame<'static>> = Vec::with_capacity(frames.len());
    let done = AtomicUsize::new(0);
    for (b, batch) in frames.chunks(GIF_BATCH).enumerate() {
        let mut quantised = batch
            .par_iter()
            .enumerate()
            .map(|(k, frame)| {
                let i = b * GIF_BATCH + k;
                let pixmap = render(frame, &view, style, &ghosts).map_err(|e| e.in_frame(i))?;
                let mut rgba = pixmap.take_demultiplied();
                let mut gf = gif::Frame::from_rgba_speed(w, h, &mut rgba, speed);
                gf.delay = delay;
                gf.make_lzw_pre_encoded();
                progress(done.fetch_add(1, Ordering::Relaxed) + 1);
                Ok(gf)
            })
            .collect::<Result<Vec<_>, RenderError>>()?;
        for gf in &quantised {
            encoder
                .write_lzw_pre_encoded_frame(gf)
                .map_err(RenderError::Gif)?;
        }
        if looping == Loop::PingPong {
            encoded.append(&mut quantised);
        }
    }
    if looping == Loop::PingPong && encoded.len() > 2 {
        for gf in encoded[1..encoded.len() - 1].iter().rev() {
            encoder
                .write_lzw_pre_encoded_frame(gf)
                .map_err(RenderError::Gif)?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
        }
    }
    encoder.into_inner().map_err(RenderError::Gif)?;
    Ok(out)
}

pub(crate) fn check_fps(fps: f64) -> Result<(), RenderError> {
    if fps.is_finite() && fps > 0.0 {
        Ok(())
    } else {
        Err(RenderError::BadFps { fps })
    }
}

/// Renders `frames` side by side into one image, `columns` per row (0
/// means one row), each cell `style.width` × `style.height`, all with one
/// shared [`View`]: a contact sheet for comparing in-betweens at a glance.
///
/// # Errors
///
/// [`RenderError::NoFrames`], a size error (also when the whole sheet is
/// too large), or a frame's error.
pub fn contact_sheet(
    frames: &[Frame],
    style: &Style,
    columns: usize,
) -> Result<tiny_skia::Pixmap, RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    style.check_size()?;
    let cols = if columns == 0 {
        frames.len()
    } else {
        columns.min(frames.len())
    };
    let rows = frames.len().div_ceil(cols);
    let (w, h) = (style.width, style.height);
    let too_large = || RenderError::ImageTooLarge {
        width: w.saturating_mul(cols as u32),
        height: h.saturating_mul(rows as u32),
        reason: "a contact sheet is limited to Style::MAX_PIXELS; use fewer frames or a smaller --size",
    };
    let (sw, sh) = (
        u32::try_from(cols)
            .ok()
            .and_then(|c| w.checked_mul(c))
            .ok_or_else(too_large)?,
        u32::try_from(rows)
            .ok()
            .and_then(|r| h.checked_mul(r))
            .ok_or_else(too_large)?,
    );
    if u64::from(sw) * u64::from(sh) > Style::MAX_PIXELS {
        return Err(too_large());
    }
    let mut sheet = tiny_skia::Pixmap::new(sw, sh).ok_or_else(too_large)?;
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

/// Writes [`contact_sheet`] as a PNG with [`write_atomic`].
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
    if !opts.force && std::fs::symlink_metadata(path).is_ok() {
        return Err(RenderError::FileExists { path: path.into() });
    }
    let sheet = contact_sheet(frames, style, columns)?;
    write_atomic(path, &encode_png(&sheet)?, opts.force)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_padded() {
        assert_eq!(frame_file_name(7, 120, "png"), "frame_0007.png");
        assert_eq!(frame_file_name(7, 10_001, "svg"), "frame_00007.svg");
        assert_eq!(frame_file_name(0, 0, "png"), "frame_0000.png");
    }

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
