//! The path-tool engine: random edit sequences keep every property of the curves, undo/redo
//! restore exactly, inserting on the curve barely changes it, corners break tangents.

mod common;

use kappa::editor::{EditPoint, Editor, PathDoc};
use kappa::Scheme;
use kurbo::{ParamCurve, Point};
use proptest::prelude::*;

/// Every piece whose curve matches the document: each of its points lies on its segment at
/// `t_max`, |κ| is equal on both sides of every joint, and |κ| is locally maximal at `t_max`
/// wherever the segment reports a maximum (the foundation's checks). Warm re-solves may
/// follow another solution branch than a cold solve; both must have these properties.
fn check(e: &Editor) {
    let doc = e.doc();
    for k in 0..e.pieces() {
        let Some(spline) = e.piece_spline(k) else {
            continue;
        };
        if e.piece_error(k).is_some() {
            // A stale curve: its last solve failed, which the edit reported.
            continue;
        }
        let pts: Vec<Point> = e
            .piece_points(k)
            .iter()
            .map(|&i| doc.points[i].point())
            .collect();
        let interior: Vec<Point> = if spline.is_closed() {
            pts.clone()
        } else if pts.len() == 2 {
            vec![pts[0].midpoint(pts[1])]
        } else {
            pts[1..pts.len() - 1].to_vec()
        };
        let size = pts
            .iter()
            .fold(kurbo::Rect::from_points(pts[0], pts[0]), |r, &p| {
                r.union_pt(p)
            });
        let size = size.width().max(size.height());
        let segs = spline.segments();
        assert_eq!(segs.len(), interior.len());
        // Relative to the piece, with a floor at the rounding of the coordinates themselves
        // (insertions can make pieces far smaller than their distance from the origin).
        let far = pts
            .iter()
            .map(|p| p.x.abs().max(p.y.abs()))
            .fold(0.0, f64::max);
        for (seg, p) in segs.iter().zip(&interior) {
            assert!(
                (seg.eval(seg.t_max) - *p).hypot() <= 1e-9 * size + 1e-12 * far,
                "piece {k} {:?}: point {p:?}, curve at t_max {:?} ({seg:?})",
                e.piece_points(k),
                seg.eval(seg.t_max)
            );
        }
        let kmax = spline.max_abs_curvature();
        // Straight pieces (two points, or collinear ones) have |κ| = 0 up to rounding:
        // nothing to compare or peak.
        if pts.len() == 2 || kmax * size < 1e-9 || size < 1e-9 * far || on_one_line(&pts, size) {
            continue;
        }
        let joints = if spline.is_closed() {
            segs.len()
        } else {
            segs.len() - 1
        };
        for j in 0..joints {
            let (a, b) = (&segs[j], &segs[(j + 1) % segs.len()]);
            let (ka, kb) = (a.curvature(1.0).abs(), b.curvature(0.0).abs());
            // The end curvature of a segment of control-polygon length `l` moves by about
            // `δ / l²` when its control points move by `δ`, and the solve places them to
            // 1e-12 of the size: a segment shrunk next to an inflection at its point (a
            // thousandth of a unit long, say) has its end curvature that much less exact.
            let l =
                |s: &kappa::Segment<Point>| (s.q[1] - s.q[0]).hypot() + (s.q[2] - s.q[1]).hypot();
            let shortest = l(a).min(l(b));
            assert!(
                (ka - kb).abs()
                    <= 1e-6 * kmax + 1e-12 / size + 1e-12 * size / (shortest * shortest),
                "joint {j}: {ka} vs {kb}"
            );
        }
        for seg in segs {
            let t = seg.t_max;
            if seg.extremum() == kappa::Extremum::Max && t > 1e-3 && t < 1.0 - 1e-3 {
                // The largest |κ| near t_max (golden-section search within ±0.02, inside the
                // segment) is at t_max,
                // or |κ| is flat there (a degenerate stationary point).
                let w = 0.02f64.min(0.5 * t).min(0.5 * (1.0 - t));
                let found = common::golden_max(|x| seg.curvature(x).abs(), t - w, t + w);
                let h = 1e-4;
                let slope = (seg.curvature(t + h).abs() - seg.curvature(t - h).abs()) / (2.0 * h);
                assert!(
                    (found - t).abs() <= 1e-6 || slope.abs() <= 1e-6 * kmax + 1e-12 / size,
                    "{:?} a={}: peak at {found}, t_max = {t}; piece {pts:?} closed {}",
                    seg.scheme,
                    seg.a,
                    spline.is_closed()
                );
            }
        }
    }
}

/// Whether all points lie on one line, to 1e-9 of `size` (the solver's straight case).
fn on_one_line(pts: &[Point], size: f64) -> bool {
    let (a, b) = pts
        .iter()
        .flat_map(|p| pts.iter().map(move |q| (*p, *q)))
        .max_by(|x, y| (x.0 - x.1).hypot2().total_cmp(&(y.0 - y.1).hypot2()))
        .unwrap();
    let d = b - a;
    let len = d.hypot();
    len == 0.0
        || pts
            .iter()
            .all(|p| ((*p - a).cross(d) / len).abs() <= 1e-9 * size)
}

