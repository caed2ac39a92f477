//! `immerse mesh-morph`: morphs between compatible planar tilings.

use super::plain_points;
use super::write::{Writing, write_frames};
use crate::Outcome;
use crate::args::MeshMorphArgs;
use crate::output;
use immerse_mesh::mesh_morph::{LinearCheck, MeshMorphOptions, check_linear, mesh_morph};
use immerse_mesh::tiling::Tiling;
use immerse_render as render;
use serde::Serialize;

/// One frame of `mesh-morph --json` (docs/design.md §10).
#[derive(Serialize)]
struct FrameJson<'a> {
    /// Time in [0, 1].
    t: f64,
    /// Vertex positions, y up.
    points: Vec<[f64; 2]>,
    /// The faces, as in the input.
    faces: &'a [Vec<u32>],
    /// True when every face is strictly convex and counter-clockwise
    /// (decided exactly).
    valid: bool,
}

/// The JSON of `mesh-morph --json`.
#[derive(Serialize)]
struct MorphJson<'a> {
    /// The method used.
    method: &'static str,
    /// The frames in order of t.
    frames: Vec<FrameJson<'a>>,
}

/// The image style of `immerse mesh-morph`.
fn style(args: &MeshMorphArgs) -> render::Style {
    render::Style::DEFAULT
        .with_size(args.out.image.size.0, args.out.image.size.1)
        .with_wireframe(true)
}

pub(crate) fn run(args: &MeshMorphArgs) -> anyhow::Result<Outcome> {
    super::check_fps("--fps", args.out.image.fps)?;
    // Every output is checked before any work.
    let images = if args.check_linear {
        None
    } else {
        args.out
            .check_images(args.run.force, args.frames as usize, &style(args))?
    };
    if let Some(json) = &args.out.json
        && !args.check_linear
    {
        super::check_output_file(json, args.run.force)?;
    }
    super::one_stdout(&args.out.on_stdout())?;
    let a = Tiling::from_path(&args.source)?;
    let b = Tiling::from_path(&args.target)?;
    if args.check_linear {
        return Ok(match check_linear(&a, &b) {
            LinearCheck::Valid => {
                output::print(
                    "the linear morph is valid: every face stays convex and counter-clockwise for all t in [0, 1]",
                )?;
                Outcome::Success
            }
            LinearCheck::Degenerates {
                vertex,
                a: p,
                b: q,
                t_from,
                t_to,
            } => {
                output::print(&format!(
                    "the linear morph is not valid: the corner at vertex {vertex} between {p} and {q} folds for t in [{t_from:.6}, {t_to:.6}]"
                ))?;
                Outcome::Negative
            }
            LinearCheck::Incompatible(why) => {
                anyhow::bail!(
                    "{} and {}: {why}",
                    args.source.display(),
                    args.target.display()
                )
            }
        });
    }
    let method = args.method;
    let mut options = MeshMorphOptions::DEFAULT
        .with_weights(args.weights)
        .with_area_improvement(args.area_improvement);
    if let Some(path) = &args.intermediate {
        options = options.with_intermediate(Some(Tiling::from_path(path)?), 0.5);
    }
    let n = args.frames as usize;
    let times: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    // A spinner where the solve can take seconds (about a million vertex
    // positions and more), quiet otherwise.
    let busy = super::spinner(
        &format!("morphing {} vertices over {n} frames", a.points.len()),
        args.run.quiet || a.points.len() * n < 1_000_000,
    );
    let frames = mesh_morph(&a, &b, method, &times, &options);
    busy.finish_and_clear();
    let frames = frames?;
    let invalid = frames.iter().filter(|f| !f.valid).count();
    if let Some(json) = &args.out.json {
        let doc = MorphJson {
            method: method.as_str(),
            frames: frames
                .iter()
                .map(|f| FrameJson {
                    t: f.t,
                    points: plain_points(&f.points),
                    faces: &a.faces,
                    valid: f.valid,
                })
                .collect(),
        };
        super::write_json(json, &doc, false, args.run.force)?;
    }
    if let (Some(out), Some(images)) = (&args.out.output, images) {
        let plain: Vec<render::Frame> = frames
            .iter()
            .map(|f| render::Frame {
                points: plain_points(&f.points),
                faces: a.faces.clone(),
                outline: a.boundary(),
                ..render::Frame::default()
            })
            .collect();
        let writing = Writing {
            style: style(args),
            fps: args.out.image.fps,
            looping: render::Loop::Loop,
            force: args.run.force,
            quiet: args.run.quiet,
        };
        write_frames(&plain, None, out, images, &writing)?;
    }
    if !args.run.quiet {
        output::note(&format!(
            "{} frames by the {} method: {} valid, {invalid} with a folded or degenerate face",
            frames.len(),
            method.as_str(),
            frames.len() - invalid
        ));
    }
    Ok(Outcome::Success)
}
