//! Uniform cubic B-spline benchmarks: periodic interpolation of 10³, 10⁵ and 10⁶ points
//! (fresh, and re-solved in place with `set_points`), and the exact maximum curvature of a
//! 10⁴-segment spline (2D and 3D; measured-looking data, and a worst case with a small loop in
//! nearly every segment).
//!
//! Run with `cargo bench --bench bspline`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use kappa::{BSpline, BSpline3, Point3};
use kurbo::Point;
use std::hint::black_box;

/// A closed loop of `n` points: radius 100 with a 7-fold wave, each point moved radially by a
/// pseudo-random amount of up to `jitter` times the point spacing (0.1: like measured data;
/// 8: a small loop in nearly every segment).
fn wavy(n: usize, jitter: f64) -> Vec<Point> {
    let spacing = std::f64::consts::TAU * 100.0 / n as f64;
    (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            let noise = ((i as f64 * 12.9898).sin() * 43758.5453).fract();
            let r = 100.0 + 10.0 * (7.0 * th).sin() + noise * jitter * spacing;
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect()
}

/// The same loop lifted into 3D with a 5-fold wave in z.
fn wavy3(n: usize, jitter: f64) -> Vec<Point3> {
    wavy(n, jitter)
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            Point3::new(p.x, p.y, 20.0 * (5.0 * th).sin())
        })
        .collect()
}

fn interpolation(c: &mut Criterion) {
    let mut g = c.benchmark_group("bspline_periodic");
    g.sample_size(20);
    for n in [1_000usize, 100_000, 1_000_000] {
        let pts = wavy(n, 0.1);
        g.bench_function(BenchmarkId::new("2d", n), |b| {
            b.iter(|| black_box(BSpline::periodic(black_box(&pts)).unwrap()))
        });
        let pts3 = wavy3(n, 0.1);
        g.bench_function(BenchmarkId::new("3d", n), |b| {
            b.iter(|| black_box(BSpline3::periodic(black_box(&pts3)).unwrap()))
        });
    }
    // Re-solving in place: no fresh pages to fault in.
    let n = 1_000_000;
    let pts = wavy(n, 0.1);
    let mut spline = BSpline::periodic(&pts).unwrap();
    g.bench_function(BenchmarkId::new("2d_set_points", n), |b| {
        b.iter(|| spline.set_points(black_box(&pts), true).unwrap())
    });
    g.finish();
}

fn max_curvature(c: &mut Criterion) {
    let mut g = c.benchmark_group("bspline_max_curvature");
    g.sample_size(20);
    let n = 10_000;
    for (label, jitter) in [("2d", 0.1), ("2d_loops", 8.0)] {
        let s = BSpline::periodic(&wavy(n, jitter)).unwrap();
        g.bench_function(BenchmarkId::new(label, n), |b| {
            b.iter(|| black_box(s.max_curvature()))
        });
    }
    for (label, jitter) in [("3d", 0.1), ("3d_loops", 8.0)] {
        let s = BSpline3::periodic(&wavy3(n, jitter)).unwrap();
        g.bench_function(BenchmarkId::new(label, n), |b| {
            b.iter(|| black_box(s.max_curvature()))
        });
    }
    g.finish();
}

criterion_group!(benches, interpolation, max_curvature);
criterion_main!(benches);
