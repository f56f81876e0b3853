//! One G1 Hermite problem, many curvature profiles (seed 003 Fig. 2): the clothoid (linear
//! curvature), cubic curvature functions with κ₀ = κ₁ = κ₂ or κ₁ = κ₂ = κ₃, quintic ones with
//! the first or last five control curvatures equal, and a cubic with dκ/ds = 0 at both ends
//! (κ₀ = κ₁, κ₂ = κ₃) — each with its curvature comb, inflections (red) and curvature extrema
//! (blue). Prints each solution's length, control curvatures and analysis.
//!
//! Run with `cargo run --release --features render --example intrinsic_variety [OUT.png]`.

use kappa::intrinsic::picture::{variety_data, variety_figure, variety_profiles};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "intrinsic_variety.png".into());
    let data = variety_data();
    for (name, profile) in variety_profiles() {
        let seg = data.solve(&profile)?;
        println!(
            "{name}: length {:.4}, κ = {:.4?}, inflections {:.4?}, monotone {}",
            seg.length(),
            seg.curvatures(),
            seg.inflections(),
            seg.is_monotone()
        );
    }
    variety_figure(260)?.save_png(&out)?;
    println!("wrote {out}");
    Ok(())
}
