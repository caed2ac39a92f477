//! [`Easing`] curves with CSS semantics, and [`frame_times`].
//!
//! A CSS `cubic-bezier(x1, y1, x2, y2)` is the Bézier curve through
//! `(0,0), (x1,y1), (x2,y2), (1,1)`; the eased value of `x` is `y(s)` where
//! `x(s) = x`. Because `x1, x2 ∈ [0, 1]`, `x(s)` is non-decreasing, so the
//! root is unique; we take Newton steps from `s = x` and fall back to
//! bisection whenever a step would leave the bracket.

use std::fmt;
use std::str::FromStr;

use crate::RenderError;

/// How time advances across the frames of an animation, as in CSS
/// `transition-timing-function`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Easing {
    /// Constant speed.
    Linear,
    /// Starts slowly: `cubic-bezier(0.42, 0, 1, 1)`.
    EaseIn,
    /// Ends slowly: `cubic-bezier(0, 0, 0.58, 1)`.
    EaseOut,
    /// Starts and ends slowly: `cubic-bezier(0.42, 0, 0.58, 1)`.
    EaseInOut,
    /// `cubic-bezier(x1, y1, x2, y2)`; `x1` and `x2` should lie in `[0, 1]`
    /// ([`Easing::cubic_bezier`] checks this, [`Easing::apply`] clamps them).
    CubicBezier(f64, f64, f64, f64),
}

/// Error of the Newton/bisection solve on `x`.
const X_TOLERANCE: f64 = 1e-12;

impl Easing {
    /// The easings known by name, as they parse; `cubic-bezier(x1,y1,x2,y2)`
    /// gives any other.
    pub const NAMES: [&'static str; 5] = ["linear", "ease", "ease-in", "ease-out", "ease-in-out"];

    /// A checked [`Easing::CubicBezier`].
    ///
    /// # Errors
    ///
    /// [`RenderError::BadEasing`] when a parameter is not finite or `x1`,
    /// `x2` lie outside `[0, 1]`.
    pub fn cubic_bezier(x1: f64, y1: f64, x2: f64, y2: f64) -> Result<Easing, RenderError> {
        let bad = |reason: &str| RenderError::BadEasing {
            input: format!("cubic-bezier({x1},{y1},{x2},{y2})"),
            reason: reason.into(),
        };
        if ![x1, y1, x2, y2].iter().all(|v| v.is_finite()) {
            return Err(bad("parameters must be finite numbers"));
        }
        if !(0.0..=1.0).contains(&x1) || !(0.0..=1.0).contains(&x2) {
            return Err(bad("x1 and x2 must lie in [0,1]"));
        }
        Ok(Easing::CubicBezier(x1, y1, x2, y2))
    }

    /// The control points `(x1, y1, x2, y2)` of this easing.
    pub fn control_points(&self) -> (f64, f64, f64, f64) {
        match *self {
            Easing::Linear => (0.0, 0.0, 1.0, 1.0),
            Easing::EaseIn => (0.42, 0.0, 1.0, 1.0),
            Easing::EaseOut => (0.0, 0.0, 0.58, 1.0),
            Easing::EaseInOut => (0.42, 0.0, 0.58, 1.0),
            Easing::CubicBezier(a, b, c, d) => (a, b, c, d),
        }
    }

    /// The eased value of `x`. `x` is clamped to `[0, 1]` (NaN counts as 0),
    /// so `apply(0) = 0` and `apply(1) = 1`; in between the result may leave
    /// `[0, 1]` when `y1` or `y2` do (overshoot).
    ///
    /// # Examples
    ///
    /// ```
    /// use immerse_render::Easing;
    ///
    /// assert_eq!(Easing::Linear.apply(0.25), 0.25);
    /// assert!(Easing::EaseIn.apply(0.25) < 0.25);
    /// assert!((Easing::EaseInOut.apply(0.5) - 0.5).abs() < 1e-9);
    /// ```
    pub fn apply(&self, x: f64) -> f64 {
        let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        if x == 0.0 || x == 1.0 || *self == Easing::Linear {
            return x;
        }
        let (x1, y1, x2, y2) = self.control_points();
        let clamp01 = |v: f64| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let (x1, x2) = (clamp01(x1), clamp01(x2));
        let s = solve(x1, x2, x);
        let y = bezier(y1, y2, s);
        if y.is_finite() { y } else { x }
    }
}

/// One coordinate of the Bézier with end values 0 and 1.
fn bezier(p1: f64, p2: f64, s: f64) -> f64 {
    let u = 1.0 - s;
    3.0 * u * u * s * p1 + 3.0 * u * s * s * p2 + s * s * s
}

fn bezier_slope(p1: f64, p2: f64, s: f64) -> f64 {
    let u = 1.0 - s;
    3.0 * u * u * p1 + 6.0 * u * s * (p2 - p1) + 3.0 * s * s * (1.0 - p2)
}

/// The `s ∈ [0, 1]` with `x(s) = x` (x(s) is non-decreasing).
fn solve(x1: f64, x2: f64, x: f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut s = x;
    for _ in 0..100 {
        let err = bezier(x1, x2, s) - x;
        if err.abs() < X_TOLERANCE {
            return s;
        }
        if err < 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let slope = bezier_slope(x1, x2, s);
        let newton = s - err / slope;
        s = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi <= lo + f64::EPSILON {
            break;
        }
    }
    s
}

/// The CSS name: `linear`, `ease-in`, ... or `cubic-bezier(x1,y1,x2,y2)`.
impl fmt::Display for Easing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Easing::Linear => f.write_str("linear"),
            Easing::EaseIn => f.write_str("ease-in"),
            Easing::EaseOut => f.write_str("ease-out"),
            Easing::EaseInOut => f.write_str("ease-in-out"),
            Easing::CubicBezier(a, b, c, d) => write!(f, "cubic-bezier({a},{b},{c},{d})"),
        }
    }
}

