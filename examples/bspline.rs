//! Uniform cubic B-splines through points: an open curve in the plane and a closed one in
//! space, with their maximum curvature (where an offset or a pipe of radius 1/κmax would
//! start to fold), and a large spline re-solved in place.
//!
//! `cargo run --release --example bspline`

use kappa::{BSpline, BSpline3, Error, Point3};
use kurbo::{Point, Shape};

fn main() -> Result<(), Error> {
    // The paper's set S/T1: a relaxed (open) spline, zero curvature at both ends.
    let points = [
        Point::new(-1.0, 3.0),
        Point::new(-0.2, 1.7),
        Point::new(1.0, 2.75),
        Point::new(2.75, 2.5),
        Point::new(1.75, 1.25),
        Point::new(2.0, 2.5),
        Point::new(3.0, 1.25),
        Point::new(4.0, 0.75),
    ];
    let open = BSpline::relaxed(&points)?;
    let max = open.max_curvature();
    println!(
        "open 2D: {} segments, length {:.6}, κmax = {:.12} at t = {:?} → {:?}",
        open.segment_count(),
        open.arclen(1e-12),
        max.value,
        max.params,
        max.params.iter().map(|&t| open.eval(t)).collect::<Vec<_>>()
    );
    println!(
        "  offsets closer than {:.6} (= 1/κmax) develop no cusps",
        1.0 / max.value
    );
    println!("  as SVG: {}", open.to_bezpath().to_svg());

    // A closed spline through points of a helix-like loop in space.
    let loop3: Vec<Point3> = (0..12)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 12.0;
            Point3::new(a.cos(), a.sin(), 0.3 * (3.0 * a).sin())
        })
        .collect();
    let closed = BSpline3::periodic(&loop3)?;
    let max = closed.max_curvature();
    println!(
        "closed 3D: {} segments, κmax = {:.12}, attained {} times (symmetric data: all reported)",
        closed.segment_count(),
        max.value,
        max.params.len()
    );

    // Many points, re-solved in place (no allocation) after they move.
    let n = 100_000;
    let ring = |phase: f64| -> Vec<Point> {
        (0..n)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / n as f64;
                let r = 100.0 + 5.0 * (7.0 * a + phase).sin();
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect()
    };
    let mut big = BSpline::periodic(&ring(0.0))?;
    let start = std::time::Instant::now();
    big.set_points(&ring(0.5), true)?;
    let solved = start.elapsed();
    let max = big.max_curvature();
    println!(
        "{n} points: re-solved in {solved:?}, κmax = {:.9} at t = {:?}, area {:.3}",
        max.value,
        max.params,
        big.area()
    );
    Ok(())
}
