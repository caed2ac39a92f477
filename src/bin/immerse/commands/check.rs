//! `immerse check`: is a curve self-overlapping, and its facts.

use crate::Outcome;
use crate::args::CheckArgs;
use crate::output;
use immerse::Curve;
use immerse::geom::polygon;
use serde::Serialize;

/// The JSON report of `immerse check --json`.
#[derive(Debug, Serialize)]
struct CheckReport {
    /// Number of points after cleaning.
    points: usize,
    /// Turning number of the cleaned curve as given (before any reversal);
    /// null when the curve doubles back on itself (a cusp).
    turning_number: Option<i64>,
    /// True when no two edges touch except neighbours at their vertex.
    simple: bool,
    /// True when the curve was clockwise and has been reversed.
    reversed: bool,
    /// True when the curve bounds an immersed disk.
    self_overlapping: bool,
    /// Why the curve is not self-overlapping; null when it is.
    reason: Option<String>,
}

/// The outcome of a report that says `self_overlapping`, after writing
/// the report where --json asks; true with it when the report went to
/// stdout, which then holds nothing else.
fn answer<T: Serialize>(
    args: &CheckArgs,
    report: &T,
    self_overlapping: bool,
) -> anyhow::Result<(Outcome, bool)> {
    let outcome = if self_overlapping {
        Outcome::Success
    } else {
        Outcome::Negative
    };
    let mut on_stdout = false;
    if let Some(json) = &args.json {
        super::write_json(json, report, true, args.force)?;
        on_stdout = immerse_render::is_stdout(json);
    }
    Ok((outcome, on_stdout))
}

pub(crate) fn run(args: &CheckArgs) -> anyhow::Result<Outcome> {
    if let Some(json) = &args.json {
        super::check_output_file(json, args.force)?;
    }
    let curve = match Curve::from_path(&args.curve) {
        Ok(c) => c,
        // A file of several shapes is a drawing: answered shape by shape.
        Err(immerse::curve::CurveError::SeveralParts { .. }) => return run_drawing(args),
        Err(e) => return Err(e.into()),
    };
    let crossing = polygon::first_self_intersection(&curve.points);
    let json_on_stdout = args.json.as_deref().is_some_and(immerse_render::is_stdout);
    let bar = super::LateProgress::new("check", json_on_stdout);
    let verdict =
        immerse::triangulate_with_progress(&curve.points, immerse::Quality::Any, &mut |f| {
            bar.update(f)
        });
    bar.finish();
    if let Err(e) = &verdict
        && !e.is_answer()
    {
        anyhow::bail!("{}: {e}", args.curve.display());
    }
    let report = CheckReport {
        points: curve.len(),
        turning_number: curve.turning_number_as_given(),
        simple: crossing.is_none(),
        reversed: curve.reversed,
        self_overlapping: verdict.is_ok(),
        reason: verdict.as_ref().err().map(ToString::to_string),
    };
    let (outcome, on_stdout) = answer(args, &report, report.self_overlapping)?;
    if on_stdout {
        return Ok(outcome);
    }
    let mut lines = vec![format!(
        "{}: {}",
        args.curve.display(),
        match &report.reason {
            None => "self-overlapping".to_string(),
            Some(r) => format!("not self-overlapping ({r})"),
        }
    )];
    let dropped = if curve.dropped > 0 {
        format!(" ({} repeated point(s) dropped)", curve.dropped)
    } else {
        String::new()
    };
    lines.push(format!("  points:         {}{dropped}", report.points));
    lines.push(match curve.turning_as_given {
        polygon::Turning::Number(k) => format!("  turning number: {k}"),
        polygon::Turning::Cusp(i) => {
            format!("  turning number: undefined (the curve doubles back at point {i})")
        }
    });
    lines.push(format!(
        "  orientation:    {}",
        if curve.reversed {
            "clockwise as given; reversed to counter-clockwise"
        } else {
            "as given"
        }
    ));
    lines.push(match crossing {
        None => "  simple:         yes".to_string(),
        Some((i, j)) => format!("  simple:         no (edges {i} and {j} touch)"),
    });
    output::print(&lines.join("\n"))?;
    Ok(outcome)
}

/// One shape's answer in `immerse check --json` on a drawing.
#[derive(Debug, Serialize)]
struct ShapeReport {
    /// The shape's id (empty when it has none).
    id: String,
    /// What names it: `shape K (path 'ID' subpath J)`.
    label: String,
    /// Its facts, as for one curve.
    #[serde(flatten)]
    report: CheckReport,
}

/// The JSON report of `immerse check --json` on a drawing.
#[derive(Debug, Serialize)]
struct DrawingReport {
    /// True when every shape is self-overlapping.
    self_overlapping: bool,
    /// Reading notices (gradients flattened, open strokes left out).
    notices: Vec<String>,
    /// One answer per shape, in painting order.
    shapes: Vec<ShapeReport>,
}

/// `check` on a drawing (docs/design.md §2a): every shape is decided; the
/// answer is yes when all are self-overlapping.
fn run_drawing(args: &CheckArgs) -> anyhow::Result<Outcome> {
    let drawing = immerse::drawing::Drawing::read_path(&args.curve)?;
    let verdicts = drawing.triangulate();
    let mut shapes = Vec::with_capacity(drawing.len());
    for (shape, verdict) in drawing.shapes.iter().zip(&verdicts) {
        if let Err(e) = verdict
            && !e.is_answer()
        {
            anyhow::bail!("{} ({}): {e}", args.curve.display(), shape.label);
        }
        shapes.push(ShapeReport {
            id: shape.id.clone(),
            label: shape.label.clone(),
            report: CheckReport {
                points: shape.points.len(),
                turning_number: match polygon::turning_number(&shape.points) {
                    polygon::Turning::Number(k) => Some(if shape.reversed { -k } else { k }),
                    polygon::Turning::Cusp(_) => None,
                },
                simple: polygon::first_self_intersection(&shape.points).is_none(),
                reversed: shape.reversed,
                self_overlapping: verdict.is_ok(),
                reason: verdict.as_ref().err().map(ToString::to_string),
            },
        });
    }
    let report = DrawingReport {
        self_overlapping: shapes.iter().all(|s| s.report.self_overlapping),
        notices: drawing.notices.clone(),
        shapes,
    };
    let (outcome, on_stdout) = answer(args, &report, report.self_overlapping)?;
    if on_stdout {
        return Ok(outcome);
    }
    let good = report
        .shapes
        .iter()
        .filter(|s| s.report.self_overlapping)
        .count();
    let mut lines = vec![format!(
        "{}: a drawing of {} shapes: {}",
        args.curve.display(),
        report.shapes.len(),
        if report.self_overlapping {
            "every shape self-overlapping".to_string()
        } else {
            format!(
                "{} of {} not self-overlapping",
                report.shapes.len() - good,
                report.shapes.len()
            )
        }
    )];
    for s in &report.shapes {
        lines.push(format!(
            "  {}: {}, {} points{}",
            s.label,
            match &s.report.reason {
                None => "self-overlapping".to_string(),
                Some(r) => format!("not self-overlapping ({r})"),
            },
            s.report.points,
            if s.report.reversed {
                ", clockwise as given (reversed)"
            } else {
                ""
            }
        ));
    }
    for n in &report.notices {
        lines.push(format!("  notice: {n}"));
    }
    output::print(&lines.join("\n"))?;
    Ok(outcome)
}
