//! The one error type of the crate.

use std::path::PathBuf;

/// Everything that can go wrong while rendering or writing frames.
///
/// Messages are lowercase, have no trailing period and name the offending
/// path or value together with the fix, so that a context chain printed with
/// `{:#}` reads as one line.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The image width or height is zero.
    #[error("image size {width}x{height} is empty; use a width and height of at least 1 pixel")]
    EmptyImage {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
    },
    /// The image is too large for the pixel buffer or for the output format.
    #[error("image size {width}x{height} is too large: {reason}")]
    ImageTooLarge {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// Which limit was hit.
        reason: &'static str,
    },
    /// A triangle, face, outline or spine refers to a point (or triangle)
    /// that does not exist.
    #[error("{what} refers to index {index}, but there are only {len}; check the frame's indices")]
    BadIndex {
        /// Which list holds the bad index (`"triangle"`, `"outline"`, ...).
        what: &'static str,
        /// The offending index.
        index: u32,
        /// How many points (or triangles, for the spine) there are.
        len: usize,
    },
    /// A problem in one frame of a sequence.
    #[error("frame {frame}")]
    InFrame {
        /// Index of the frame in the input slice.
        frame: usize,
        /// What went wrong with it.
        #[source]
        source: Box<RenderError>,
    },
    /// A point that must be drawn (an animated outline vertex) is not finite.
    #[error("point {index} has a non-finite coordinate; remove or fix it")]
    NonFinitePoint {
        /// Index of the point.
        index: u32,
    },
    /// Keyframe times that are not finite, strictly increasing frame
    /// positions from 0 to the last frame, one per shape.
    #[error(
        "keyframe {key}: time {time} is not a frame position after the previous key's and at most the last frame ({last}); give one strictly increasing time per shape"
    )]
    KeyTime {
        /// The key.
        key: usize,
        /// Its time.
        time: f64,
        /// The last frame.
        last: usize,
    },
    /// A sequence writer was given no frames.
    #[error("no frames to write; give at least one frame")]
    NoFrames,
    /// An animated SVG needs frames whose outlines can be interpolated.
    #[error(
        "frame {frame} has {found} outline vertices but frame 0 has {expected}; an animated svg needs the same non-empty outline length in every frame"
    )]
    OutlineMismatch {
        /// The first frame that does not match.
        frame: usize,
        /// Outline length of frame 0.
        expected: usize,
        /// Outline length of `frame`.
        found: usize,
    },
    /// A Lottie animation draws each frame's outline, and this one has none.
    #[error("frame {frame} has no outline; a lottie animation draws the outline of every frame")]
    EmptyOutline {
        /// The first frame without an outline.
        frame: usize,
    },
    /// The frame rate is not from [`crate::MIN_FPS`] to [`crate::MAX_FPS`]
    /// frames per second.
    #[error(
        "frame rate {fps} is not from {} to {} frames per second",
        crate::MIN_FPS,
        crate::MAX_FPS
    )]
    BadFps {
        /// The rejected frame rate.
        fps: f64,
    },
    /// A GIF cannot play this many frames per second: its delays are whole
    /// hundredths of a second, at least 2.
    #[error(
        "a gif plays at most 50 frames per second (its frame delays are whole hundredths of a second, and browsers slow down delays under 2), not {fps}; ask for 50 or fewer, or write png frames or an animated svg"
    )]
    GifFpsTooHigh {
        /// The rejected frame rate.
        fps: f64,
    },
    /// The caller stopped the work (see [`crate::encode_gif`]).
    #[error("stopped before the end")]
    Cancelled,
    /// A contact sheet would have more pixels than are rendered.
    #[error(
        "a contact sheet of {frames} frames in {columns} columns would be {width}x{height} pixels, over the limit of {limit} pixels; use fewer frames or a smaller size"
    )]
    SheetTooLarge {
        /// Number of frames.
        frames: usize,
        /// Columns of the grid.
        columns: usize,
        /// Sheet width in pixels.
        width: u64,
        /// Sheet height in pixels.
        height: u64,
        /// The limit ([`Style::MAX_PIXELS`](crate::Style::MAX_PIXELS)).
        limit: u64,
    },
    /// An easing string could not be parsed or has out-of-range parameters.
    #[error(
        "invalid easing '{input}': {reason}; expected linear, ease, ease-in, ease-out, ease-in-out or cubic-bezier(x1,y1,x2,y2) with x1 and x2 in [0,1]"
    )]
    BadEasing {
        /// The text that was rejected.
        input: String,
        /// Why it was rejected.
        reason: String,
    },
    /// A loop mode string is not one of the known names.
    #[error("invalid loop mode '{input}'; expected once, loop or ping-pong")]
    BadLoop {
        /// The text that was rejected.
        input: String,
    },
    /// A colour string is not `#rrggbb` or `#rrggbbaa`.
    #[error("invalid colour '{input}'; expected #rrggbb or #rrggbbaa")]
    BadColor {
        /// The text that was rejected.
        input: String,
    },
    /// The output folder exists and already holds files.
    #[error("output folder {} is not empty; pass --force to write into it", path.display())]
    DirNotEmpty {
        /// The folder.
        path: PathBuf,
    },
    /// The output folder path exists but is not a folder.
    #[error("output path {} exists and is not a folder; choose another path", path.display())]
    NotADir {
        /// The path.
        path: PathBuf,
    },
    /// An output file's path names a folder.
    #[error("output path {} is a folder; name a file", path.display())]
    IsADir {
        /// The path.
        path: PathBuf,
    },
    /// The folder an output would be written in does not exist.
    #[error("cannot write {}: there is no folder {}; create it first", path.display(), folder.display())]
    NoFolder {
        /// The output path.
        path: PathBuf,
        /// The missing folder.
        folder: PathBuf,
    },
    /// The output file exists.
    #[error("output file {} already exists; pass --force to overwrite it", path.display())]
    FileExists {
        /// The file.
        path: PathBuf,
    },
    /// Reading or writing a file or folder failed.
    #[error("cannot write {}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The operating system's reason.
        #[source]
        source: std::io::Error,
    },
    /// The PNG encoder failed.
    #[error("cannot encode png")]
    Png(#[source] png::EncodingError),
    /// The GIF encoder failed.
    #[error("cannot encode gif")]
    Gif(#[source] gif::EncodingError),
}

impl RenderError {
    pub(crate) fn in_frame(self, frame: usize) -> RenderError {
        RenderError::InFrame {
            frame,
            source: Box::new(self),
        }
    }

    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> RenderError {
        RenderError::Io {
            path: path.into(),
            source,
        }
    }
}