#[derive(Clone, Debug)]
enum Op {
    Add(f64, f64),
    Move(usize, f64, f64),
    Drag(usize, f64, f64),
    DragShape(usize, f64),
    EndDrag,
    Insert(f64, f64),
    Delete(usize),
    Shape(usize, f64),
    Corner(usize),
    Close(bool),
    Scheme(usize),
    Undo,
    Redo,
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        3 => (0.0f64..200.0, 0.0f64..200.0).prop_map(|(x, y)| Op::Add(x, y)),
        3 => (0usize..20, -8.0f64..8.0, -8.0f64..8.0).prop_map(|(i, x, y)| Op::Move(i, x, y)),
        2 => (0usize..20, -8.0f64..8.0, -8.0f64..8.0).prop_map(|(i, x, y)| Op::Drag(i, x, y)),
        1 => (0usize..20, 0.7f64..0.95).prop_map(|(i, a)| Op::DragShape(i, a)),
        1 => Just(Op::EndDrag),
        1 => (0.0f64..200.0, 0.0f64..200.0).prop_map(|(x, y)| Op::Insert(x, y)),
        1 => (0usize..20).prop_map(Op::Delete),
        1 => (0usize..20, 0.7f64..0.95).prop_map(|(i, a)| Op::Shape(i, a)),
        1 => (0usize..20).prop_map(Op::Corner),
        1 => any::<bool>().prop_map(Op::Close),
        1 => (0usize..3).prop_map(Op::Scheme),
        1 => Just(Op::Undo),
        1 => Just(Op::Redo),
    ]
}

fn apply(e: &mut Editor, op: &Op) {
    let n = e.doc().points.len().max(1);
    match *op {
        Op::Add(x, y) => {
            e.add_point(Point::new(x, y));
        }
        Op::Move(i, dx, dy) => {
            if let Some(p) = e.doc().points.get(i % n) {
                let q = p.point() + kurbo::Vec2::new(dx, dy);
                e.move_point(i % n, q);
            }
        }
        Op::Drag(i, dx, dy) => {
            if let Some(p) = e.doc().points.get(i % n) {
                let q = p.point() + kurbo::Vec2::new(dx, dy);
                e.drag_point(i % n, q);
            }
        }
        Op::DragShape(i, a) => {
            e.drag_shape(i % n, a);
        }
        Op::EndDrag => {
            e.end_drag();
        }
        Op::Insert(x, y) => {
            e.insert_on_curve(Point::new(x, y));
        }
        Op::Delete(i) => {
            e.delete_point(i % n);
        }
        Op::Shape(i, a) => {
            e.set_shape(i % n, a);
        }
        Op::Corner(i) => {
            e.toggle_corner(i % n);
        }
        Op::Close(c) => {
            e.set_closed(c);
        }
        Op::Scheme(s) => {
            e.set_scheme([Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig][s]);
        }
        Op::Undo => {
            e.undo();
        }
        Op::Redo => {
            e.redo();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    #[test]
    fn random_edits_keep_the_curve_right_and_undo_restores_exactly(
        ops in prop::collection::vec(op(), 1..40),
    ) {
        let mut e = Editor::new(Scheme::EkCubic);
        let mut history = vec![(e.doc().clone(), e.to_bezpath())];
        for op in &ops {
            apply(&mut e, op);
            check(&e);
            // Never a blank: every piece shows a curve, whatever failed.
            for k in 0..e.pieces() {
                prop_assert!(e.piece_spline(k).is_some(), "piece {} blank after {:?}", k, op);
            }
            if !matches!(op, Op::Undo | Op::Redo) {
                history.push((e.doc().clone(), e.to_bezpath()));
            }
        }
        // Undo everything that can be undone, then redo it: each state comes back exactly.
        let mut states = vec![(e.doc().clone(), e.to_bezpath())];
        while e.undo() {
            states.push((e.doc().clone(), e.to_bezpath()));
        }
        prop_assert_eq!(e.doc(), &PathDoc { scheme: Scheme::EkCubic, ..PathDoc::default() });
        for (doc, path) in states.iter().rev().skip(1) {
            prop_assert!(e.redo());
            prop_assert_eq!(e.doc(), doc);
            prop_assert_eq!(&e.to_bezpath(), path);
        }
    }
}

fn wave(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let x = i as f64 * 20.0;
            Point::new(
                x,
                40.0 * (i as f64 * 0.9).sin() + 10.0 * ((i * i) % 7) as f64,
            )
        })
        .collect()
}

/// A closed blob of `n` points, radius 100 ± 20.
fn blob(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = 100.0 + 20.0 * (3.0 * th).sin();
            Point::new(110.0 + r * th.cos(), 110.0 + r * th.sin())
        })
        .collect()
}

fn sample_distance(from: &kurbo::BezPath, to: &kurbo::BezPath) -> f64 {
    let targets: Vec<kurbo::PathSeg> = to.segments().collect();
    let mut worst: f64 = 0.0;
    for seg in from.segments() {
        for i in 0..=20 {
            let p = seg.eval(i as f64 / 20.0);
            let d = targets
                .iter()
                .map(|s| kurbo::ParamCurveNearest::nearest(s, p, 1e-9).distance_sq)
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            worst = worst.max(d);
        }
    }
    worst
}

