//! κ-space curve benchmarks: a closed 3D loop of 50 and of 10 000 points — the whole
//! construction cold (3D κ solve + quartic replacement), the replacement alone from a solved
//! κ-curve, the interactive case (one point moved: warm re-solve + replacement), and the
//! replacement with optimized γ.
//!
//! Run with `cargo bench --bench space`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use kappa::space::{Gamma, SpaceCurve, SpaceOptions};
use kappa::{Point3, Scheme, Shape, Solver3};
use std::hint::black_box;

/// A closed loop of `n` points with radii alternating 100 and 90 and a height wave of
/// amplitude 20 (three periods): jagged in plan, twisted in space.
fn loop3(n: usize) -> Vec<Point3> {
    (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 100.0 } else { 90.0 };
            Point3::new(r * th.cos(), r * th.sin(), 20.0 * (3.0 * th).sin())
        })
        .collect()
}

fn space(c: &mut Criterion) {
    let mut g = c.benchmark_group("space_closed");
    for n in [50usize, 10_000] {
        if n > 1000 {
            g.sample_size(10);
        }
        let pts = loop3(n);
        let options = SpaceOptions::default();
        g.bench_function(BenchmarkId::new("cold", n), |b| {
            b.iter(|| black_box(SpaceCurve::new(&pts, true, &options).unwrap()))
        });
        let mut solver = Solver3::new();
        let spline = solver
            .solve(&pts, true, Scheme::Kappa, &Shape::Neutral)
            .unwrap();
        g.bench_function(BenchmarkId::new("replace_only", n), |b| {
            b.iter(|| black_box(SpaceCurve::from_spline(spline.clone(), &options).unwrap()))
        });
        let optimized = SpaceOptions::default().with_gamma(Gamma::Optimized);
        g.bench_function(BenchmarkId::new("replace_only_optimized_gamma", n), |b| {
            b.iter(|| black_box(SpaceCurve::from_spline(spline.clone(), &optimized).unwrap()))
        });
        // A small drag: a tenth of the point spacing.
        let step = 0.1 * std::f64::consts::TAU * 100.0 / n as f64;
        let mut moved = pts.clone();
        moved[n / 5].x += 0.8 * step;
        moved[n / 5].z -= 0.6 * step;
        g.bench_function(BenchmarkId::new("move_one_point_warm", n), |b| {
            let mut flip = false;
            b.iter(|| {
                flip = !flip;
                let spline = solver.resolve(if flip { &moved } else { &pts }).unwrap();
                black_box(SpaceCurve::from_spline(spline, &options).unwrap())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, space);
criterion_main!(benches);
