//! Solver benchmarks: the paper's bear drawing cold (κ and εκ; curve by curve, and as one
//! batch over rayon's pool), warm re-solves after a point moves (the interactive case), and
//! scaling to 100 000 points.
//!
//! Run with `cargo bench --all-features --bench solve`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use kappa::fit::{FitMethod, FitOptions};
use kappa::{builtin_design, BatchCurve, BatchSolver, Design, Scheme, Shape, Solver, Spline};
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
        ("ek_trig_0.75", Scheme::EkTrig, Shape::Global(0.75)),
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
    // The same curves as one batch, spread over the threads of rayon's pool.
    for (label, scheme, shape) in [
        ("kappa_batch", Scheme::Kappa, Shape::Neutral),
        ("ek_cubic_0.85_batch", Scheme::EkCubic, Shape::Global(0.85)),
    ] {
        let batch: Vec<BatchCurve<'_, Point>> = curves
            .iter()
            .map(|(pts, closed)| BatchCurve::new(pts, *closed, &shape))
            .collect();
        g.bench_function(label, |b| {
            let mut solver = BatchSolver::new();
            b.iter(|| {
                for spline in solver.solve(&batch, scheme) {
                    black_box(spline.unwrap());
                }
            })
        });
    }
    // εκ-trig solved and fitted to cubics (1e-4 of each curve's size), and the fit alone.
    let solved: Vec<Spline> = curves
        .iter()
        .map(|(pts, closed)| Spline::ek_trig(pts, *closed, 0.75).unwrap())
        .collect();
    g.bench_function("ek_trig_0.75_solve_fit", |b| {
        let mut solvers: Vec<Solver> = curves.iter().map(|_| Solver::new()).collect();
        b.iter(|| {
            for ((pts, closed), s) in curves.iter().zip(solvers.iter_mut()) {
                let spline = s
                    .solve(pts, *closed, Scheme::EkTrig, &Shape::Global(0.75))
                    .unwrap();
                black_box(spline.fit(&FitOptions::default()).unwrap());
            }
        })
    });
    g.bench_function("ek_trig_0.75_fit_only", |b| {
        b.iter(|| {
            for spline in &solved {
                black_box(spline.fit(&FitOptions::default()).unwrap());
            }
        })
    });
    g.bench_function("ek_trig_0.75_fit_only_hermite", |b| {
        let options = FitOptions {
            method: FitMethod::Hermite,
            ..FitOptions::default()
        };
        b.iter(|| {
            for spline in &solved {
                black_box(spline.fit(&options).unwrap());
            }
        })
    });
    g.bench_function("ek_trig_0.75_fit_only_unchecked", |b| {
        let options = FitOptions {
            check_samples: 0,
            ..FitOptions::default()
        };
        b.iter(|| {
            for spline in &solved {
                black_box(spline.fit(&options).unwrap());
            }
        })
    });
    g.finish();
}

fn warm(c: &mut Criterion) {
    let pts = star(50);
    let mut g = c.benchmark_group("move_one_point_50");
    for (label, scheme, shape) in [
        ("kappa", Scheme::Kappa, Shape::Neutral),
        ("ek_cubic_0.85", Scheme::EkCubic, Shape::Global(0.85)),
        ("ek_trig_0.75", Scheme::EkTrig, Shape::Global(0.75)),
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

/// The path tool's drag update on a 100-point closed path: move one point, warm re-solve,
/// and build the path and its comb for drawing.
fn editor_drag(c: &mut Criterion) {
    use kappa::editor::Editor;
    let mut g = c.benchmark_group("editor_drag_100");
    for (label, scheme) in [
        ("kappa", Scheme::Kappa),
        ("ek_cubic", Scheme::EkCubic),
        ("ek_trig", Scheme::EkTrig),
    ] {
        let mut e = Editor::new(scheme);
        for p in star(100) {
            e.add_point(p);
        }
        e.set_closed(true);
        let base = e.doc().points[30].point();
        let mut k = 0usize;
        g.bench_function(label, |b| {
            b.iter(|| {
                k += 1;
                // Back and forth by up to half a unit, like a hand dragging.
                let off = 0.5 * ((k % 8) as f64 / 4.0 - 1.0);
                let change = e.move_point(30, base + kurbo::Vec2::new(off, -off));
                black_box(change);
                black_box(e.to_bezpath());
                black_box(e.curvature_comb(10.0, 8));
            })
        });
    }
    g.finish();
    // The same updates as one drag gesture (Editor::drag_point, what the web page sends):
    // one undo step for the whole gesture instead of a snapshot per update.
    let mut g = c.benchmark_group("editor_drag_gesture_100");
    for (label, scheme) in [
        ("kappa", Scheme::Kappa),
        ("ek_cubic", Scheme::EkCubic),
        ("ek_trig", Scheme::EkTrig),
    ] {
        let mut e = Editor::new(scheme);
        for p in star(100) {
            e.add_point(p);
        }
        e.set_closed(true);
        let base = e.doc().points[30].point();
        let mut k = 0usize;
        g.bench_function(label, |b| {
            b.iter(|| {
                k += 1;
                let off = 0.5 * ((k % 8) as f64 / 4.0 - 1.0);
                let change = e.drag_point(30, base + kurbo::Vec2::new(off, -off));
                black_box(change);
                black_box(e.to_bezpath());
                black_box(e.curvature_comb(10.0, 8));
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bear, warm, scaling, editor_drag);
criterion_main!(benches);