#[test]
fn inserting_on_the_curve_barely_changes_it() {
    // For each scheme, insert a point at the middle of every stretch between two points of a
    // 12-point wave: the new curve stays within 2% of the path's size of the old one, and
    // the old curve passes through the new point exactly.
    let mut worst: f64 = 0.0;
    for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
        for closed in [false, true] {
            let pts = if closed { blob(12) } else { wave(12) };
            let size = 220.0;
            for target in 1..11 {
                let mut e = Editor::new(scheme);
                for &p in &pts {
                    e.add_point(p);
                }
                e.set_closed(closed);
                let before = e.to_bezpath();
                // A point on the curve between points target and target + 1.
                let hit = e.hit_test(pts[target].midpoint(pts[target + 1])).unwrap();
                let (at, change) = e.insert_on_curve(hit.point).unwrap();
                assert!(
                    change.errors.is_empty(),
                    "{scheme:?} closed={closed} at {target}: {change:?}"
                );
                assert_eq!(e.doc().points.len(), 13);
                assert!((e.doc().points[at].point() - hit.point).hypot() < 1e-6);
                assert!(
                    at == target + 1,
                    "inserted at {at}, expected {}",
                    target + 1
                );
                let after = e.to_bezpath();
                let d = sample_distance(&before, &after).max(sample_distance(&after, &before));
                worst = worst.max(d / size);
                assert!(
                    d <= 0.02 * size,
                    "{scheme:?} closed={closed} at {target}: moved {d}"
                );
            }
        }
    }
    println!(
        "largest change after an insertion: {:.4} of the size",
        worst
    );
}

#[test]
fn corners_break_tangents_and_pieces_interpolate() {
    let mut e = Editor::new(Scheme::EkCubic);
    for p in wave(9) {
        e.add_point(p);
    }
    e.toggle_corner(4);
    assert_eq!(e.pieces(), 2);
    assert_eq!(e.piece_points(0), &[0, 1, 2, 3, 4]);
    assert_eq!(e.piece_points(1), &[4, 5, 6, 7, 8]);
    let a = e.piece_spline(0).unwrap().to_bezpath();
    let b = e.piece_spline(1).unwrap().to_bezpath();
    let end = a.segments().last().unwrap();
    let start = b.segments().next().unwrap();
    // Both pieces pass through the corner point; the tangents there differ.
    assert_eq!(end.end(), e.doc().points[4].point());
    assert_eq!(start.start(), e.doc().points[4].point());
    let t0 = (end.end() - end.eval(0.999)).normalize();
    let t1 = (start.eval(0.001) - start.start()).normalize();
    assert!(t0.cross(t1).abs() > 0.05, "no tangent break at the corner");
    // Closing with the corner: one open piece from the corner round to itself.
    e.set_closed(true);
    assert_eq!(e.pieces(), 1);
    assert_eq!(e.piece_points(0), &[4, 5, 6, 7, 8, 0, 1, 2, 3, 4]);
    e.toggle_corner(4);
    assert_eq!(e.pieces(), 1);
    assert!(e.piece_spline(0).unwrap().is_closed());
}

#[test]
fn drags_are_warm_and_errors_keep_the_last_curve() {
    let mut e = Editor::new(Scheme::EkTrig);
    for p in wave(20) {
        e.add_point(p);
    }
    let cold = e.set_shape(5, 0.8);
    let mut p = e.doc().points[7].point();
    let mut total = 0;
    for _ in 0..20 {
        p.y += 0.5;
        let c = e.move_point(7, p);
        assert!(c.errors.is_empty() && !c.restructured);
        assert_eq!(c.resolved, [0]);
        total += c.iterations;
    }
    assert!(
        total <= 20 * 8,
        "warm drags took {total} iterations (cold edit: {cold:?})"
    );
    check(&e);
    // Drag a point onto its neighbour: the piece keeps its curve and says why.
    let before = e.to_bezpath();
    let q = e.doc().points[8].point();
    let c = e.move_point(7, q);
    assert_eq!(c.errors.len(), 1);
    assert!(matches!(c.errors[0].1, kappa::Error::RepeatedPoint { .. }));
    assert_eq!(e.to_bezpath(), before);
    // Dragging on recovers.
    let c = e.move_point(7, q + kurbo::Vec2::new(5.0, 5.0));
    assert!(c.errors.is_empty());
    check(&e);
}

#[test]
fn a_drag_gesture_is_one_undo_step() {
    for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
        let mut built = Editor::new(scheme);
        for p in wave(8) {
            built.add_point(p);
        }
        built.set_closed(true);
        // A fresh history.
        let (mut e, _) = Editor::from_doc(built.doc().clone());
        let mut m = e.clone();
        let (doc0, path0) = (e.doc().clone(), e.to_bezpath());
        // A gesture of 50 updates draws exactly what 50 single moves draw.
        let start = e.doc().points[3].point();
        for k in 1..=50 {
            let q = start + kurbo::Vec2::new(0.3 * k as f64, -0.2 * k as f64);
            let c = e.drag_point(3, q);
            assert!(c.errors.is_empty() && !c.restructured, "{scheme:?}: {c:?}");
            m.move_point(3, q);
        }
        assert_eq!(e.doc(), m.doc());
        assert_eq!(e.to_bezpath(), m.to_bezpath());
        check(&e);
        e.end_drag();
        let (doc1, path1) = (e.doc().clone(), e.to_bezpath());
        // A second gesture on the same point after end_drag, then one on another point
        // without end_drag: three undo steps in all.
        e.drag_point(3, start);
        let (doc2, path2) = (e.doc().clone(), e.to_bezpath());
        e.drag_point(5, e.doc().points[5].point() + kurbo::Vec2::new(4.0, 4.0));
        e.drag_point(5, e.doc().points[5].point() + kurbo::Vec2::new(4.0, 4.0));
        check(&e);
        let (doc3, path3) = (e.doc().clone(), e.to_bezpath());
        for (doc, path) in [(&doc2, &path2), (&doc1, &path1), (&doc0, &path0)] {
            assert!(e.undo());
            assert_eq!(e.doc(), doc);
            assert_eq!(&e.to_bezpath(), path);
        }
        assert!(
            !e.undo(),
            "{scheme:?}: the gestures took more than three steps"
        );
        for (doc, path) in [(&doc1, &path1), (&doc2, &path2), (&doc3, &path3)] {
            assert!(e.redo());
            assert_eq!(e.doc(), doc);
            assert_eq!(&e.to_bezpath(), path);
        }
        // A drag after an undo starts a new step and drops the redo history.
        e.undo();
        e.drag_point(5, Point::new(1.0, 2.0));
        assert!(!e.redo());
        assert!(e.undo());
        assert_eq!(e.doc(), &doc2);
        // Out of range: nothing happens.
        assert_eq!(
            e.drag_point(99, Point::ZERO),
            kappa::editor::Change::default()
        );
        assert_eq!(e.drag_shape(99, 0.8), kappa::editor::Change::default());
    }
}

