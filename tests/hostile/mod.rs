//! Hostile input: generators of structured inputs from raw bytes (through `arbitrary`) and the
//! oracles that check every entry point's answer to them.
//!
//! Shared by the fuzz targets in `fuzz/fuzz_targets/` (which include this file by path) and
//! the ordinary tests (`tests/fuzz_smoke.rs` replays the committed seeds and a deterministic
//! stream of random inputs through the same oracles). An oracle never accepts a bare "no
//! panic": every `Ok` is checked (finite numbers, interpolation, peaks at the points, G2
//! where claimed, end conditions) and every `Err` must be the variant that the input
//! explains (a `NonFinitePoint` names a point that is not finite, and so on).
//!
//! Values are drawn at mixed scales: sizes from 1e-9 to 1e9, offsets up to 1e9 from the
//! origin, near-duplicate points, collinear runs, points on circles, and now and then NaN,
//! infinities, ±1e308 and subnormals.
#![allow(dead_code)]

pub mod inputs;
pub mod oracles;

#[allow(unused_imports)]
pub use inputs::*;
#[allow(unused_imports)]
pub use oracles::*;
pub mod targets;
