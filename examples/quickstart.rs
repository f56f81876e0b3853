//! Solve a κ-curve and an εκ-curve through a few points and print them as SVG path data.
//!
//! `cargo run --example quickstart`

use kappa::{Error, Spline};
use kurbo::Point;

fn main() -> Result<(), Error> {
    let points = [
        Point::new(40.0, 160.0),
        Point::new(100.0, 30.0),
        Point::new(170.0, 120.0),
        Point::new(230.0, 40.0),
        Point::new(260.0, 170.0),
    ];
    let kappa = Spline::kappa(&points, true)?;
    println!(
        "κ-curve ({} iterations): {}",
        kappa.iterations(),
        kappa.to_svg()
    );
    let sharp = Spline::ek_cubic(&points, false, 0.9)?;
    println!(
        "open εκ-curve, a = 0.9 ({} iterations): {}",
        sharp.iterations(),
        sharp.to_svg()
    );
    for (i, seg) in kappa.segments().iter().enumerate() {
        println!("segment {i}: curvature peak at t = {:.6}", seg.t_max);
    }
    Ok(())
}
