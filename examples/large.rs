//! Solve a closed star loop of many points (radii alternating 100 and 90) and report the time:
//! `cargo run --release --example large -- 100000 kappa`.

use kappa::{Scheme, Shape, Solver};
use kurbo::Point;
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let (scheme, shape) = match args.next().as_deref() {
        Some("kappa") => (Scheme::Kappa, Shape::Neutral),
        _ => (Scheme::EkCubic, Shape::Global(0.85)),
    };
    let points: Vec<Point> = (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 100.0 } else { 90.0 };
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect();
    let start = Instant::now();
    match Solver::new().solve(&points, true, scheme, &shape) {
        Ok(s) => println!(
            "{n} points, {scheme:?}: {:?} in {:.3?}",
            s.report(),
            start.elapsed()
        ),
        Err(e) => println!("{n} points, {scheme:?}: {e} after {:.3?}", start.elapsed()),
    }
}
