//! Rasterise and write plain 2-D geometry: the pictures of *immerse*.
//!
//! This crate draws closed curves that may cross themselves, filled as
//! *immersed disks*: the fill may overlap itself, and a spot covered k times
//! is shaded k layers deep. It knows nothing of how the geometry was made;
//! the input is a [`Frame`] of points, counter-clockwise triangles (which
//! may overlap), an outline loop, optional polygon faces, a spine and
//! markers.
//!
//! The pipeline, for one animation:
//!
//! ```text
//! &[Frame] ──> View::fit (one world→pixel mapping for all frames, y flipped)
//!          ──> render (tiny-skia; depth-shaded fill, wireframe, outline, onion skin)
//!          ──> encode_png / write_png_sequence / write_gif (rayon in parallel)
//!          ──> svg_frame / write_svg_sequence / write_animated_svg (SMIL)
//!          ──> lottie / write_lottie (one shape layer, path keyframes)
//! ```
//!
//! Writers never overwrite silently: [`check_output_dir`] and
//! [`OutputFile`] refuse existing output unless `force` is given (and can
//! check before any work), every file appears by an atomic rename, a frame
//! sequence by a folder moved into place, and
//! [`remove_partial_outputs`] removes what an interrupted run was writing. [`Easing`] and [`frame_times`]
//! turn a frame count into CSS-style eased animation times.
//!
//! The crate has no features. It re-exports [`tiny_skia`], whose
//! [`Pixmap`](tiny_skia::Pixmap) [`render`] returns.
//!
//! # Examples
//!
//! Two triangles overlap; the doubly covered spot is darker:
//!
//! ```
//! use immerse_render::{render, Frame, Style, View};
//!
//! let frame = Frame {
//!     points: vec![[0.0, 0.0], [4.0, 0.0], [0.0, 4.0], [1.0, 1.0], [5.0, 1.0], [1.0, 5.0]],
//!     triangles: vec![[0, 1, 2], [3, 4, 5]],
//!     ..Frame::default()
//! };
//! let style = Style::DEFAULT.with_size(100, 100).with_wireframe(false);
//! let view = View::fit(std::slice::from_ref(&frame), &style);
//! let pixmap = render(&frame, &view, &style, &[])?;
//!
//! let red_at = |p: [f64; 2]| {
//!     let [x, y] = view.to_pixel(p);
//!     pixmap.pixel(x as u32, y as u32).unwrap().red()
//! };
//! let (once, twice) = (red_at([0.5, 3.0]), red_at([1.5, 1.5]));
//! assert!(twice < once);
//! # Ok::<(), immerse_render::RenderError>(())
//! ```
#![forbid(unsafe_code)]
#![deny(rustdoc::broken_intra_doc_links)]

mod easing;
mod error;
mod frame;
mod io;
mod lottie;
mod output;
mod raster;
mod style;
mod svg;
mod view;

pub use easing::{Easing, frame_times};
pub use error::RenderError;
pub use frame::{DrawingKeys, Frame, Layer, Paint, Scene, Track};
pub use io::{
    Destination, NewOutputDir, OutputFile, check_output_dir, check_output_file, frame_file_name,
    is_stdout, remove_partial_outputs, resolve_output, write_atomic,
};
pub use lottie::{Keys, lottie, lottie_drawing, lottie_keys, write_lottie};
pub use output::{
    GIF_MAX_FPS, Loop, MAX_FPS, MIN_FPS, Output, check_fps, check_gif_fps, contact_sheet,
    contact_sheet_columns, contact_sheet_size, encode_gif, fps_in_range, write_contact_sheet,
    write_gif, write_png_sequence,
};
pub use raster::{encode_png, render};
pub use style::{Rgba, Style};
pub use svg::{
    BACKGROUND_ID, OUTLINE_ID, animated_svg, animated_svg_drawing, animated_svg_keys, svg_frame,
    write_animated_svg, write_svg_sequence,
};
pub use tiny_skia;
pub use view::View;
