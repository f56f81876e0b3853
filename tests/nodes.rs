//! The node path of a solved curve (`Spline::to_node_bezpath`, `Editor::node_outline`): nodes
//! at every input point and joint, exact for κ and εκ-cubic, and a structure that depends
//! only on the topology (what point-compatible font masters need).

mod common;

use common::paper_curves;
use kappa::editor::{EditPoint, Editor, PathDoc};
use kappa::{Scheme, Shape, Solver, Spline, TRIG_NODE_CUBICS};
use kurbo::{BezPath, ParamCurve, PathEl, Point};
use proptest::prelude::*;

fn kinds(p: &BezPath) -> Vec<core::mem::Discriminant<PathEl>> {
    p.elements().iter().map(core::mem::discriminant).collect()
}

/// The parts of `curve` in the documented order of `to_node_bezpath`: (segment, t0, t1).
fn parts(curve: &Spline) -> Vec<(usize, f64, f64)> {
    let segs = curve.segments();
    let n = segs.len();
    let mut out = Vec::new();
    if curve.is_closed() {
        for j in 0..n {
            out.push((j, segs[j].t_max, 1.0));
            out.push(((j + 1) % n, 0.0, segs[(j + 1) % n].t_max));
        }
    } else {
        out.push((0, 0.0, segs[0].t_max));
        for j in 0..n - 1 {
            out.push((j, segs[j].t_max, 1.0));
            out.push((j + 1, 0.0, segs[j + 1].t_max));
        }
        out.push((n - 1, segs[n - 1].t_max, 1.0));
    }
    out
}

/// The largest distance between `path` and `curve` at corresponding parameters: each path
/// segment against its part of the curve (`per` path segments per part), 9 samples each.
fn distance(curve: &Spline, path: &BezPath, per: usize) -> f64 {
    let segs: Vec<_> = path.segments().collect();
    let parts = parts(curve);
    assert_eq!(segs.len(), parts.len() * per);
    let mut worst = 0.0f64;
    for (k, ps) in segs.iter().enumerate() {
        let (j, t0, t1) = parts[k / per];
        let (a, b) = (
            (k % per) as f64 / per as f64,
            (k % per + 1) as f64 / per as f64,
        );
        for i in 0..=8 {
            let s = i as f64 / 8.0;
            let t = t0 + (t1 - t0) * (a + (b - a) * s);
            worst = worst.max((ps.eval(s) - curve.segments()[j].eval(t)).hypot());
        }
    }
    worst
}

fn solve(points: &[Point], closed: bool, scheme: Scheme) -> Spline {
    let shape = match scheme {
        Scheme::Kappa => Shape::Neutral,
        Scheme::EkCubic => Shape::Global(0.8),
        Scheme::EkTrig => Shape::Global(0.7),
    };
    Solver::new()
        .solve(points, closed, scheme, &shape)
        .unwrap_or_else(|e| panic!("{scheme:?}: {e}"))
}

/// On the paper drawings: every input point is a node, the path has two parts per segment,
/// and it is the curve (κ, εκ-cubic: to rounding; εκ-trig: within the Hermite cubics' error,
/// measured here).
#[test]
fn node_paths_of_the_paper_drawings() {
    let mut trig_worst = 0.0f64;
    for (name, i, pts, closed, size) in paper_curves() {
        for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
            let curve = solve(&pts, closed, scheme);
            let path = curve.to_node_bezpath();
            let parts = if scheme == Scheme::EkTrig {
                TRIG_NODE_CUBICS
            } else {
                1
            };
            let n = curve.segments().len();
            assert_eq!(
                path.elements().len(),
                1 + 2 * n * parts + usize::from(closed),
                "{name} {i} {scheme:?}"
            );
            let nodes: Vec<Point> = path
                .elements()
                .iter()
                .filter_map(|e| e.end_point())
                .collect();
            for q in &pts {
                let d = nodes
                    .iter()
                    .map(|p| (*p - *q).hypot())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d <= 1e-9 * size,
                    "{name} {i} {scheme:?}: point {q:?} is {d} from a node"
                );
            }
            let err = distance(&curve, &path, parts) / size;
            if scheme == Scheme::EkTrig {
                trig_worst = trig_worst.max(err);
            } else {
                assert!(err <= 1e-9, "{name} {i} {scheme:?}: {err}");
            }
        }
    }
    println!("εκ-trig node path: largest distance {trig_worst:.2e} of the drawing size");
    assert!(trig_worst <= 5e-4, "{trig_worst}");
}

