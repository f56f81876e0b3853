//! The viable region of seed 003 (Fig. 4): for fixed G1 data, which end curvatures
//! `(κ_s, κ_e)` admit a G2 segment with monotone curvature, for curvature functions of degree
//! 3, 5 and 10 (blue: monotone without inflection; grey: a solution, but not monotone; white:
//! no solution reached). The red dot is the clothoid's end curvatures. The region grows with
//! the degree, as in the paper.
//!
//! Run with `cargo run --release --features render --example viable_region [OUT.png]`.

use kappa::intrinsic::picture::{
    viable_data, viable_figure, VIABLE_DEGREES, VIABLE_K_END, VIABLE_K_START,
};
use kappa::intrinsic::{viable_region, Viability};

/// Samples per axis.
const SAMPLES: usize = 61;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "viable_region.png".into());
    for degree in VIABLE_DEGREES {
        let region = viable_region(
            &viable_data(),
            degree,
            VIABLE_K_START,
            VIABLE_K_END,
            SAMPLES,
        )?;
        println!(
            "degree {degree}: {} monotone, {} other solutions, {} without solution",
            region.count(Viability::Monotone),
            region.count(Viability::Solved),
            region.count(Viability::NoSolution)
        );
    }
    viable_figure(300, SAMPLES)?.save_png(&out)?;
    println!("wrote {out}");
    Ok(())
}
