//! The local linear-reducible scheme (Surazhsky & Gotsman *Controllable
//! Morphing* §4.1) with the optional area improvement (Surazhsky & Gotsman
//! *Controllable Morphing* §4.3).
//!
//! Each interior vertex's star is translated so its centre sits at the origin
//! and morphed on its own: linearly when the linear morph of the star is valid
//! (decided exactly, Surazhsky & Gotsman *Controllable Morphing* Appendix A,
//! see [`super::check_star_linear`]), otherwise by interpolating the polar
//! coordinates of its neighbours (Surazhsky & Gotsman *Controllable Morphing*
//! §4). For the polar morph the neighbours' angles are unwrapped by
//! accumulating the sector angles, so each interpolated sector angle lies
//! between its two end values, in (0, π), and the star stays valid; the common
//! 2π offset is chosen to make the mean rotation smallest. The centre's
//! barycentric coordinates in the morphed star form row `i` of `A(t)`. By
//! Theorem 4.1, when the linear morph of the whole tiling is valid every star
//! is morphed linearly and the result is the linear morph (with weights that
//! reproduce the vertex).

use super::{MeshFrame, MeshMorphError, MeshMorphOptions, Problem, check_star_linear, lerp};
use immerse_base::geom::Point;
use std::f64::consts::TAU;

/// How one star moves.
enum StarMotion {
    /// Neighbours relative to the centre, at t = 0 and t = 1.
    Linear(Vec<Point>, Vec<Point>),
    /// Radii and unwrapped angles at t = 0 and t = 1.
    Polar {
        r0: Vec<f64>,
        r1: Vec<f64>,
        th0: Vec<f64>,
        th1: Vec<f64>,
    },
}

fn unwrapped_angles(rel: &[Point]) -> Vec<f64> {
    let mut th = vec![rel[0].y.atan2(rel[0].x)];
    for j in 1..rel.len() {
        let step = rel[j - 1].perp_dot(rel[j]).atan2(rel[j - 1].dot(rel[j]));
        th.push(th[j - 1] + step);
    }
    th
}

fn star_motion(p: &Problem<'_>, v: u32) -> StarMotion {
    let (c0, c1) = (p.a.points[v as usize], p.b.points[v as usize]);
    let ring0 = p.ring(v, &p.a.points);
    let ring1 = p.ring(v, &p.b.points);
    let rel0: Vec<Point> = ring0.iter().map(|&q| q - c0).collect();
    let rel1: Vec<Point> = ring1.iter().map(|&q| q - c1).collect();
    if check_star_linear(c0, &ring0, c1, &ring1).is_ok() {
        return StarMotion::Linear(rel0, rel1);
    }
    let th0 = unwrapped_angles(&rel0);
    let mut th1 = unwrapped_angles(&rel1);
    let d = th0.len() as f64;
    let mean_diff: f64 = th0.iter().zip(&th1).map(|(a, b)| a - b).sum::<f64>() / d;
    let shift = (mean_diff / TAU).round() * TAU;
    for x in &mut th1 {
        *x += shift;
    }
    StarMotion::Polar {
        r0: rel0.iter().map(|x| x.length()).collect(),
        r1: rel1.iter().map(|x| x.length()).collect(),
        th0,
        th1,
    }
}

/// Rescales the radial edges so every sector's area evolves linearly
/// (Surazhsky & Gotsman *Controllable Morphing* §4.3): sector `j` between edges
/// `j`, `j + 1` with angle γ gets lengths `ā_j s`, `ā_{j+1} s` with
/// `½ ā_j ā_{j+1} s² sin γ = S(t)`, where `ā` are the linearly interpolated
/// lengths and `S(t)` the linearly interpolated area; each edge takes the mean
/// of its two sectors' values.
fn improve_areas(z: &mut [Point], rel0: &[Point], rel1: &[Point], t: f64) {
    let d = z.len();
    let bar: Vec<f64> = (0..d)
        .map(|j| lerp(rel0[j].length(), rel1[j].length(), t))
        .collect();
    let mut sum = vec![0.0; d];
    for j in 0..d {
        let k = (j + 1) % d;
        let target = 0.5 * lerp(rel0[j].perp_dot(rel0[k]), rel1[j].perp_dot(rel1[k]), t);
        let sin_g = z[j].perp_dot(z[k]) / (z[j].length() * z[k].length());
        let s2 = 2.0 * target / (bar[j] * bar[k] * sin_g);
        let s = if s2.is_finite() && s2 > 0.0 {
            s2.sqrt()
        } else {
            1.0
        };
        sum[j] += bar[j] * s;
        sum[k] += bar[k] * s;
    }
    for j in 0..d {
        let len = z[j].length();
        if len > 0.0 && sum[j] > 0.0 {
            z[j] *= 0.5 * sum[j] / len;
        }
    }
}

pub(crate) fn morph(
    p: &Problem<'_>,
    times: &[f64],
    opts: &MeshMorphOptions,
) -> Result<Vec<MeshFrame>, MeshMorphError> {
    let mut solver = p.weight_solver()?;
    let motions: Vec<StarMotion> = p.interior.iter().map(|&v| star_motion(p, v)).collect();
    times
        .iter()
        .map(|&t| {
            let rows: Vec<Vec<f64>> = p
                .interior
                .iter()
                .zip(&motions)
                .map(|(&v, m)| {
                    let mut z: Vec<Point> = match m {
                        StarMotion::Linear(r0, r1) => {
                            r0.iter().zip(r1).map(|(a, b)| a.lerp(*b, t)).collect()
                        }
                        StarMotion::Polar { r0, r1, th0, th1 } => (0..r0.len())
                            .map(|j| {
                                let th = lerp(th0[j], th1[j], t);
                                lerp(r0[j], r1[j], t) * Point::new(th.cos(), th.sin())
                            })
                            .collect(),
                    };
                    if opts.area_improvement {
                        let c0 = p.a.points[v as usize];
                        let c1 = p.b.points[v as usize];
                        let rel0: Vec<Point> =
                            p.ring(v, &p.a.points).iter().map(|&q| q - c0).collect();
                        let rel1: Vec<Point> =
                            p.ring(v, &p.b.points).iter().map(|&q| q - c1).collect();
                        improve_areas(&mut z, &rel0, &rel1, t);
                    }
                    opts.weights.of(Point::ZERO, &z)
                })
                .collect();
            let mut pts = p.boundary_at(t);
            p.solve_weights(&mut solver, &rows, &mut pts)?;
            Ok(p.frame(t, pts))
        })
        .collect()
}
