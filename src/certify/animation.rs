//! Certifying a whole animation read from a file (`immerse certify`,
//! docs/design.md §13): every segment of every animated outline, with its
//! keys' triangulations when the file has them, else by
//! [`super::certify_motion`].

use rayon::prelude::*;

use super::motion::{Piece, Source};
use super::read::{AnimatedPath, Animation, Format, Play};
use super::{Defect, Failure, MotionOptions, Player, SParam, Verdict, certify_motion};
use crate::immersion::check;
use crate::quality::{Quality, triangulate_with};

/// The answer about an animation, a path or a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Answer {
    /// Valid at every time (for this player).
    Certified,
    /// A shape it shows is not self-overlapping.
    Invalid,
    /// Neither shown within the limits, or not a motion certify covers.
    Undecided,
}

/// A certificate failure, for reports.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FailureReport {
    /// "triangle", "fan" or "start".
    pub what: &'static str,
    /// The triangle's corners.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub triangle: Option<[u32; 3]>,
    /// The fan's vertex.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertex: Option<usize>,
    /// Where (s of the segment).
    pub s: SParam,
    /// True when only the player's margin fails.
    pub within_margin: bool,
    /// In words.
    pub message: String,
}

impl From<&Failure> for FailureReport {
    fn from(f: &Failure) -> Self {
        let (what, triangle, vertex) = match &f.defect {
            Defect::Start(_) => ("start", None, None),
            Defect::Triangle { corners, .. } => ("triangle", Some(*corners), None),
            Defect::Fan { vertex } => ("fan", None, Some(*vertex)),
        };
        FailureReport {
            what,
            triangle,
            vertex,
            s: f.at.clone(),
            within_margin: f.within_margin,
            message: f.to_string(),
        }
    }
}

/// The outcome of one segment (key i to key i + 1).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SegmentOutcome {
    /// i.
    pub index: usize,
    /// Time of key i.
    pub t0: f64,
    /// Time of key i + 1.
    pub t1: f64,
    /// How it is played: linear, eased, hold, not-covered.
    pub play: &'static str,
    /// The answer.
    pub answer: Answer,
    /// True when certified by key i's own triangulation alone (the
    /// keyframe certificate).
    pub as_given: bool,
    /// The certified pieces of the segment, each under one
    /// triangulation: where it starts and ends, and where the
    /// triangulation came from (a key's, or triangulated there).
    pub pieces: Vec<Piece>,
    /// The first certificate failure met, if any (of the key's own
    /// triangulation when there is one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure: Option<FailureReport>,
    /// Where the shape is not self-overlapping (s of the segment).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub invalid_at: Option<SParam>,
    /// Certified on [0, this] when undecided.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub certified_up_to: Option<f64>,
    /// Why undecided or not covered.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The outcome of one animated outline.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PathOutcome {
    /// Where it is in the file.
    pub name: String,
    /// Keys.
    pub keys: usize,
    /// Points per key (of the first key).
    pub points: usize,
    /// True when read in reverse vertex order (clockwise as given).
    pub reversed: bool,
    /// The answer.
    pub answer: Answer,
    /// One outcome per segment.
    pub segments: Vec<SegmentOutcome>,
    /// Why the last key is not valid, if it is not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub last_key: Option<String>,
}

/// The certificate of an animation.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct AnimationReport {
    /// What the file was read as.
    pub format: Format,
    /// The player's arithmetic certified against.
    pub player: Player,
    /// The answer: certified only when every segment of every path is.
    pub answer: Answer,
    /// Segments in all.
    pub segments: usize,
    /// Segments certified.
    pub certified: usize,
    /// Of those, certified by their first key's own triangulation alone.
    pub certified_as_given: usize,
    /// Segments with an invalid shape.
    pub invalid: usize,
    /// Segments undecided or not covered.
    pub undecided: usize,
    /// The outlines.
    pub paths: Vec<PathOutcome>,
    /// What the file has that is not certified.
    pub skipped: Vec<String>,
}

/// Certify every animated outline of `anim` against `player`.
pub fn certify_animation(
    anim: &Animation,
    player: Player,
    options: MotionOptions,
) -> AnimationReport {
    let paths: Vec<PathOutcome> = anim
        .paths
        .iter()
        .map(|p| certify_path(p, anim.format, player, options))
        .collect();
    let all = || paths.iter().flat_map(|p| &p.segments);
    let count = |a: Answer| all().filter(|s| s.answer == a).count();
    let answer = if paths.iter().any(|p| p.answer == Answer::Invalid) {
        Answer::Invalid
    } else if paths.iter().all(|p| p.answer == Answer::Certified) {
        Answer::Certified
    } else {
        Answer::Undecided
    };
    AnimationReport {
        format: anim.format,
        player,
        answer,
        segments: all().count(),
        certified: count(Answer::Certified),
        certified_as_given: all().filter(|s| s.as_given).count(),
        invalid: count(Answer::Invalid),
        undecided: count(Answer::Undecided),
        paths,
        skipped: anim.skipped.clone(),
    }
}

