//! Morphing two curves, in the stages of docs/design.md §5–§7, each a room
//! of its own, data flowing one way (each stage uses only those listed
//! after it):
//!
//! - [`Tween`] (`tween`): the front door; a morph's certified keys and its
//!   frames at any t.
//! - `plan`: equal counts, correspondences, triangulations, the two sides
//!   of the staged route raced, the best plan kept.
//! - `output`: what a morph gives ([`Frame`], [`Morph`]) and its JSON.
//! - `measure`: the measures of motion a viewer sees (docs/design.md §7b,
//!   §7c), which the planner holds its routes to; `crate::frames`
//!   re-exports them.
//!
//! Below this module, two rooms of the crate's own, whose public items it
//! re-exports: `crate::staged`, the staged route (legs toward
//! intermediates, flips at the keys between legs; [`Fallback`],
//! [`Intermediate`]), and below it `crate::propagate`, one compatible
//! morph under a fixed triangulation, laid out along the dual tree
//! ([`Compatible`], [`ThirdVertexPath`], [`MorphError`]). Flip sequences
//! and the flip gate live in the crate's `flip` module.

pub(crate) mod measure;
pub(crate) mod output;
mod plan;
mod tween;

pub use crate::propagate::MorphError;
pub(crate) use crate::propagate::compatible::DEFAULT_FAN_MARGIN;
pub use crate::propagate::compatible::{Compatible, CompatibleError, area_and_centroid, lay_out};
pub use crate::propagate::paths::ThirdVertexPath;
pub(crate) use crate::staged::Staged;
pub use crate::staged::{Fallback, Intermediate};
pub use output::{Frame, Morph};
pub use plan::{
    Correspondence, Counts, CurveMorphError, CurveMorphOptions, KEY_TOLERANCE, MorphReport, Side,
};
pub(crate) use tween::strictly_increasing;
pub use tween::{Keyframe, Tween, timed_keyframes};

use crate::immersion::CheckedTriangles;
use crate::tree::RootChoice;

/// Options of a morph.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct MorphOptions {
    /// The third-vertex path. Default: [`ThirdVertexPath::Rigid`].
    pub path: ThirdVertexPath,
    /// The root of the propagation. Default: [`RootChoice::Disk`].
    pub root: RootChoice,
    /// Margin ε (radians) the hybrid path keeps below 2π in every vertex
    /// fan. Default: 0.05.
    pub fan_margin: f64,
    /// Whether the last leg races the other paths against `path`
    /// (docs/design.md §7c); false where [`Tween::new`] plans one path
    /// alone to certify the keys (§13).
    pub(crate) rivals: bool,
}

impl MorphOptions {
    /// The defaults.
    pub const DEFAULT: MorphOptions = MorphOptions {
        path: ThirdVertexPath::Rigid,
        root: RootChoice::Disk,
        fan_margin: DEFAULT_FAN_MARGIN,
        rivals: true,
    };
}

crate::options::setters! {
    MorphOptions: Default {
        /// Sets the third-vertex path.
        fn with_path(path: ThirdVertexPath);
        /// Sets the fan margin ε.
        fn with_fan_margin(fan_margin: f64);
    }
}

impl Compatible {
    /// The frames of this pair's morph along `path`, one per value in
    /// `times` (the pair shares one triangulation: [`Compatible::new`]).
    ///
    /// Every frame is checked with the exact immersion test before it is
    /// returned. When the requested path is not guaranteed (`linear`,
    /// `rotate-slide`) and any frame fails, the whole morph is recomputed
    /// with the guaranteed paths in turn, and [`Morph::fallback`] is set.
    /// End frames (t = 0 and t = 1) are the inputs exactly.
    ///
    /// # Errors
    ///
    /// [`MorphError::InvalidFrame`] (a bug) when a guaranteed path produced
    /// an invalid frame.
    pub fn morph(&self, times: &[f64], path: ThirdVertexPath) -> Result<Morph, MorphError> {
        use rayon::prelude::*;
        let plan = self;
        let tris = plan.triangles();
        // Every frame shares the plan's triangulation: its combinatorics
        // are checked once, and each frame's triangles as it is computed,
        // the frames on every core.
        let checked = CheckedTriangles::new(plan.source().len(), tris);
        let build = |path: ThirdVertexPath| -> Result<Vec<Frame>, (f64, String)> {
            let frames: Vec<Result<Frame, (f64, String)>> = times
                .par_iter()
                .map(|&t| {
                    let points = plan.positions(t, path);
                    checked
                        .check(&points)
                        .map_err(|defect| (t, defect.to_string()))?;
                    Ok(Frame {
                        t,
                        points,
                        triangles: tris.to_vec(),
                    })
                })
                .collect();
            // The first failure in time order, as when checked one by one.
            frames.into_iter().collect()
        };
        let mut fallbacks = Vec::new();
        let mut last = (0.0, String::new());
        for (k, p) in crate::staged::recovery_paths(path).into_iter().enumerate() {
            if k > 0 && !p.is_guaranteed() {
                continue;
            }
            match build(p) {
                // Every path before the k-th failed and left a fallback.
                Ok(frames) => {
                    fallbacks.extend(crate::staged::guide_fallback(
                        plan.has_rigid_guide(),
                        p,
                        "the morph",
                    ));
                    return Ok(Morph::new(vec![p], fallbacks, frames));
                }
                Err((t, defect)) => {
                    fallbacks.push(Fallback::new(
                        &format!("did not use the {p} path"),
                        &format!("its frame at t = {t} is not an immersion ({defect})"),
                    ));
                    last = (t, defect);
                }
            }
        }
        Err(MorphError::InvalidFrame {
            t: last.0,
            path,
            defect: last.1,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_recovered_failure_is_not_reported_as_a_bug() {
        let e = MorphError::InvalidFrame {
            t: 0.25,
            path: ThirdVertexPath::Hybrid,
            defect: "triangle 3 is clockwise".into(),
        };
        assert!(e.to_string().contains("this is a bug"));
        let why = e.reason();
        assert!(!why.contains("bug"), "{why}");
        assert!(why.contains("t = 0.25") && why.contains("hybrid") && why.contains("triangle 3"));
        assert_eq!(
            MorphError::Fraction(2.0).reason(),
            MorphError::Fraction(2.0).to_string()
        );
    }
}