#[test]
fn a_shape_slider_drag_is_one_undo_step() {
    for scheme in [Scheme::EkCubic, Scheme::EkTrig] {
        let mut built = Editor::new(scheme);
        for p in wave(7) {
            built.add_point(p);
        }
        let (mut e, _) = Editor::from_doc(built.doc().clone());
        let mut m = e.clone();
        let (doc0, path0) = (e.doc().clone(), e.to_bezpath());
        for k in 0..30 {
            let a = 0.7 + 0.008 * k as f64;
            let c = e.drag_shape(2, a);
            assert!(
                c.errors.is_empty() && c.resolved == [0],
                "{scheme:?}: {c:?}"
            );
            m.set_shape(2, a);
        }
        // The same curve as single shape edits, passing through its points with peaks.
        assert_eq!(e.doc(), m.doc());
        assert_eq!(e.to_bezpath(), m.to_bezpath());
        check(&e);
        // A drag of the point right after is a new step; so is another slider drag after
        // end_drag.
        let (doc1, path1) = (e.doc().clone(), e.to_bezpath());
        e.drag_point(2, e.doc().points[2].point() + kurbo::Vec2::new(3.0, 0.0));
        let (doc2, path2) = (e.doc().clone(), e.to_bezpath());
        e.end_drag();
        e.drag_shape(4, 0.9);
        e.drag_shape(4, 0.91);
        for (doc, path) in [(&doc2, &path2), (&doc1, &path1), (&doc0, &path0)] {
            assert!(e.undo());
            assert_eq!(e.doc(), doc);
            assert_eq!(&e.to_bezpath(), path);
        }
        assert!(!e.undo());
    }
}

#[test]
fn hit_test_finds_the_nearest_curve_point() {
    let mut e = Editor::new(Scheme::Kappa);
    assert!(e.hit_test(Point::ZERO).is_none());
    for p in wave(6) {
        e.add_point(p);
    }
    let path = e.to_bezpath();
    for seg in path.segments() {
        let on = seg.eval(0.3);
        let hit = e.hit_test(on).unwrap();
        assert!(hit.distance < 1e-6, "{hit:?}");
    }
    // Off the curve: the distance is that of the nearest point of the path.
    let q = Point::new(50.0, 120.0);
    let hit = e.hit_test(q).unwrap();
    let best = path
        .segments()
        .map(|s| {
            kurbo::ParamCurveNearest::nearest(&s, q, 1e-9)
                .distance_sq
                .sqrt()
        })
        .fold(f64::INFINITY, f64::min);
    assert!((hit.distance - best).abs() < 1e-6);
}

#[cfg(feature = "serde")]
#[test]
fn document_round_trips_through_json() {
    let mut e = Editor::new(Scheme::EkTrig);
    for p in wave(5) {
        e.add_point(p);
    }
    e.toggle_corner(2);
    e.set_shape(1, 0.85);
    let json = serde_json::to_string(e.doc()).unwrap();
    assert!(json.contains("\"ek-trig\""));
    let doc: PathDoc = serde_json::from_str(&json).unwrap();
    assert_eq!(&doc, e.doc());
    let (f, change) = Editor::from_doc(doc);
    assert!(change.errors.is_empty());
    // Solved from scratch: the same curve as the edited one, to solver precision.
    assert_eq!(f.pieces(), e.pieces());
    for k in 0..f.pieces() {
        let (a, b) = (f.piece_spline(k).unwrap(), e.piece_spline(k).unwrap());
        for (x, y) in a.segments().iter().zip(b.segments()) {
            assert!((x.t_max - y.t_max).abs() < 1e-9);
            assert!((x.q[1] - y.q[1]).hypot() < 1e-9);
        }
    }
    // A missing corner flag defaults to false.
    let doc: PathDoc = serde_json::from_str(
        r#"{"points": [{"x": 0, "y": 0, "shape": 0.7}], "closed": false, "scheme": "kappa"}"#,
    )
    .unwrap();
    assert_eq!(
        doc.points[0],
        EditPoint {
            x: 0.0,
            y: 0.0,
            shape: 0.7,
            corner: false,
            tangent: None,
            tangent_in: None,
        }
    );
}

