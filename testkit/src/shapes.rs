//! Curves that the tests, benchmarks and examples generate, so that every
//! table measures the same shapes.

use immerse_base::geom::Point;
use std::f64::consts::TAU;

/// The least and greatest corner of the bounding box of `points`
/// (infinite corners for no points).
pub fn bounds(points: &[Point]) -> (Point, Point) {
    points.iter().fold(
        (Point::splat(f64::INFINITY), Point::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// A star-shaped blob of `n` vertices about the origin, radius 1.2 ± 30 %
/// (the benchmarks' blob, counter-clockwise).
pub fn star_blob(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let f = TAU * i as f64 / n as f64;
            let r = 1.2 * (1.0 + 0.2 * (3.0 * f + 0.4).cos() + 0.1 * (5.0 * f + 1.3).cos());
            Point::from_angle(f) * r
        })
        .collect()
}

/// A spiral strip of `m` stations curling `turns` times with the given
/// width (outer edge out, inner edge back, n = 2m vertices) and its zigzag
/// triangulation: an immersed disk for any number of turns; it overlaps
/// itself once the width is more than the radius gained in a turn (0.12).
pub fn spiral_strip(m: usize, turns: f64, width: f64) -> (Vec<Point>, Vec<[u32; 3]>) {
    let station = |i: usize| {
        let th = turns * TAU * i as f64 / (m - 1) as f64;
        (th, 1.0 + 0.12 * th / TAU)
    };
    let mut pts: Vec<Point> = (0..m)
        .map(|i| {
            let (th, r) = station(i);
            Point::from_angle(th) * (r + width / 2.0)
        })
        .collect();
    pts.extend((0..m).rev().map(|i| {
        let (th, r) = station(i);
        Point::from_angle(th) * (r - width / 2.0)
    }));
    let n = 2 * m as u32;
    let tris = (0..(m as u32 - 1))
        .flat_map(|i| [[i, i + 1, n - 1 - i], [i + 1, n - 2 - i, n - 1 - i]])
        .collect();
    (pts, tris)
}

/// A wide spiral strip of `n` vertices (n even) turning `turns` times
/// whose turns do not touch (a simple polygon): the decision DP's
/// benchmark shape.
pub fn wide_spiral(n: usize, turns: f64) -> Vec<Point> {
    let half = n / 2;
    let at = |i: usize, r0: f64| {
        let a = i as f64 / (half - 1) as f64 * turns * TAU;
        let r = r0 + 0.25 * a;
        Point::new(r * a.cos(), r * a.sin())
    };
    let mut pts: Vec<Point> = (0..half).map(|i| at(i, 2.0)).collect();
    pts.extend((0..half).rev().map(|i| at(i, 1.0)));
    pts
}
