//! One function per fuzz target: decode the bytes, call the entry point, check the answer.
//! The fuzz targets and the smoke test call exactly these.

use kappa::{Scheme, Shape, SolveOptions, Solver};

use super::inputs::Gen;
use super::oracles::*;

/// Solver options: mostly the defaults, sometimes a small cap, a looser tolerance or a bad
/// tolerance.
fn options(g: &mut Gen) -> SolveOptions {
    let mut o = SolveOptions::default();
    match g.below(8) {
        0 => o.max_iterations = g.below(20),
        1 => o.tolerance = g.pick(&[1e-9, 1e-6, 0.0, -1.0, f64::NAN, f64::INFINITY]),
        2 => {
            o.max_iterations = g.below(50);
            o.accept_unconverged = true;
        }
        _ => {}
    }
    o
}

/// κ, εκ-cubic and εκ-trig solves, open and closed, with shapes.
pub fn solve2d(data: &[u8]) {
    let mut g = Gen::new(data);
    let scheme = g.scheme();
    let closed = g.flag();
    let opts = options(&mut g);
    let points = g.points(40);
    let shape = g.shape(scheme, points.len());
    let result = Solver::with_options(opts).solve(&points, closed, scheme, &shape);
    let what = format!("solve {scheme:?} closed={closed} {shape:?} {opts:?} {points:?}");
    check_solve2d(&points, closed, scheme, &shape, &opts, &result, &what);
}

/// A solve, then warm re-solves after perturbations of the points or the shapes.
pub fn resolve(data: &[u8]) {
    let mut g = Gen::new(data);
    let scheme = g.scheme();
    let closed = g.flag();
    let opts = options(&mut g);
    let mut points = g.points(24);
    let mut shape = g.shape(scheme, points.len());
    let mut solver = Solver::with_options(opts);
    let first = solver.solve(&points, closed, scheme, &shape);
    // The points of the solver's last problem: what `resolve_shapes` re-solves.
    let mut solver_points = points.clone();
    let what = format!("solve {scheme:?} closed={closed} {shape:?} {opts:?} {points:?}");
    check_solve2d(&points, closed, scheme, &shape, &opts, &first, &what);
    let mut scheme = scheme;
    for step in 0..4 {
        if g.is_empty() {
            break;
        }
        match g.below(6) {
            // Move one point by a small or large amount.
            0..=2 if !points.is_empty() => {
                let i = g.below(points.len());
                let size = size_of(&arrays(&points)).max(1e-300);
                let d = size * g.pick(&[1e-12, 1e-6, 1e-3, 0.1, 1.0, 10.0]);
                points[i].x += d * g.unit();
                points[i].y += d * g.unit();
                if g.below(8) == 0 {
                    // Onto its neighbour.
                    points[i] = points[(i + 1) % points.len()];
                }
            }
            // Another number of points.
            3 => {
                if g.flag() || points.is_empty() {
                    let p = g.points(1);
                    points.extend(p);
                } else {
                    points.pop();
                }
            }
            // New shapes (the slider).
            _ => {
                let new_scheme = g.scheme();
                let new_shape = g.shape(new_scheme, points.len());
                let r = solver.resolve_shapes(new_scheme, &new_shape);
                let what = format!("{what}; step {step}: shapes {new_scheme:?} {new_shape:?}");
                if let Ok(_) | Err(kappa::Error::NotConverged { .. }) = &r {
                    // The solver took the new shapes.
                    scheme = new_scheme;
                    shape = new_shape;
                }
                check_resolved(&solver_points, scheme, &opts, &r, &what);
                continue;
            }
        }
        let r = solver.resolve(&points);
        // The solver takes the points unless it returns early: without a previous solve, or
        // with per-point shapes that cannot follow another number of points.
        let early = match &r {
            Err(kappa::Error::InvalidOption(_)) => true,
            Err(kappa::Error::ShapeCount { .. }) => points.len() != solver_points.len(),
            _ => false,
        };
        if !early {
            solver_points.clone_from(&points);
        }
        let what = format!("{what}; step {step}: {points:?}");
        check_resolved(&points, scheme, &opts, &r, &what);
    }
    let _ = shape;
}