/// The structure depends only on the number of points and the closed flag (so masters of
/// one glyph interpolate), in every scheme, with the shapes varying too.
#[test]
fn node_paths_of_moved_points_have_the_same_elements() {
    let base = [
        (0.0, 0.0),
        (100.0, 10.0),
        (160.0, 80.0),
        (120.0, 150.0),
        (40.0, 160.0),
        (-20.0, 90.0),
    ]
    .map(Point::from);
    proptest!(ProptestConfig::with_cases(48), |(
        moves in proptest::collection::vec((-25.0f64..25.0, -25.0f64..25.0), 6),
        closed in any::<bool>(),
        a in 0.7f64..0.95,
    )| {
        let moved: Vec<Point> = base.iter().zip(&moves).map(|(p, d)| *p + kurbo::Vec2::new(d.0, d.1)).collect();
        for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
            let shape = if scheme == Scheme::Kappa { Shape::Neutral } else { Shape::Global(a) };
            let (Ok(s0), Ok(s1)) = (
                Solver::new().solve(&base, closed, scheme, &Shape::Neutral),
                Solver::new().solve(&moved, closed, scheme, &shape),
            ) else {
                continue;
            };
            prop_assert_eq!(kinds(&s0.to_node_bezpath()), kinds(&s1.to_node_bezpath()));
        }
    });
}

/// A collapsed segment (the wave's inflection through its middle point) is kept as parts
/// of no length: the wave and the same wave with its middle point moved off the line have
/// the same elements, where `to_bezpath` drops the collapsed one.
#[test]
fn collapsed_segments_keep_their_parts() {
    let wave = [
        (100.0, 300.0),
        (250.0, 200.0),
        (400.0, 300.0),
        (550.0, 400.0),
        (700.0, 300.0),
    ]
    .map(Point::from);
    let mut off = wave;
    off[2].y += 5.0;
    let (a, b) = (
        Spline::kappa(&wave, false).unwrap(),
        Spline::kappa(&off, false).unwrap(),
    );
    assert!(a.segments()[1].is_collapsed());
    assert_ne!(kinds(&a.to_bezpath()), kinds(&b.to_bezpath()));
    assert_eq!(kinds(&a.to_node_bezpath()), kinds(&b.to_node_bezpath()));
    assert!(distance(&a, &a.to_node_bezpath(), 1) < 1e-9);
}

fn doc(points: &[(f64, f64, bool)], scheme: Scheme, shape: f64) -> PathDoc {
    PathDoc {
        points: points
            .iter()
            .map(|&(x, y, corner)| EditPoint {
                x,
                y,
                shape,
                corner,
                tangent: None,
                tangent_in: None,
            })
            .collect(),
        closed: true,
        scheme,
        solution: Vec::new(),
    }
}

/// An editor document with corners (a `D`: a stem between two corners, a bowl of three
/// points): lines between corners, the bowl's node path, and the same elements for a second
/// master with other positions and shapes.
#[test]
fn node_outlines_of_two_masters_match() {
    let light = [
        (0.0, 0.0, true),
        (0.0, 700.0, true),
        (300.0, 650.0, false),
        (420.0, 350.0, false),
        (300.0, 50.0, false),
    ];
    let bold = [
        (0.0, 0.0, true),
        (0.0, 700.0, true),
        (380.0, 620.0, false),
        (520.0, 350.0, false),
        (360.0, 80.0, false),
    ];
    for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
        let (s0, s1) = match scheme {
            Scheme::Kappa => (2.0 / 3.0, 2.0 / 3.0),
            _ => (0.72, 0.9),
        };
        let (a, ca) = Editor::from_doc(doc(&light, scheme, s0));
        let (b, cb) = Editor::from_doc(doc(&bold, scheme, s1));
        assert!(ca.errors.is_empty() && cb.errors.is_empty(), "{scheme:?}");
        let (pa, pb) = (a.node_outline(), b.node_outline());
        assert_eq!(kinds(&pa), kinds(&pb), "{scheme:?}");
        assert!(matches!(pa.elements().last(), Some(PathEl::ClosePath)));
        // The stem is a line.
        assert!(
            pa.elements()
                .iter()
                .any(|e| *e == PathEl::LineTo(Point::new(0.0, 700.0))),
            "{scheme:?}"
        );
        // Every point is a node.
        let nodes: Vec<Point> = pa.elements().iter().filter_map(|e| e.end_point()).collect();
        for &(x, y, _) in &light {
            assert!(
                nodes.iter().any(|p| (*p - Point::new(x, y)).hypot() < 1e-9),
                "{scheme:?} {x} {y}"
            );
        }
    }
}