#[cfg(feature = "render")]
#[test]
fn svg_import_and_export() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200">
        <polyline points="10,10 50,40 90,10 130,40" fill="none" stroke="black"/>
        <g transform="translate(100 100)"><polygon points="0,0 40,0 20,30"/></g>
        <path d="M 0 150 C 20 130 40 170 60 150 L 80 190 Z"/>
    </svg>"#;
    let docs = kappa::editor::import_svg(svg, Scheme::Kappa).unwrap();
    assert_eq!(docs.len(), 3);
    assert!(!docs[0].closed && docs[0].points.len() == 4);
    assert_eq!(docs[0].points[1].point(), Point::new(50.0, 40.0));
    assert!(docs[1].closed && docs[1].points.len() == 3);
    assert_eq!(docs[1].points[2].point(), Point::new(120.0, 130.0));
    assert!(docs[2].closed && docs[2].points.len() == 3);
    assert_eq!(docs[2].points[1].point(), Point::new(60.0, 150.0));
    assert!(matches!(
        kappa::editor::import_svg("not svg", Scheme::Kappa),
        Err(kappa::Error::InvalidSvg(_))
    ));
    // Export: the path data of the solved curve and the points.
    let (e, _) = Editor::from_doc(docs[0].clone());
    let out = e.to_svg(200.0, 200.0, true);
    assert!(out.starts_with("<svg") && out.contains("<path d=\"M10,10 Q"));
    assert_eq!(out.matches("<circle").count(), 4);
    // And back: the exported SVG's path vertices are the curve's segment ends.
    let again = kappa::editor::import_svg(&out, Scheme::Kappa).unwrap();
    assert_eq!(
        again[0].points.first().unwrap().point(),
        Point::new(10.0, 10.0)
    );
}

/// The κ-curve through a dense open sine (45 samples of `(10 i, 50 sin 0.3 i)`) does not
/// converge (docs/curves.md, "Known limits"): a solve that fails for sure.
fn failing_sine(n: usize) -> PathDoc {
    PathDoc {
        points: (0..n)
            .map(|i| EditPoint {
                x: 10.0 * i as f64,
                y: 300.0 + 50.0 * (0.3 * i as f64).sin(),
                // Ignored by κ; εκ-cubic with it converges.
                shape: 0.8,
                corner: false,
                tangent: None,
                tangent_in: None,
            })
            .collect(),
        closed: false,
        scheme: Scheme::Kappa,
        solution: Vec::new(),
    }
}

#[test]
fn a_solve_that_fails_shows_its_best_curve_flagged_also_after_undo_and_redo() {
    let (mut e, change) = Editor::from_doc(failing_sine(45));
    assert_eq!(change.errors.len(), 1);
    let kappa::Error::NotConverged { residual, .. } = change.errors[0].1 else {
        panic!("{:?}", change.errors);
    };
    assert!(residual > 1e-12 && residual.is_finite());
    // Drawn: the best iterate, through the points' neighbourhood, flagged.
    let shown = e.to_bezpath();
    assert!(shown.segments().count() >= 43);
    assert!(shown
        .elements()
        .iter()
        .all(|el| el.end_point().is_some_and(|p| p.is_finite())));
    assert!(matches!(
        e.piece_error(0),
        Some(kappa::Error::NotConverged { .. })
    ));
    // An edit that solves, then undo into the failed state: its curve and message return.
    let p = e.doc().points[20].point();
    let c = e.set_scheme(Scheme::EkCubic);
    assert!(c.errors.is_empty(), "{c:?}");
    assert!(e.undo());
    assert_eq!(e.to_bezpath(), shown);
    assert!(matches!(
        e.errors()[..],
        [(0, kappa::Error::NotConverged { .. })]
    ));
    assert!(e.redo() && e.errors().is_empty());
    assert!(e.undo());
    assert_eq!(e.doc().points[20].point(), p);
    assert_eq!(e.errors().len(), 1);
}

#[test]
fn drag_updates_of_a_failing_long_path_are_capped_and_finished_at_the_end() {
    let (mut e, _) = Editor::from_doc(failing_sine(300));
    let p = e.doc().points[150].point();
    let cap = kappa::editor::DRAG_WORK / 300;
    for k in 1..=5 {
        let c = e.drag_point(150, p + kurbo::Vec2::new(0.0, k as f64));
        // Each update stays within the drag budget, and still shows a curve.
        assert!(
            c.iterations <= cap,
            "update {k}: {} iterations",
            c.iterations
        );
        assert_eq!(c.errors.len(), 1);
        assert!(e.piece_spline(0).is_some());
    }
    // Mouse up: the flagged piece is solved again with the full budget.
    let done = e.end_drag();
    assert_eq!(done.resolved, [0]);
    assert!(done.iterations > cap, "{done:?}");
    assert!(e.piece_spline(0).is_some());
}

#[test]
fn insert_on_curve_never_repeats_a_point() {
    let mut e = Editor::new(Scheme::Kappa);
    for p in [(100.0, 100.0), (200.0, 150.0), (300.0, 100.0)] {
        e.add_point(Point::from(p));
    }
    let (doc, path) = (e.doc().clone(), e.to_bezpath());
    // Beyond the open end: the nearest curve point is the end point itself.
    assert_eq!(e.insert_on_curve(Point::new(350.0, 80.0)), None);
    assert_eq!(e.doc(), &doc);
    assert_eq!(e.to_bezpath(), path);
    // Between points it inserts.
    let (at, c) = e.insert_on_curve(Point::new(150.0, 140.0)).unwrap();
    assert!(c.errors.is_empty() && !c.rejected);
    assert_eq!(at, 1);
}

