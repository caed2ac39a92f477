//! What the tests, benchmarks and examples of the immerse workspace share,
//! so that each exists once: the seeded random generator ([`Rng`]), the
//! curve generators ([`shapes`], and the stress families in [`stress`]),
//! the stress driver and shrinker ([`stress`]), the pair lists of
//! `curves/` ([`pairs`]), the pacing measures ([`pacing`]), a running
//! `immerse serve` with a loopback client ([`serve`]) and the independent
//! exact checker of a straight-line segment ([`exact_check`]), and
//! [`morph_pair`], a whole curve morph in one call; with the
//! `render` feature, the render crate's synthetic morph (`synth`).
//!
//! A development crate: never published, never a dependency of a library.
//! Without its default `immerse` feature it holds only what needs no more
//! than `immerse-base` ([`Rng`], [`shapes`], [`pairs`], [`exact_check`]).

pub mod exact_check;
pub mod pairs;
pub mod rng;
pub mod shapes;

#[cfg(feature = "immerse")]
pub mod pacing;
#[cfg(feature = "immerse")]
pub mod serve;
#[cfg(feature = "immerse")]
pub mod stress;
#[cfg(feature = "render")]
pub mod synth;

pub use rng::Rng;

/// A curve morph at `fractions` in one call, as the tests and measuring
/// examples want it: [`immerse::Tween::new`], then
/// [`immerse::Tween::morph`], with the plan's report whose fallbacks are
/// the morph's (the plan's and those of the frames).
///
/// # Errors
///
/// As [`immerse::Tween::new`] and [`immerse::Tween::morph`].
#[cfg(feature = "immerse")]
pub fn morph_pair(
    a: &[immerse::Point],
    b: &[immerse::Point],
    fractions: &[f64],
    options: &immerse::CurveMorphOptions,
) -> Result<(immerse::morph::MorphReport, immerse::morph::Morph), immerse::morph::CurveMorphError> {
    let tween = immerse::Tween::new(a, b, options)?;
    let morph = tween.morph(fractions)?;
    let mut report = tween.report().clone();
    report.fallbacks.clone_from(&morph.fallbacks);
    Ok((report, morph))
}

/// The workspace's root folder (where `curves/` and `tests/` are).
pub fn workspace_root() -> std::path::PathBuf {
    let kit = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    kit.parent().unwrap_or(kit).to_path_buf()
}
