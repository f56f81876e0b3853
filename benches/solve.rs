//! Solver benchmarks: the paper's bear drawing cold (κ and εκ), warm re-solves after a point
//! moves (the interactive case), and scaling to 100 000 points.
//!
//! Run with `cargo bench --all-features --bench solve`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use kappa::{builtin_design, Design, Scheme, Shape, Solver};
use kurbo::Point;
use std::hint::black_box;

fn design(name: &str) -> Vec<(Vec<Point>, bool)> {
    let d = Design::from_json(builtin_design(name).unwrap()).unwrap();
    d.curves
        .iter()
        .map(|c| (c.kurbo_points(), c.is_closed()))
        .collect()
}

/// A closed star of `n` points with alternating radii 100 and 90 (a jagged outline, the kind
/// that makes the classic loop oscillate).
fn star(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 100.0 } else { 90.0 };
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect()
}

fn bear(c: &mut Criterion) {
    let curves = design("bear");
    let mut g = c.benchmark_group("bear_cold");
    for (label, scheme, shape) in [
        ("kappa", Scheme::Kappa, Shape::Neutral),
        ("ek_cubic_0.85", Scheme::EkCubic, Shape::Global(0.85)),
    ] {
        g.bench_function(label, |b| {
            let mut solvers: Vec<Solver> = curves.iter().map(|_| Solver::new()).collect();
            b.iter(|| {
                for ((pts, closed), s) in curves.iter().zip(solvers.iter_mut()) {
                    black_box(s.solve(pts, *closed, scheme, &shape).unwrap());
                }
            })
        });
    }
    g.finish();
}

fn warm(c: &mut Criterion) {
    let pts = star(50);
    let mut g = c.benchmark_group("move_one_point_50");
    for (label, scheme, shape) in [
        ("kappa", Scheme::Kappa, Shape::Neutral),
        ("ek_cubic_0.85", Scheme::EkCubic, Shape::Global(0.85)),
    ] {
        let mut moved = pts.clone();
        moved[10] += kurbo::Vec2::new(0.8, -0.5);
        g.bench_function(BenchmarkId::new("warm", label), |b| {
            let mut s = Solver::new();
            s.solve(&pts, true, scheme, &shape).unwrap();
            let mut flip = false;
            b.iter(|| {
                flip = !flip;
                black_box(s.resolve(if flip { &moved } else { &pts }).unwrap());
            })
        });
        g.bench_function(BenchmarkId::new("cold", label), |b| {
            let mut s = Solver::new();
            b.iter(|| black_box(s.solve(&moved, true, scheme, &shape).unwrap()))
        });
    }
    g.finish();
}

fn scaling(c: &mut Criterion) {
    let mut g = c.benchmark_group("closed_points");
    g.sample_size(10);
    for (label, scheme, shape, sizes) in [
        (
            "ek_cubic_0.85",
            Scheme::EkCubic,
            Shape::Global(0.85),
            &[1_000usize, 10_000, 100_000][..],
        ),
        (
            "kappa",
            Scheme::Kappa,
            Shape::Neutral,
            &[1_000usize, 10_000][..],
        ),
    ] {
        for &n in sizes {
            let pts = star(n);
            g.bench_function(BenchmarkId::new(label, n), |b| {
                let mut s = Solver::new();
                b.iter(|| black_box(s.solve(&pts, true, scheme, &shape).unwrap()))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bear, warm, scaling);
criterion_main!(benches);
