//! Intrinsic-curve benchmarks: G1 Hermite solves of degree 1 (the clothoid) and 3 (a profile
//! with dκ/ds = 0 at both ends, which needs Newton's method), G2 solves of degree 3 and 5,
//! and fitting one segment with cubic Béziers.
//!
//! Run with `cargo bench --bench intrinsic`.

use criterion::{criterion_group, criterion_main, Criterion};
use kappa::fit::FitOptions;
use kappa::intrinsic::{Control, Hermite, Profile};
use kurbo::Point;
use std::hint::black_box;

fn g1_data() -> Hermite {
    Hermite::g1(Point::ZERO, 0.3, Point::new(10.0, 4.0), 1.6)
}

fn g2_data() -> Hermite {
    Hermite::g2(Point::ZERO, 0.3, -0.1, Point::new(10.0, 4.0), 1.6, 0.3)
}

fn hermite(c: &mut Criterion) {
    let mut g = c.benchmark_group("hermite");
    let g1 = g1_data();
    let g2 = g2_data();
    let flat_ends = Profile::new(vec![
        Control::Free,
        Control::Same(0),
        Control::Same(3),
        Control::Free,
    ]);
    g.bench_function("g1_degree1", |b| {
        let p = Profile::clothoid();
        b.iter(|| black_box(black_box(&g1).solve(&p).unwrap()))
    });
    g.bench_function("g1_degree3_flat_ends", |b| {
        b.iter(|| black_box(black_box(&g1).solve(&flat_ends).unwrap()))
    });
    g.bench_function("g2_degree3", |b| {
        let p = Profile::free(3);
        b.iter(|| black_box(black_box(&g2).solve(&p).unwrap()))
    });
    g.bench_function("g2_degree5", |b| {
        let p = Profile::free(5);
        b.iter(|| black_box(black_box(&g2).solve(&p).unwrap()))
    });
    g.bench_function("g2_degree3_rational", |b| {
        let p = Profile::free(3).with_weights(vec![1.0, 2.0, 0.5, 1.0]);
        b.iter(|| black_box(black_box(&g2).solve(&p).unwrap()))
    });
    g.finish();
}

fn fitting(c: &mut Criterion) {
    let mut g = c.benchmark_group("fit_segment");
    let seg = g2_data().solve(&Profile::free(5)).unwrap();
    for (label, tol) in [("1e-3", 1e-3), ("1e-6", 1e-6)] {
        let options = FitOptions {
            check_samples: 0,
            ..FitOptions::relative(tol)
        };
        g.bench_function(label, |b| {
            b.iter(|| black_box(black_box(&seg).to_bezpath(&options).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, hermite, fitting);
criterion_main!(benches);