/// Parses `linear`, `ease`, `ease-in`, `ease-out`, `ease-in-out` or
/// `cubic-bezier(x1,y1,x2,y2)` (case-insensitive, spaces allowed). `ease` is
/// CSS's `cubic-bezier(0.25,0.1,0.25,1)`.
///
/// # Examples
///
/// ```
/// use immerse_render::Easing;
///
/// assert_eq!("ease-in".parse::<Easing>()?, Easing::EaseIn);
/// assert_eq!(
///     "cubic-bezier(0.1, 0.7, 1.0, 0.1)".parse::<Easing>()?,
///     Easing::CubicBezier(0.1, 0.7, 1.0, 0.1)
/// );
/// assert!("cubic-bezier(2,0,1,1)".parse::<Easing>().is_err());
/// # Ok::<(), immerse_render::RenderError>(())
/// ```
impl FromStr for Easing {
    type Err = RenderError;

    fn from_str(input: &str) -> Result<Easing, RenderError> {
        let bad = |reason: &str| RenderError::BadEasing {
            input: input.into(),
            reason: reason.into(),
        };
        let s = input.trim().to_ascii_lowercase();
        match s.as_str() {
            "linear" => return Ok(Easing::Linear),
            "ease" => return Ok(Easing::CubicBezier(0.25, 0.1, 0.25, 1.0)),
            "ease-in" => return Ok(Easing::EaseIn),
            "ease-out" => return Ok(Easing::EaseOut),
            "ease-in-out" => return Ok(Easing::EaseInOut),
            _ => {}
        }
        let Some(args) = s
            .strip_prefix("cubic-bezier")
            .map(str::trim_start)
            .and_then(|r| r.strip_prefix('('))
            .and_then(|r| r.trim_end().strip_suffix(')'))
        else {
            return Err(bad("unknown name"));
        };
        let nums = args
            .split(',')
            .map(|a| {
                let a = a.trim();
                a.parse::<f64>()
                    .map_err(|_| bad(&format!("'{a}' is not a number")))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        let [x1, y1, x2, y2] = nums[..] else {
            return Err(bad(&format!("needs 4 numbers, found {}", nums.len())));
        };
        Easing::cubic_bezier(x1, y1, x2, y2).map_err(|e| match e {
            RenderError::BadEasing { reason, .. } => bad(&reason),
            other => other,
        })
    }
}

/// The animation time of each of `frames` frames: frame `i` of `N` gets
/// `easing.apply(i / (N - 1))`, so the first is 0 and the last 1. One frame
/// gives `[0]`, none gives `[]`.
///
/// # Examples
///
/// ```
/// use immerse_render::{frame_times, Easing};
///
/// assert_eq!(frame_times(3, &Easing::Linear), vec![0.0, 0.5, 1.0]);
/// assert_eq!(frame_times(1, &Easing::EaseIn), vec![0.0]);
/// ```
pub fn frame_times(frames: usize, easing: &Easing) -> Vec<f64> {
    match frames {
        0 => Vec::new(),
        1 => vec![0.0],
        n => (0..n)
            .map(|i| easing.apply(i as f64 / (n - 1) as f64))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Easing; 6] = [
        Easing::Linear,
        Easing::EaseIn,
        Easing::EaseOut,
        Easing::EaseInOut,
        Easing::CubicBezier(0.1, -0.5, 0.9, 1.5),
        Easing::CubicBezier(1.0, 0.0, 0.0, 1.0),
    ];

    #[test]
    fn every_name_parses_and_others_do_not() {
        for name in Easing::NAMES {
            let e: Easing = name.parse().unwrap();
            // A named easing prints as its name, except `ease`, which has
            // no variant of its own.
            if name != "ease" {
                assert_eq!(e.to_string(), name);
            }
        }
        assert!("ease-sideways".parse::<Easing>().is_err());
    }

    #[test]
    fn endpoints_are_fixed() {
        for e in ALL {
            assert_eq!(e.apply(0.0), 0.0, "{e}");
            assert_eq!(e.apply(1.0), 1.0, "{e}");
            assert_eq!(e.apply(-3.0), 0.0, "{e}");
            assert_eq!(e.apply(f64::NAN), 0.0, "{e}");
        }
    }

    #[test]
    fn monotone_when_y_in_unit_interval() {
        for e in [
            Easing::EaseIn,
            Easing::EaseOut,
            Easing::EaseInOut,
            Easing::CubicBezier(1.0, 0.0, 0.0, 1.0),
            Easing::CubicBezier(0.0, 1.0, 1.0, 0.0),
        ] {
            let mut prev = 0.0;
            for i in 0..=2000 {
                let y = e.apply(f64::from(i) / 2000.0);
                assert!(y >= prev - 1e-12, "{e} at {i}");
                prev = y;
            }
        }
    }

    #[test]
    fn ease_in_out_is_symmetric() {
        for i in 0..=100 {
            let x = f64::from(i) / 100.0;
            let a = Easing::EaseInOut.apply(x);
            let b = Easing::EaseInOut.apply(1.0 - x);
            assert!((a + b - 1.0).abs() < 1e-9, "{x}");
        }
    }

    #[test]
    fn diagonal_bezier_is_linear_and_solve_is_accurate() {
        let e = Easing::CubicBezier(0.0, 0.0, 1.0, 1.0);
        for i in 0..=100 {
            let x = f64::from(i) / 100.0;
            assert!((e.apply(x) - x).abs() < 1e-9);
        }
        // Flat spots in x(s) (x1 = 1, x2 = 0 has x'(1/2) = 0 ... and x1 = x2 = 0
        // has x'(0) = 0) must not break the solve.
        for (x1, x2) in [(1.0, 0.0), (0.0, 0.0), (1.0, 1.0)] {
            for i in 1..100 {
                let x = f64::from(i) / 100.0;
                let s = solve(x1, x2, x);
                assert!((bezier(x1, x2, s) - x).abs() < 1e-9, "{x1} {x2} {x}");
            }
        }
    }

    #[test]
    fn parse_round_trips_and_rejects() {
        for e in ALL {
            assert_eq!(e.to_string().parse::<Easing>().unwrap(), e);
        }
        assert_eq!(
            " Ease-In-Out ".parse::<Easing>().unwrap(),
            Easing::EaseInOut
        );
        for bad in [
            "",
            "bounce",
            "cubic-bezier(",
            "cubic-bezier(0,0,1)",
            "cubic-bezier(0,0,1,1,1)",
            "cubic-bezier(0,x,1,1)",
            "cubic-bezier(-0.1,0,1,1)",
            "cubic-bezier(0,0,1.5,1)",
            "cubic-bezier(nan,0,1,1)",
            "cubic-bezier(0,inf,1,1)",
        ] {
            let err = bad.parse::<Easing>().unwrap_err();
            assert!(err.to_string().contains("expected linear"), "{err}");
        }
    }

    #[test]
    fn times() {
        assert!(frame_times(0, &Easing::Linear).is_empty());
        let t = frame_times(5, &Easing::EaseInOut);
        assert_eq!((t[0], t[4]), (0.0, 1.0));
        assert!((t[2] - 0.5).abs() < 1e-9);
    }
}
