//! Convergence rates on clicks on whole pixels: random walks on an integer grid, 4–40
//! clicks, steps of up to 5 units each way, open and closed; or, with `pixels`, the
//! whole-pixel samples of circles, lemniscates, spirals and sines (the generators of
//! `tests/integer_input.rs`, in `tests/common/walks.rs`).
//!
//! ```text
//! cargo run --release --example walks -- [count] [seed]
//! cargo run --release --example walks -- pixels
//! ```
//!
//! Prints each failure (scheme, case, residual, time, points) and the rate per scheme, with
//! the default solver options. The rates are in docs/curves.md, "Known limits".

use kappa::{Error, Scheme, Shape, Solver};

#[path = "../tests/common/walks.rs"]
mod walks;

fn arg<T: std::str::FromStr>(args: &[String], i: usize, default: T) -> Result<T, String> {
    args.get(i).map_or(Ok(default), |s| {
        s.parse()
            .map_err(|_| format!("argument {i} ({s:?}) is not a number"))
    })
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let cases: Vec<(String, Vec<_>, bool)> = if args.get(1).map(String::as_str) == Some("pixels") {
        walks::pixel_samples()
    } else {
        let count: usize = arg(&args, 1, 4000)?;
        let seed: u64 = arg(&args, 2, 7)?;
        walks::grid_walks(&mut walks::Lcg(seed), count)
            .into_iter()
            .enumerate()
            .map(|(i, (points, closed))| (format!("walk {i}"), points, closed))
            .collect()
    };
    let schemes = [
        (Scheme::Kappa, 2.0 / 3.0),
        (Scheme::EkCubic, 0.8),
        (Scheme::EkTrig, 0.7),
    ];
    for (scheme, a) in schemes {
        let mut solver = Solver::new();
        let (mut ok, mut total, mut iterations) = (0, 0, 0usize);
        let start = std::time::Instant::now();
        for (name, points, closed) in &cases {
            let one = std::time::Instant::now();
            match solver.solve(points, *closed, scheme, &Shape::Global(a)) {
                Ok(s) => {
                    ok += 1;
                    total += 1;
                    iterations += s.iterations();
                }
                Err(Error::NotConverged { residual, .. }) => {
                    total += 1;
                    let pts: Vec<String> =
                        points.iter().map(|p| format!("{},{}", p.x, p.y)).collect();
                    println!(
                        "failed: {scheme:?} {name}, closed {closed}, {} points, \
                         residual {residual:.1e}, {:.0} ms: {}",
                        points.len(),
                        one.elapsed().as_secs_f64() * 1e3,
                        pts.join(" ")
                    );
                }
                // Input no curve goes through (a point repeated, a line doubling back).
                Err(_) => {}
            }
        }
        println!(
            "{scheme:?}: {ok}/{total} converge ({:.3} %), {iterations} iterations on those, {:.1} s",
            100.0 * ok as f64 / total as f64,
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
