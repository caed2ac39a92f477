//! Helpers of the unit tests.

use crate::geom::Point;

/// Points from their coordinates.
pub(crate) fn points<const N: usize>(xy: [(f64, f64); N]) -> [Point; N] {
    xy.map(|(x, y)| Point::new(x, y))
}

/// The unit square, counter-clockwise from the origin.
pub(crate) fn unit_square() -> [Point; 4] {
    points([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
}

/// The regular `n`-gon on the unit circle, counter-clockwise from (1, 0).
pub(crate) fn regular_polygon(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            Point::new(a.cos(), a.sin())
        })
        .collect()
}

/// The test kit's xorshift64 stream from `seed`, uniform in [0, 1).
pub(crate) fn unit_rng(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed | 1;
    move || testkit::rng::unit_from_bits(testkit::rng::xorshift64(&mut s))
}

/// `rounds` rounds on random points of a grid, drawn from
/// [`unit_rng`]`(seed)`: each round draws its point count `least + ⌊r ×
/// spread⌋`, then the grid's side (`coarse` in every `every`-th round from
/// the first, else 1000), then hands `round` the count and a source of
/// points on that grid (each coordinate `⌊r × side⌋`). `round` answers yes
/// (`Some(true)`), no (`Some(false)`) or that the round does not count
/// (`None`); the yes and no answers are counted.
pub(crate) fn grid_rounds(
    seed: u64,
    rounds: usize,
    (least, spread): (usize, f64),
    (every, coarse): (usize, f64),
    mut round: impl FnMut(usize, &mut dyn FnMut() -> Point) -> Option<bool>,
) -> (usize, usize) {
    let mut r = unit_rng(seed);
    let (mut yes, mut no) = (0, 0);
    for i in 0..rounds {
        let n = least + (r() * spread) as usize;
        let g = if i % every == 0 { coarse } else { 1000.0 };
        let mut point = || Point::new((r() * g).floor(), (r() * g).floor());
        match round(n, &mut point) {
            Some(true) => yes += 1,
            Some(false) => no += 1,
            None => {}
        }
    }
    (yes, no)
}