/// Whether a key's shape is valid: with its triangles when given, else by
/// the DP.
fn static_check(
    points: &[crate::geom::Point],
    triangles: Option<&[[u32; 3]]>,
) -> Result<(), String> {
    if let Some(t) = triangles
        && check(points, t).is_ok()
    {
        return Ok(());
    }
    match triangulate_with(points, Quality::Delaunay) {
        Ok(_) => Ok(()),
        Err(e) => Err(format!("not self-overlapping ({e})")),
    }
}

fn certify_path(
    path: &AnimatedPath,
    format: Format,
    player: Player,
    options: MotionOptions,
) -> PathOutcome {
    let segments: Vec<SegmentOutcome> = (0..path.keys.len().saturating_sub(1))
        .into_par_iter()
        .map(|i| certify_one(path, i, format, player, options))
        .collect();
    let last_key = path.keys.last().and_then(|k| {
        let covered = path
            .play
            .last()
            .is_none_or(|p| !matches!(p, Play::NotCovered(_)));
        (covered && k.points.len() >= 3)
            .then(|| static_check(&k.points, k.triangles.as_deref()).err())
            .flatten()
    });
    let answer = if last_key.is_some() || segments.iter().any(|s| s.answer == Answer::Invalid) {
        Answer::Invalid
    } else if segments.iter().all(|s| s.answer == Answer::Certified) {
        Answer::Certified
    } else {
        Answer::Undecided
    };
    PathOutcome {
        name: path.name.clone(),
        keys: path.keys.len(),
        points: path.keys.first().map_or(0, |k| k.points.len()),
        reversed: path.reversed,
        answer,
        segments,
        last_key,
    }
}

fn certify_one(
    path: &AnimatedPath,
    i: usize,
    format: Format,
    player: Player,
    options: MotionOptions,
) -> SegmentOutcome {
    let (a, b) = (&path.keys[i], &path.keys[i + 1]);
    let play = &path.play[i];
    let mut out = SegmentOutcome {
        index: i,
        t0: a.t,
        t1: b.t,
        play: match play {
            Play::Linear => "linear",
            Play::Eased => "eased",
            Play::Hold => "hold",
            Play::NotCovered(_) => "not-covered",
        },
        answer: Answer::Undecided,
        as_given: false,
        pieces: Vec::new(),
        failure: None,
        invalid_at: None,
        certified_up_to: None,
        reason: None,
    };
    if let Play::Hold = play {
        match static_check(&a.points, a.triangles.as_deref()) {
            Ok(()) => out.answer = Answer::Certified,
            Err(why) => {
                out.answer = Answer::Invalid;
                out.invalid_at = Some(SParam::point(0.0));
                out.reason = Some(format!("the held key {why}"));
            }
        }
        return out;
    }
    if a.points.len() < 3 || a.points.len() != b.points.len() {
        out.reason = Some(match play {
            Play::NotCovered(why) => why.clone(),
            _ => format!(
                "keys {i} and {} have {} and {} points: not a straight-line motion",
                i + 1,
                a.points.len(),
                b.points.len()
            ),
        });
        return out;
    }
    let given: Vec<&[[u32; 3]]> = match format {
        Format::ImmerseKeyframes => a.triangles.iter().map(Vec::as_slice).collect(),
        _ => [&a.triangles, &b.triangles]
            .into_iter()
            .flatten()
            .map(Vec::as_slice)
            .collect(),
    };
    let r = certify_motion(&a.points, &b.points, &given, player, options);
    out.failure = r.first_failure.as_ref().map(FailureReport::from);
    match r.verdict {
        Verdict::Certified => {
            out.answer = Answer::Certified;
            out.as_given =
                !given.is_empty() && r.pieces.len() == 1 && r.pieces[0].source == Source::Given(0);
            out.pieces = r.pieces;
        }
        Verdict::Invalid { at } => {
            out.pieces = r.pieces;
            out.answer = Answer::Invalid;
            out.invalid_at = Some(SParam::point(at));
        }
        Verdict::Undecided { reached, reason } => {
            out.pieces = r.pieces;
            out.certified_up_to = Some(reached);
            out.reason = Some(reason);
        }
    }
    if let Play::NotCovered(why) = play
        && out.answer == Answer::Certified
    {
        out.answer = Answer::Undecided;
        out.reason = Some(format!(
            "the keys' straight-line motion is certified, but {why}"
        ));
    }
    out
}
