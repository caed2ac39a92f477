//! The bodies of immerse's fuzz targets, shared by the libFuzzer binaries
//! in `fuzz_targets/` (nightly, `cargo fuzz run TARGET`) and by the stable
//! driver in this crate's tests (`cargo test --release`), which runs them
//! over the seeds in `seeds/`, the project's `curves/`, and fixed-seed
//! random and mutated inputs. See README.md.
//!
//! Each body drops nothing silently: every input either is rejected with
//! an error (no panic) or yields a value whose documented invariants are
//! asserted here.

use arbitrary::Unstructured;
use immerse::curve::{Curve, Format, MAX_COORDINATE, MAX_POINTS, MIN_COORDINATE};
use immerse::geom::polygon::{Turning, turning_number};
use immerse::geom::{Orientation, Point, orient};
use immerse::{NotSelfOverlapping, check, is_valid_triangle, triangulate};
use immerse::{improve, triangulate_maxmin};

/// Most points [`check_points`] builds: the DP, the max–min DP and the
/// exhaustive comparison stay well under a millisecond at this size.
pub const MAX_FUZZ_POINTS: usize = 14;

/// Exhaustive comparison with the DP up to this many points.
const BRUTE_FORCE_POINTS: usize = 8;

/// Fuzz target `curve_json`.
pub fn curve_json(data: &[u8]) {
    curve_bytes(data, Format::Json);
}

/// Fuzz target `curve_text`.
pub fn curve_text(data: &[u8]) {
    curve_bytes(data, Format::Text);
}

/// Fuzz target `curve_svg`.
pub fn curve_svg(data: &[u8]) {
    curve_bytes(data, Format::Svg);
}

/// Parses `data` as a curve in `format`; an error is fine (it must not
/// panic), an accepted curve must keep the invariants of [`Curve`].
pub fn curve_bytes(data: &[u8], format: Format) {
    match Curve::from_bytes(data, format, "fuzz", "fuzz") {
        Ok(curve) => assert_curve_invariants(&curve),
        Err(e) => {
            // Every message names the source and is one line.
            let msg = e.to_string();
            assert!(msg.starts_with("fuzz"), "{msg}");
            assert!(!msg.chars().any(char::is_control), "one printable line: {msg:?}");
        }
    }
}

/// The invariants the `immerse::curve` module documents for a [`Curve`].
///
/// # Panics
///
/// When one is broken: that is a bug in the reader or the cleaner.
pub fn assert_curve_invariants(c: &Curve) {
    let p = &c.points;
    let n = p.len();
    assert!(n >= 3, "a curve has at least 3 points, got {n}");
    assert!(n <= MAX_POINTS, "{n} points exceed MAX_POINTS");
    for (i, q) in p.iter().enumerate() {
        for v in [q.x, q.y] {
            assert!(v.is_finite(), "point {i} is not finite: {q:?}");
            let a = v.abs();
            assert!(
                a <= MAX_COORDINATE && (a == 0.0 || a >= MIN_COORDINATE),
                "point {i} out of range: {q:?}"
            );
        }
        assert_ne!(*q, p[(i + 1) % n], "points {i} and its successor repeat");
    }
    let mut distinct = p.clone();
    distinct.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    distinct.dedup();
    assert!(distinct.len() >= 3, "fewer than 3 distinct points");
    let a = p[0];
    let b = *p.iter().find(|&&q| q != a).expect("distinct points");
    assert!(
        p.iter().any(|&q| orient(a, b, q) != Orientation::Collinear),
        "all points on one line"
    );
    let now = turning_number(p);
    if c.reversed {
        assert_eq!(c.turning_as_given, Turning::Number(-1));
        assert_eq!(now, Turning::Number(1), "a reversed curve turns +1");
    } else {
        assert_ne!(c.turning_as_given, Turning::Number(-1), "not reversed");
        assert_eq!(now, c.turning_as_given, "turning number as given");
    }
    assert_eq!(c.turning_number(), Some(now).and_then(|t| match t {
        Turning::Number(k) => Some(k),
        Turning::Cusp(_) => None,
    }));
}

/// Fuzz target `check_points`: decodes a small point list ([`points_from`])
/// and triangulates it three ways. Every triangulation returned must pass
/// [`check`]; the DP and the max–min DP must agree on the answer; up to
/// eight points, the answer must agree with exhaustive search.
pub fn check_points(data: &[u8]) {
    let points = points_from(data);
    let dp = triangulate(&points);
    if let Ok(imm) = &dp {
        assert_eq!(imm.points, points);
        assert_eq!(check(&imm.points, &imm.triangles), Ok(()), "DP: {points:?}");
        let better = improve(imm.clone());
        assert_eq!(better.points, points);
        assert_eq!(
            check(&better.points, &better.triangles),
            Ok(()),
            "improve: {points:?}"
        );
    }
    let best = triangulate_maxmin(&points);
    if let Ok(imm) = &best {
        assert_eq!(
            check(&imm.points, &imm.triangles),
            Ok(()),
            "maxmin: {points:?}"
        );
    }
    assert_eq!(
        dp.as_ref().err(),
        best.as_ref().err(),
        "DP and max-min DP disagree on {points:?}"
    );
    if let Err(NotSelfOverlapping::OutOfRange(i)) = dp {
        // Outside the predicates' exact range nothing is decided.
        assert!(i < points.len());
        return;
    }
    if (3..=BRUTE_FORCE_POINTS).contains(&points.len())
        && turning_number(&points) == Turning::Number(1)
    {
        assert_eq!(
            dp.is_ok(),
            brute(&points, 0, points.len() - 1),
            "DP disagrees with exhaustive search on {points:?}"
        );
    }
}

