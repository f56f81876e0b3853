#![no_main]
//! Warm re-solves (`Solver::resolve`, `resolve_shapes`) after hostile perturbations.

#[path = "../../tests/hostile/mod.rs"]
mod hostile;

libfuzzer_sys::fuzz_target!(|data: &[u8]| hostile::targets::resolve(data));