/// Checks a warm re-solve: as a solve of the current points, except that shape errors (the
/// shapes carried over from earlier solves) and "no previous solve" are only typed.
fn check_resolved(
    points: &[kurbo::Point],
    scheme: Scheme,
    opts: &SolveOptions,
    r: &Result<kappa::Spline, kappa::Error>,
    what: &str,
) {
    use kappa::Error;
    match r {
        Err(Error::InvalidOption(_) | Error::ShapeCount { .. } | Error::ShapeOutOfRange { .. }) => {
        }
        // A re-solve keeps the scheme and closedness of the last problem set up.
        Ok(s) => check_solve2d(
            points,
            s.is_closed(),
            s.scheme(),
            &Shape::Neutral,
            opts,
            r,
            what,
        ),
        // (The closedness of the last problem may differ from the one asked: the permissive
        // check of a repeated pair is the closed one.)
        Err(_) => check_solve2d(points, true, scheme, &Shape::Neutral, opts, r, what),
    }
}

/// G1 and G2 Hermite problems with every kind of profile.
pub fn hermite(data: &[u8]) {
    use kappa::intrinsic::{Control, Hermite, HermiteEnd, Profile, Turning};
    let mut g = Gen::new(data);
    let start = kurbo::Point::new(g.number(), g.number());
    let chord = g.scale() * if g.below(16) == 0 { 1e-12 } else { 1.0 };
    let dir = g.angle();
    let end = if g.below(16) == 0 {
        kurbo::Point::new(g.number(), g.number())
    } else {
        start + chord * kurbo::Vec2::new(dir.cos(), dir.sin())
    };
    let g2 = g.flag();
    let curvature = |g: &mut Gen| {
        g2.then(|| match g.below(6) {
            0 => g.number(),
            _ => g.unit() * g.pick(&[0.1, 1.0, 5.0]) / chord,
        })
    };
    let h = Hermite {
        start: HermiteEnd {
            point: start,
            angle: g.angle(),
            curvature: curvature(&mut g),
        },
        end: HermiteEnd {
            point: end,
            angle: g.angle(),
            curvature: if g.below(32) == 0 {
                None
            } else {
                curvature(&mut g)
            },
        },
        turning: if g.flag() {
            Turning::Nearest
        } else {
            Turning::AsGiven
        },
    };
    let degree = if g.below(16) == 0 {
        g.below(24)
    } else {
        g.below(8)
    };
    let controls: Vec<Control> = (0..=degree)
        .map(|_| match g.below(8) {
            0 => Control::Given(g.unit() * g.pick(&[0.1, 1.0, 10.0]) / chord),
            1 => Control::Same(g.below(degree + 2)),
            2 if g.below(8) == 0 => Control::Given(g.number()),
            _ => Control::Free,
        })
        .collect();
    let weights = (g.below(4) == 0).then(|| {
        let len = if g.below(8) == 0 {
            g.below(degree + 3)
        } else {
            degree + 1
        };
        (0..len)
            .map(|_| match g.below(8) {
                0 => g.number(),
                _ => 0.1 + 3.0 * g.fraction(),
            })
            .collect::<Vec<f64>>()
    });
    let profile = Profile { controls, weights };
    let result = h.solve(&profile);
    check_hermite(&h, &profile, &result, &format!("{h:?} {profile:?}"));
}

/// Uniform cubic B-splines through hostile points, 2D and 3D, open and closed, with their
/// maximum curvature.
pub fn bspline(data: &[u8]) {
    let mut g = Gen::new(data);
    let closed = g.flag();
    if g.flag() {
        let points = g.points(60);
        let r = kappa::BSpline::new(&points, closed);
        check_bspline2d(&points, closed, &r, &format!("closed={closed} {points:?}"));
    } else {
        let points = g.points3(60);
        let r = kappa::BSpline3::new(&points, closed);
        check_bspline3d(&points, closed, &r, &format!("closed={closed} {points:?}"));
    }
}

