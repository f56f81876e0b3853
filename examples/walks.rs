//! Convergence rates on random walks on an integer grid: the clicks of a designer who
//! snaps to whole pixels, 4–40 of them, steps of up to 5 units each way, open and closed
//! (the generator of `tests/integer_input.rs`, in `tests/common/walks.rs`).
//!
//! ```text
//! cargo run --release --example walks -- [count] [seed]
//! ```
//!
//! Prints each failure (scheme, walk, residual, time, points) and the rate per scheme, with the
//! default solver options. The rates are in docs/curves.md, "Known limits".

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
    let count: usize = arg(&args, 1, 4000)?;
    let seed: u64 = arg(&args, 2, 7)?;
    let cases = walks::grid_walks(&mut walks::Lcg(seed), count);
    let schemes = [
        (Scheme::Kappa, 2.0 / 3.0),
        (Scheme::EkCubic, 0.8),
        (Scheme::EkTrig, 0.7),
    ];
    for (scheme, a) in schemes {
        let mut solver = Solver::new();
        let (mut ok, mut total, mut iterations) = (0, 0, 0usize);
        let start = std::time::Instant::now();
        for (idx, (points, closed)) in cases.iter().enumerate() {
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
                        "failed: {scheme:?} walk {idx}, closed {closed}, {} points, \
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
