//! What the tests, benchmarks and examples of the immerse workspace share,
//! so that each exists once: the seeded random generator ([`Rng`]), the
//! curve generators ([`shapes`], and the stress families in [`stress`]),
//! the stress driver and shrinker ([`stress`]), the pair lists of
//! `curves/` ([`pairs`]), the pacing measures ([`pacing`]), a running
//! `immerse serve` with a loopback client ([`serve`]) and the independent
//! exact checker of a straight-line segment ([`exact_check`]); with the
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

/// The workspace's root folder (where `curves/` and `tests/` are).
pub fn workspace_root() -> std::path::PathBuf {
    let kit = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    kit.parent().unwrap_or(kit).to_path_buf()
}