/// Is there a triangulation of the chain `i..=j` by valid triangles?
fn brute(points: &[Point], i: usize, j: usize) -> bool {
    j == i + 1
        || (i + 1..j).any(|k| {
            is_valid_triangle(points, i, k, j) && brute(points, i, k) && brute(points, k, j)
        })
}

/// Decodes up to [`MAX_FUZZ_POINTS`] points. The first byte picks the
/// kind of coordinates (a 9×9 grid full of collinear and repeated points;
/// 16-bit integers; raw `f64` bits, NaN and infinities included; the grid
/// moved by a few ULPs, for near-duplicates), the second the count.
pub fn points_from(data: &[u8]) -> Vec<Point> {
    let mut u = Unstructured::new(data);
    let mode = u.arbitrary::<u8>().unwrap_or(0) % 4;
    let n = usize::from(u.arbitrary::<u8>().unwrap_or(0)) % (MAX_FUZZ_POINTS + 1);
    let coord = |u: &mut Unstructured<'_>| -> f64 {
        let grid = |b: u8| f64::from(b % 9) - 4.0;
        match mode {
            0 => grid(u.arbitrary().unwrap_or(0)),
            1 => f64::from(u.arbitrary::<i16>().unwrap_or(0)),
            2 => f64::from_bits(u.arbitrary().unwrap_or(0)),
            _ => {
                let v = grid(u.arbitrary().unwrap_or(0));
                let ulps = i64::from(u.arbitrary::<u8>().unwrap_or(0) % 7) - 3;
                if v == 0.0 {
                    f64::from_bits(ulps.unsigned_abs()) * ulps.signum() as f64
                } else {
                    f64::from_bits(v.to_bits().wrapping_add_signed(ulps))
                }
            }
        }
    };
    (0..n)
        .map(|_| {
            let x = coord(&mut u);
            Point::new(x, coord(&mut u))
        })
        .collect()
}

/// A small deterministic generator (xorshift64) for the stable driver.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a non-zero seed.
    pub fn new(seed: u64) -> Rng {
        Rng(seed | 1)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number below `k` (`k > 0`).
    pub fn below(&mut self, k: usize) -> usize {
        (self.next_u64() % k as u64) as usize
    }
}

/// Tokens the mutator splices in: syntax of the three formats and numbers
/// at the edges of the accepted range.
const DICTIONARY: &[&str] = &[
    "[", "]", "{", "}", ",", "\"points\":", "\"name\":", "null", "1e30", "1e31", "1e-30",
    "1e-31", "-0", "NaN", "nan", "inf", "-inf", "1e400", "0.5", "#", "\n", " ", "<svg>",
    "</svg>", "<path d=\"", "\"/>", "M", "L", "Q", "C", "A", "Z", "z", "<polygon points=\"",
    "<rect width=\"1\" height=\"1\"/>", "<circle r=\"1\"/>", "transform=\"scale(0)\"",
    "transform=\"rotate(45)\"", "<g>", "</g>", "1e38", "3.4e38",
];

/// One mutation of `input`: flip, insert, delete, duplicate, truncate or
/// splice a dictionary token, applied one to four times.
pub fn mutate(input: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut v = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let len = v.len();
        match rng.below(6) {
            0 if len > 0 => {
                let i = rng.below(len);
                v[i] ^= 1 << rng.below(8);
            }
            1 => {
                let i = rng.below(len + 1);
                v.insert(i, rng.next_u64() as u8);
            }
            2 if len > 0 => {
                let i = rng.below(len);
                let j = (i + 1 + rng.below(8)).min(len);
                v.drain(i..j);
            }
            3 if len > 0 => {
                let i = rng.below(len);
                let j = (i + 1 + rng.below(32)).min(len);
                let chunk = v[i..j].to_vec();
                let at = rng.below(len + 1);
                v.splice(at..at, chunk);
            }
            4 if len > 0 => v.truncate(rng.below(len)),
            _ => {
                let token = DICTIONARY[rng.below(DICTIONARY.len())].as_bytes();
                let at = rng.below(len + 1);
                v.splice(at..at, token.iter().copied());
            }
        }
    }
    v
}

#[cfg(test)]
mod stable;
