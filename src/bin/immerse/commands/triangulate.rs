//! `immerse triangulate`: the immersion triangulation of one curve.

use super::{LateProgress, plain_points};
use crate::Outcome;
use crate::args::TriangulateArgs;
use crate::output;
use anyhow::Context;
use immerse::triangulate_with_progress;
use immerse::{Curve, Point, RootChoice};
use immerse_render as render;
use serde::Serialize;

/// The JSON of `immerse triangulate --json` (docs/design.md §10).
#[derive(Debug, Serialize)]
struct TriangulationJson {
    /// Vertices in oriented order (turning number +1), y up.
    points: Vec<[f64; 2]>,
    /// Counter-clockwise triangles as index triples into `points`.
    triangles: Vec<[u32; 3]>,
    /// True when the curve was clockwise and has been reversed.
    reversed: bool,
    /// The spine: triangle indices from the pivot triangle to the other end.
    spine: Vec<usize>,
    /// The pivot vertex (index into `points`).
    pivot_vertex: u32,
    /// The root triangle of morph propagation (index into `triangles`).
    root_triangle: usize,
}

pub(crate) fn run(args: &TriangulateArgs) -> anyhow::Result<Outcome> {
    // Every output is checked before any work.
    if let Some(path) = &args.output {
        image_type(path)?;
        super::check_output_file(path, args.force)?;
    }
    if let Some(json) = &args.json {
        super::check_output_file(json, args.force)?;
    }
    let json_on_stdout = args.json.as_deref().is_some_and(render::is_stdout);
    let curve = Curve::from_path(&args.curve)?;
    let quality = args.quality;
    let bar = LateProgress::new("triangulate", json_on_stdout);
    let result = triangulate_with_progress(&curve.points, quality, &mut |f| bar.update(f));
    bar.finish();
    let imm = match result {
        Ok(imm) => imm,
        Err(reason) if !reason.is_answer() => {
            anyhow::bail!("{}: {reason}", args.curve.display());
        }
        Err(reason) => {
            output::note(&format!(
                "{}: not self-overlapping: {reason}",
                args.curve.display()
            ));
            return Ok(Outcome::Negative);
        }
    };
    let not_a_tree = "the triangulation's dual graph is not a tree; this is a bug in immerse";
    let spine = imm.spine().context(not_a_tree)?;
    let root = imm.root_triangle(RootChoice::Disk).context(not_a_tree)?;
    if let Some(path) = &args.output {
        draw(args, path, &imm.points, &imm.triangles, &spine, root)?;
    }
    if let Some(json) = &args.json {
        let doc = TriangulationJson {
            points: plain_points(&imm.points),
            triangles: imm.triangles.clone(),
            reversed: curve.reversed,
            spine: spine.triangles.clone(),
            pivot_vertex: spine.pivot_vertex,
            root_triangle: root,
        };
        super::write_json(json, &doc, true, args.force)?;
    }
    if !json_on_stdout {
        output::print(&format!(
            "{}: {} points, {} triangles ({quality}), minimum angle {:.3}°, spine of {} triangles, pivot vertex {}, root triangle {root}",
            args.curve.display(),
            imm.points.len(),
            imm.triangles.len(),
            imm.min_angle().to_degrees(),
            spine.triangles.len(),
            spine.pivot_vertex,
        ))?;
    }
    Ok(Outcome::Success)
}

fn draw(
    args: &TriangulateArgs,
    path: &std::path::Path,
    points: &[Point],
    triangles: &[[u32; 3]],
    spine: &immerse::Spine,
    _root: usize,
) -> anyhow::Result<()> {
    let mut frame = render::Frame::from_triangles(plain_points(points), triangles.to_vec());
    frame.spine = spine.triangles.iter().map(|&t| t as u32).collect();
    let pivot = points[spine.pivot_vertex as usize];
    frame.markers = vec![[pivot.x, pivot.y]];
    let style = render::Style::DEFAULT
        .with_size(args.size.0, args.size.1)
        .with_wireframe(true)
        .with_spine(true)
        .with_markers(true);
    let view = render::View::fit(std::slice::from_ref(&frame), &style);
    let bytes = match image_type(path)? {
        ImageType::Png => render::encode_png(&render::render(&frame, &view, &style, &[])?)?,
        ImageType::Svg => render::svg_frame(&frame, &view, &style, &[])?.into_bytes(),
    };
    render::write_atomic(path, &bytes, args.force)?;
    Ok(())
}

/// The image types `triangulate -o` draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ImageType {
    Png,
    Svg,
}

/// The image type of `path` by its extension, or a clear error.
fn image_type(path: &std::path::Path) -> anyhow::Result<ImageType> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(ImageType::Png),
        Some("svg") => Ok(ImageType::Svg),
        _ => anyhow::bail!(
            "{}: unknown image type; name a .png or .svg file",
            path.display()
        ),
    }
}
