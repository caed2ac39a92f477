//! Writing the frames of a morph or an animation in the format asked
//! for, and the image style and play mode of `immerse morph`: shared by
//! `morph`, its drawings and `animate`.

use super::keyed::{self, Played};
use super::progress_bar;
use crate::args::{FormatArg, MorphArgs, PlayArgs};
use crate::output;
use anyhow::Context;
use immerse_render as render;
use std::path::Path;

impl PlayArgs {
    /// The image style at `size` with these flags' wireframe and onion skin.
    pub(crate) fn style(&self, size: (u32, u32)) -> render::Style {
        render::Style::DEFAULT
            .with_size(size.0, size.1)
            .with_wireframe(self.wireframe)
            .with_onion_skin(self.onion)
    }

    /// How the animation plays when a flag says so (--ping-pong, --once).
    pub(crate) fn looping(&self) -> Option<render::Loop> {
        if self.ping_pong {
            Some(render::Loop::PingPong)
        } else if self.once {
            Some(render::Loop::Once)
        } else {
            None
        }
    }
}

/// The image style of `immerse morph`.
pub(crate) fn style(args: &MorphArgs) -> render::Style {
    args.play.style(args.out.image.size)
}

/// How `immerse morph`'s animations play.
pub(crate) fn looping(args: &MorphArgs) -> render::Loop {
    args.play.looping().unwrap_or(render::Loop::Loop)
}

/// How frames are written: their style, frame rate and play mode, whether
/// existing files are replaced, and whether progress is quiet.
#[derive(Clone, Debug)]
pub(crate) struct Writing {
    pub(crate) style: render::Style,
    pub(crate) fps: f64,
    pub(crate) looping: render::Loop,
    pub(crate) force: bool,
    pub(crate) quiet: bool,
}

/// How `immerse morph` writes its frames.
pub(crate) fn writing(args: &MorphArgs) -> Writing {
    Writing {
        style: style(args),
        fps: args.out.image.fps,
        looping: looping(args),
        force: args.run.force,
        quiet: args.run.quiet,
    }
}

/// Writes to `out` the Lottie or animated SVG (`kind`) that `write` makes
/// of the document, its view fitted to `frames`, as `writing` says; notes
/// what it holds unless quiet.
pub(crate) fn write_document(
    kind: keyed::Kind,
    frames: &[render::Frame],
    out: &Path,
    writing: &Writing,
    write: impl FnOnce(keyed::Document<'_>) -> anyhow::Result<keyed::Written>,
) -> anyhow::Result<()> {
    let doc = keyed::Document {
        kind,
        view: render::View::fit(frames, &writing.style),
        style: &writing.style,
        fps: writing.fps,
        looping: writing.looping,
    };
    let written = write(doc).with_context(|| format!("-o {}", out.display()))?;
    keyed::save(&written, out, writing.force)?;
    if !writing.quiet {
        output::note(&keyed::describe(kind, &written, written.text.len()));
    }
    Ok(())
}

/// Writes rendered frames to `out` as `images` and `writing` say, with a
/// progress bar.
pub(crate) fn write_frames(
    frames: &[render::Frame],
    keys: Option<&Played>,
    out: &Path,
    images: super::ImageOutput,
    writing: &Writing,
) -> anyhow::Result<()> {
    let Writing {
        ref style,
        fps,
        looping,
        force,
        quiet,
    } = *writing;
    let opts = render::Output::DEFAULT.with_force(force);
    let total = match images.format {
        FormatArg::Gif => looping.sequence(frames.len()).len(),
        _ => frames.len(),
    };
    let bar = progress_bar(total as u64, "render", quiet);
    let progress = |done: usize| bar.set_position(done as u64);
    match images.format {
        FormatArg::Png => {
            render::write_png_sequence(frames, out, style, &opts, &progress)?;
        }
        FormatArg::Svg => {
            render::write_svg_sequence(frames, out, style, &opts, &progress)?;
        }
        FormatArg::Gif => render::write_gif(frames, out, style, fps, looping, &opts, &progress)?,
        FormatArg::AnimatedSvg | FormatArg::Lottie if keys.is_some() => {
            let kind = if images.format == FormatArg::Lottie {
                keyed::Kind::Lottie
            } else {
                keyed::Kind::AnimatedSvg
            };
            let played = keys.expect("matched on is_some");
            write_document(kind, frames, out, writing, |doc| keyed::write(doc, played))?;
        }
        FormatArg::AnimatedSvg => {
            render::write_animated_svg(frames, out, style, fps, looping, &opts)?;
        }
        FormatArg::Sheet => {
            render::write_contact_sheet(frames, out, style, images.columns, &opts)?;
        }
        FormatArg::Lottie => render::write_lottie(frames, out, style, fps, looping, &opts)?,
    }
    bar.finish_and_clear();
    Ok(())
}