/// κ-space curves through hostile 3D points with every option.
pub fn space(data: &[u8]) {
    use kappa::space::{Gamma, PeakAtJoint, Replace, SpaceCurve, SpaceOptions};
    let mut g = Gen::new(data);
    let closed = g.flag();
    let points = g.points3(16);
    let replace = match g.below(8) {
        0 => Replace::None,
        1 => Replace::FULL,
        2 => Replace::Partial {
            t1: g.number(),
            t2: g.number(),
        },
        3 => Replace::fraction(g.number()),
        _ => Replace::fraction(g.pick(&[0.01, 0.05, 0.2, 0.5])),
    };
    let joints = if closed {
        points.len()
    } else {
        points.len().saturating_sub(3)
    };
    let gamma = match g.below(8) {
        0 => Gamma::Optimized,
        1 => {
            let len = if g.flag() {
                joints
            } else {
                g.below(joints + 2)
            };
            Gamma::PerJoint(
                (0..len)
                    .map(|_| g.pick(&[0.5, 0.0, 1.0]) + 0.3 * g.unit())
                    .collect(),
            )
        }
        _ => Gamma::Lambda,
    };
    let at_joint = if g.flag() {
        PeakAtJoint::Replace
    } else {
        PeakAtJoint::Keep
    };
    let options = SpaceOptions {
        replace,
        gamma,
        at_joint,
        solve: SolveOptions::default(),
    };
    let r = SpaceCurve::new(&points, closed, &options);
    check_space(
        &points,
        closed,
        &options,
        &r,
        &format!("{options:?} closed={closed} {points:?}"),
    );
}

/// The editor: a hostile document (from SVG, or points), then a random edit sequence.
pub fn editor(data: &[u8]) {
    use kappa::editor::{EditPoint, Editor, PathDoc};
    let mut g = Gen::new(data);
    let scheme = g.scheme();
    let mut ed = match g.below(5) {
        #[cfg(feature = "render")]
        0 | 4 => {
            let svg = if g.flag() {
                // Any text at all.
                String::from_utf8_lossy(g.chunk(2048)).into_owned()
            } else {
                let points = g.points(12);
                let closed = g.flag();
                svg_of(&points, closed, g.below(4))
            };
            match kappa::editor::import_svg(&svg, scheme) {
                Ok(docs) => {
                    for d in &docs {
                        assert!(
                            d.points.iter().all(|p| p.x.is_finite() && p.y.is_finite()),
                            "{svg}: {d:?}"
                        );
                    }
                    let doc = docs.into_iter().next().unwrap_or_default();
                    Editor::from_doc(doc).0
                }
                Err(kappa::Error::InvalidSvg(_)) => return,
                Err(e) => panic!("{svg}: {e:?}"),
            }
        }
        1 => {
            let points = g.points(12);
            let doc = PathDoc {
                points: points
                    .iter()
                    .map(|p| EditPoint {
                        x: p.x,
                        y: p.y,
                        shape: g.shape_value(scheme),
                        corner: g.below(6) == 0,
                        tangent: None,
                        tangent_in: None,
                    })
                    .collect(),
                closed: g.flag(),
                scheme,
                solution: Vec::new(),
            };
            Editor::from_doc(doc).0
        }
        _ => Editor::new(scheme),
    };
    check_editor(&ed, "start");
    let mut log = String::new();
    for _ in 0..24 {
        if g.is_empty() {
            break;
        }
        let n = ed.doc().points.len();
        let p = {
            let q = g.points(1);
            match (q.first(), n) {
                (Some(&q), 0) => q,
                (None, 0) => kurbo::Point::new(g.number(), g.number()),
                (Some(&q), _) if g.flag() => q,
                _ => {
                    // Near an existing point: drags, near-duplicates.
                    let base = ed.doc().points[g.below(n.max(1)).min(n.saturating_sub(1))].point();
                    let d = g.pick(&[0.0, 1e-12, 1e-6, 1.0, 100.0]);
                    base + kurbo::Vec2::new(d * g.unit(), d * g.unit())
                }
            }
        };
        let i = g.below(n + 1);
        let op = g.below(11);
        log.push_str(&format!("op {op} i {i} p {p:?}; "));
        let change = match op {
            0 | 1 => Some(ed.add_point(p)),
            2 => ed.insert_on_curve(p).map(|(_, c)| c),
            3 | 4 => Some(ed.move_point(i, p)),
            5 => Some(ed.delete_point(i)),
            6 => Some(ed.set_shape(i, g.shape_value(ed.doc().scheme))),
            7 => Some(ed.toggle_corner(i)),
            8 => Some(ed.set_closed(g.flag())),
            9 => Some(ed.set_scheme(g.scheme())),
            _ => {
                if g.flag() {
                    ed.undo();
                } else {
                    ed.redo();
                }
                None
            }
        };
        if let Some(c) = change {
            assert!(c.resolved.iter().all(|&k| k < ed.pieces()), "{log}: {c:?}");
        }
        check_editor(&ed, &log);
    }
}

