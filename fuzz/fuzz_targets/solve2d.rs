#![no_main]
//! κ, εκ-cubic and εκ-trig solves of hostile points, open and closed, with shapes.

#[path = "../../tests/hostile/mod.rs"]
mod hostile;

libfuzzer_sys::fuzz_target!(|data: &[u8]| hostile::targets::solve2d(data));