#[test]
fn structural_edits_that_would_blank_a_piece_are_rejected() {
    let mut e = Editor::new(Scheme::EkCubic);
    for p in wave(8) {
        e.add_point(p);
    }
    let (doc, path) = (e.doc().clone(), e.to_bezpath());
    // A point added on top of the last one: the piece would have no curve.
    let last = doc.points.last().unwrap().point();
    let c = e.add_point(last);
    assert!(c.rejected, "{c:?}");
    assert!(matches!(
        c.errors[..],
        [(_, kappa::Error::RepeatedPoint { .. })]
    ));
    assert_eq!(e.doc(), &doc);
    assert_eq!(e.to_bezpath(), path);
    // Deleting the point between two that coincide.
    let mut twin = doc.clone();
    twin.points[4] = twin.points[2];
    let (mut e2, _) = Editor::from_doc(twin);
    let (twin, before) = (e2.doc().clone(), e2.to_bezpath());
    let c = e2.delete_point(3);
    assert!(c.rejected && e2.doc() == &twin && e2.to_bezpath() == before);
    // Nothing was pushed on the undo stack by the rejected edits.
    assert!(e.undo());
    assert_eq!(e.doc().points.len(), 7);
}

#[test]
fn non_finite_edits_are_rejected_and_documents_round_trip() {
    let mut e = Editor::new(Scheme::EkTrig);
    for p in wave(6) {
        e.add_point(p);
    }
    let doc = e.doc().clone();
    for c in [
        e.add_point(Point::new(f64::NAN, 1.0)),
        e.move_point(2, Point::new(1.0, f64::INFINITY)),
        e.drag_point(3, Point::new(f64::NEG_INFINITY, 0.0)),
        e.set_shape(1, f64::NAN),
        e.drag_shape(1, f64::INFINITY),
    ] {
        assert!(c.rejected, "{c:?}");
        assert_eq!(e.doc(), &doc);
    }
    e.end_drag();
    #[cfg(feature = "serde")]
    {
        let text = serde_json::to_string(e.doc()).unwrap();
        let back: PathDoc = serde_json::from_str(&text).unwrap();
        assert_eq!(&back, e.doc());
    }
}

#[test]
fn huge_drawings_keep_every_piece() {
    // εκ-trig pieces are fitted for drawing: at 1e157 and beyond the fit used to fail and
    // the piece went missing from the path.
    for scale in [1.0, 1e9, 1e157, 1e250] {
        let mut e = Editor::new(Scheme::EkTrig);
        for p in wave(8) {
            e.add_point(Point::new(p.x * scale, p.y * scale));
        }
        assert!(e.errors().is_empty(), "scale {scale:e}: {:?}", e.errors());
        let path = e.to_bezpath();
        assert!(path.segments().count() >= 6, "scale {scale:e}: {path:?}");
        assert!(path.segments().all(|s| s.end().is_finite()));
        // Hit testing finds a point of the curve, at a finite distance relative to the
        // drawing (squared differences overflow beyond 1e154)
        let on = path.segments().nth(2).unwrap().eval(0.4);
        let hit = e.hit_test(on).unwrap();
        // (The drawn path is fitted within 1e-4 of the size to the exact curve hit-tested.)
        assert!(
            hit.distance <= 2e-4 * 140.0 * scale,
            "scale {scale:e}: {hit:?}"
        );
        let off = Point::new(on.x, on.y + 10.0 * scale);
        let hit = e.hit_test(off).unwrap();
        assert!(
            hit.distance.is_finite() && hit.distance <= 10.03 * scale,
            "scale {scale:e}: {hit:?}"
        );
    }
}