/// An SVG document drawing `points` as a path, polyline or polygon.
pub fn svg_of(points: &[kurbo::Point], closed: bool, kind: usize) -> String {
    let coords: Vec<String> = points.iter().map(|p| format!("{} {}", p.x, p.y)).collect();
    let body = match kind {
        0 => format!("<polyline points=\"{}\"/>", coords.join(" ")),
        1 => format!("<polygon points=\"{}\"/>", coords.join(" ")),
        2 => format!(
            "<g transform=\"rotate(30) scale(2)\"><path d=\"M {}{}\"/></g>",
            coords.join(" L "),
            if closed { " Z" } else { "" }
        ),
        _ => format!(
            "<path d=\"M {}{}\"/>",
            coords.join(" L "),
            if closed { " Z" } else { "" }
        ),
    };
    format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"100\">{body}</svg>")
}

/// The font importer on hostile bytes: parse, outlines, drafting of small glyphs.
#[cfg(feature = "font")]
pub fn font(data: &[u8]) {
    let Ok(font) = kappa::glyph::FontOutlines::parse(data) else {
        return;
    };
    check_font(&font, data);
}

/// Without the `font` feature there is nothing to fuzz.
#[cfg(not(feature = "font"))]
pub fn font(_: &[u8]) {}

/// The command-line tool's JSON inputs: every parser on the same text; what parses is solved
/// (when small) and checked like any other input.
#[cfg(feature = "serde")]
pub fn cli_json(data: &[u8]) {
    use kappa::input::{
        BSplineInput, BSplinePoints, CurveInput, HermiteInput, InputLimits, SpaceInput,
    };
    let text = String::from_utf8_lossy(data);
    let limits = InputLimits { max_points: 64 };
    let typed = |e: &kappa::Error| {
        assert!(
            matches!(e, kappa::Error::InvalidInput(m) if !m.is_empty() && !m.contains('\n')),
            "{text}: {e:?}"
        )
    };
    match CurveInput::from_json(&text, &limits) {
        Ok(c) => {
            assert!(c.points.len() <= 64 && c.points.iter().all(|p| p.is_finite()));
            if c.points.len() <= 24 {
                let opts = SolveOptions::default();
                let r = Solver::new().solve(&c.points, c.closed, c.scheme, &c.shape);
                check_solve2d(&c.points, c.closed, c.scheme, &c.shape, &opts, &r, &text);
            }
        }
        Err(e) => typed(&e),
    }
    match BSplineInput::from_json(&text, &limits) {
        Ok(b) => match b.points {
            BSplinePoints::Plane(p) => {
                assert!(p.len() <= 64);
                check_bspline2d(&p, b.closed, &kappa::BSpline::new(&p, b.closed), &text);
            }
            BSplinePoints::Space(p) => {
                assert!(p.len() <= 64);
                check_bspline3d(&p, b.closed, &kappa::BSpline3::new(&p, b.closed), &text);
            }
        },
        Err(e) => typed(&e),
    }
    match SpaceInput::from_json(&text, &limits) {
        Ok(s) => {
            assert!((0.0..=1.0).contains(&s.replace));
            if s.points.len() <= 12 {
                let options = kappa::space::SpaceOptions::default().with_replace(s.replace);
                let r = kappa::SpaceCurve::new(&s.points, s.closed, &options);
                check_space(&s.points, s.closed, &options, &r, &text);
            }
        }
        Err(e) => typed(&e),
    }
    match HermiteInput::from_json(&text) {
        Ok(h) => {
            assert!(h.profile.degree() <= kappa::input::MAX_HERMITE_DEGREE);
            if h.profile.degree() <= 12 {
                let r = h.hermite.solve(&h.profile);
                check_hermite(&h.hermite, &h.profile, &r, &text);
            }
        }
        Err(e) => typed(&e),
    }
}

/// Without the `serde` feature there is no JSON input.
#[cfg(not(feature = "serde"))]
pub fn cli_json(_: &[u8]) {}