/// Reopening the saved document (a JSON round trip where serde is on) shows the live
/// curves: the same segments, and no piece fails that solved live.
fn reopens_as_it_was(e: &Editor) -> Result<(), TestCaseError> {
    #[cfg(feature = "serde")]
    let doc: PathDoc = serde_json::from_str(&serde_json::to_string(e.doc()).unwrap()).unwrap();
    #[cfg(not(feature = "serde"))]
    let doc = e.doc().clone();
    let (f, _) = Editor::from_doc(doc);
    prop_assert_eq!(f.pieces(), e.pieces());
    let size = e
        .doc()
        .points
        .iter()
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(1.0, f64::max);
    for k in 0..e.pieces() {
        if e.piece_error(k).is_some() {
            continue;
        }
        prop_assert!(
            f.piece_error(k).is_none(),
            "piece {} fails on reload: {:?}",
            k,
            f.piece_error(k)
        );
        let (a, b) = (e.piece_spline(k).unwrap(), f.piece_spline(k).unwrap());
        prop_assert_eq!(a.segments().len(), b.segments().len());
        for (x, y) in a.segments().iter().zip(b.segments()) {
            for (p, q) in x.q.iter().zip(&y.q) {
                prop_assert!(
                    (*p - *q).hypot() <= 1e-7 * size,
                    "piece {}: {:?} vs {:?}",
                    k,
                    x,
                    y
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn a_saved_document_reopens_with_the_live_curve(
        scheme in 0usize..3,
        start in prop::collection::vec((0.0f64..900.0, 0.0f64..600.0), 3..16),
        closed in any::<bool>(),
        ops in prop::collection::vec(op(), 1..30),
    ) {
        let mut e = Editor::new([Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig][scheme]);
        for (x, y) in start {
            e.add_point(Point::new(x, y));
        }
        e.set_closed(closed);
        reopens_as_it_was(&e)?;
        for op in &ops {
            apply(&mut e, op);
            reopens_as_it_was(&e)?;
        }
    }
}

/// A drawing of two contours (an `o`): one history over both, Clear undone, and its file
/// (JSON, and inside an SVG) reopens the same drawing; a file of one path from before
/// drawings still opens.
#[cfg(feature = "serde")]
#[test]
fn drawing_of_an_o_round_trips() {
    use kappa::editor::{extract_svg_document, Drawing, DrawingDoc};
    let ring = |r: f64| -> Vec<Point> {
        (0..8)
            .map(|i| {
                let th = f64::from(i) / 8.0 * std::f64::consts::TAU;
                Point::new(300.0 + r * th.cos(), 300.0 + 1.2 * r * th.sin())
            })
            .collect()
    };
    let mut d = Drawing::new(Scheme::EkCubic);
    for r in [150.0, 90.0] {
        let pts = ring(r);
        let (k, _) = d.start_contour(pts[0]);
        for &p in &pts[1..] {
            d.add_point(k, p);
        }
        d.set_closed(k, true);
    }
    d.toggle_corner(1, 0);
    assert!(d.errors().is_empty());
    let doc = DrawingDoc::of(&d);
    assert!(d.clear() && d.is_empty());
    assert!(d.undo());
    assert_eq!(DrawingDoc::of(&d), doc);
    let svg = d.to_svg_with_document(600.0, 600.0, true);
    // Each closed contour is one subpath ending in Z, the cornered one too.
    let path = svg
        .split("<path d=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap();
    assert_eq!(path.matches('M').count(), 2);
    assert_eq!(path.matches('Z').count(), 2);
    let back = extract_svg_document(&svg).unwrap();
    assert_eq!(back, doc);
    let (again, changes) = Drawing::from_docs(back.contours, Scheme::Kappa);
    assert_eq!(again.len(), 2);
    assert!(changes.iter().all(|c| c.errors.is_empty()));
    // One path's document, as saved before drawings had several contours.
    let one = r#"{"points":[{"x":0.0,"y":0.0,"shape":0.8,"corner":false},
        {"x":100.0,"y":40.0,"shape":0.8,"corner":false},{"x":200.0,"y":0.0,"shape":0.8,
        "corner":false}],"closed":false,"scheme":"ek-cubic"}"#;
    let old = DrawingDoc::from_json(one).unwrap();
    let (d, _) = Drawing::from_docs(old.contours, Scheme::Kappa);
    assert_eq!(d.len(), 1);
    assert_eq!(d.scheme(), Scheme::EkCubic);
    assert_eq!(d.contour(0).unwrap().pieces(), 1);
}

#[derive(Clone, Debug)]
enum DrawOp {
    Start(f64, f64),
    Edit(usize, Op),
    DeleteContour(usize),
    Clear,
    Scheme(usize),
    Undo,
    Redo,
}

fn draw_op() -> impl Strategy<Value = DrawOp> {
    prop_oneof![
        4 => (0.0f64..200.0, 0.0f64..200.0).prop_map(|(x, y)| DrawOp::Start(x, y)),
        12 => (0usize..4, op()).prop_map(|(k, o)| DrawOp::Edit(k, o)),
        8 => (0usize..4, 0.0f64..200.0, 0.0f64..200.0)
            .prop_map(|(k, x, y)| DrawOp::Edit(k, Op::Add(x, y))),
        // Hostile input: refused, nothing recorded.
        1 => Just(DrawOp::Start(f64::NAN, 1.0)),
        1 => (0usize..4).prop_map(|k| DrawOp::Edit(k, Op::Add(f64::INFINITY, 0.0))),
        1 => (0usize..4, 0usize..20).prop_map(|(k, i)| DrawOp::Edit(k, Op::Move(i, f64::NAN, 0.0))),
        1 => (0usize..4).prop_map(DrawOp::DeleteContour),
        1 => Just(DrawOp::Clear),
        1 => (0usize..3).prop_map(DrawOp::Scheme),
        2 => Just(DrawOp::Undo),
        2 => Just(DrawOp::Redo),
    ]
}

/// The points, closed flags and schemes of a drawing's contours.
fn outline_of(d: &kappa::editor::Drawing) -> Vec<(Vec<EditPoint>, bool, Scheme)> {
    d.docs()
        .into_iter()
        .map(|c| (c.points, c.closed, c.scheme))
        .collect()
}

fn apply_draw(d: &mut kappa::editor::Drawing, op: &DrawOp) {
    let schemes = [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig];
    match op {
        DrawOp::Start(x, y) => {
            d.start_contour(Point::new(*x, *y));
        }
        DrawOp::Edit(k, o) => {
            let k = k % d.len().max(1);
            let Some(e) = d.contour(k) else { return };
            let n = e.doc().points.len().max(1);
            let at = |i: usize| e.doc().points.get(i % n).map(|p| p.point());
            match *o {
                Op::Add(x, y) => {
                    d.add_point(k, Point::new(x, y));
                }
                Op::Move(i, dx, dy) => {
                    if let Some(p) = at(i) {
                        d.move_point(k, i % n, p + kurbo::Vec2::new(dx, dy));
                    }
                }
                Op::Drag(i, dx, dy) => {
                    if let Some(p) = at(i) {
                        d.drag_point(k, i % n, p + kurbo::Vec2::new(dx, dy));
                    }
                }
                Op::DragShape(i, a) => {
                    d.drag_shape(k, i % n, a);
                }
                Op::EndDrag => {
                    d.end_drag();
                }
                Op::Insert(x, y) => {
                    d.insert_on_curve(Point::new(x, y));
                }
                Op::Delete(i) => {
                    d.delete_point(k, i % n);
                }
                Op::Shape(i, a) => {
                    d.set_shape(k, i % n, a);
                }
                Op::Corner(i) => {
                    d.toggle_corner(k, i % n);
                }
                Op::Close(c) => {
                    d.set_closed(k, c);
                }
                Op::Scheme(s) => {
                    d.set_scheme(schemes[s]);
                }
                Op::Undo => {
                    d.undo();
                }
                Op::Redo => {
                    d.redo();
                }
            }
        }
        DrawOp::DeleteContour(k) => {
            d.delete_contour(k % d.len().max(1));
        }
        DrawOp::Clear => {
            d.clear();
        }
        DrawOp::Scheme(s) => {
            d.set_scheme(schemes[*s]);
        }
        DrawOp::Undo => {
            d.undo();
        }
        DrawOp::Redo => {
            d.redo();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    /// Random edits of a drawing of several contours: every contour's curve stays right,
    /// undoing everything leaves an empty drawing, and redoing everything brings back the
    /// same contours.
    #[test]
    fn random_drawing_edits_undo_and_redo_exactly(ops in prop::collection::vec(draw_op(), 1..60)) {
        let mut d = kappa::editor::Drawing::new(Scheme::EkCubic);
        for o in &ops {
            apply_draw(&mut d, o);
        }
        d.end_drag();
        for e in d.contours() {
            check(e);
        }
        let end = outline_of(&d);
        let mut steps = 0;
        while d.undo() {
            steps += 1;
        }
        prop_assert!(d.is_empty());
        for _ in 0..steps {
            prop_assert!(d.redo());
        }
        prop_assert_eq!(outline_of(&d), end);
    }
}

/// The largest distance between two paths of the same segments, sampled at 9 parameters.
fn path_gap(a: &kurbo::BezPath, b: &kurbo::BezPath) -> f64 {
    let (sa, sb): (Vec<_>, Vec<_>) = (a.segments().collect(), b.segments().collect());
    assert_eq!(sa.len(), sb.len());
    sa.iter()
        .zip(&sb)
        .flat_map(|(x, y)| {
            (0..=8).map(move |i| (x.eval(i as f64 / 8.0) - y.eval(i as f64 / 8.0)).hypot())
        })
        .fold(0.0, f64::max)
}

/// A document point without tangents.
fn plain_point(x: f64, y: f64, corner: bool) -> EditPoint {
    EditPoint {
        x,
        y,
        shape: 0.8,
        corner,
        tangent: None,
        tangent_in: None,
    }
}

#[test]
fn tangents_are_held_undone_and_saved() {
    use kurbo::Vec2;
    let doc = PathDoc {
        points: vec![
            plain_point(100.0, 100.0, false),
            plain_point(300.0, 80.0, false),
            plain_point(320.0, 260.0, false),
            plain_point(120.0, 280.0, false),
        ],
        closed: true,
        scheme: Scheme::EkCubic,
        solution: Vec::new(),
    };
    let (mut editor, change) = Editor::from_doc(doc);
    assert!(change.errors.is_empty());
    let free = editor.to_bezpath();
    let seg = &editor.piece_spline(0).unwrap().segments()[1];
    let d = seg.derivative(seg.t_max);
    let turned = Vec2::from_angle(d.atan2() + 0.05);
    let change = editor.set_tangent(1, Some(turned * 3.0), false);
    assert!(change.errors.is_empty() && !change.rejected, "{change:?}");
    let seg = &editor.piece_spline(0).unwrap().segments()[1];
    let d = seg.derivative(seg.t_max);
    assert!(turned.cross(d).atan2(turned.dot(d)).abs() <= 1e-9);
    // Saved and reopened (serde), the same curve.
    let text = serde_json::to_string(editor.doc()).unwrap();
    assert!(text.contains("\"tangent\""));
    let (reopened, _) = Editor::from_doc(serde_json::from_str(&text).unwrap());
    let (a, b) = (reopened.to_bezpath(), editor.to_bezpath());
    assert!(path_gap(&a, &b) <= 1e-9 * 300.0);
    // Undo gives the free curve back; bad tangents are rejected.
    assert!(editor.undo());
    assert!(path_gap(&editor.to_bezpath(), &free) <= 1e-9 * 300.0);
    for bad in [Vec2::ZERO, Vec2::new(f64::NAN, 1.0)] {
        assert!(editor.set_tangent(2, Some(bad), false).rejected);
    }
}

#[test]
fn a_corner_with_the_line_s_direction_is_a_smooth_join() {
    use kurbo::Vec2;
    // A line from (0, 0) to (200, 0), then a curve through two points back up: the join at
    // (200, 0) is a corner whose outgoing tangent runs along the line.
    let mut points = vec![
        plain_point(0.0, 0.0, true),
        plain_point(200.0, 0.0, true),
        plain_point(300.0, 60.0, false),
        plain_point(260.0, 160.0, false),
    ];
    points[1].tangent = Some([1.0, 0.0]);
    let doc = PathDoc {
        points,
        closed: false,
        scheme: Scheme::Kappa,
        solution: Vec::new(),
    };
    let (editor, change) = Editor::from_doc(doc);
    assert!(change.errors.is_empty(), "{:?}", change.errors);
    let curve = editor.piece_spline(1).unwrap();
    let d = curve.segments()[0].derivative(0.0);
    let line = Vec2::new(1.0, 0.0);
    assert!(line.cross(d).atan2(line.dot(d)).abs() <= 1e-9, "{d:?}");
}
