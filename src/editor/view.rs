//! What the editor draws: the path as kurbo paths, its curvature comb and SVG, and hit
//! testing.

use kurbo::{BezPath, Point};

use crate::fit::{FitMethod, FitOptions};
use crate::Segment;

use super::Editor;

/// The result of [`Editor::hit_test`]: the nearest point on the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The piece.
    pub piece: usize,
    /// The segment within the piece.
    pub segment: usize,
    /// The parameter on that segment.
    pub t: f64,
    /// The nearest curve point.
    pub point: Point,
    /// Its distance from the query point.
    pub distance: f64,
}

impl Editor {
    /// The whole path as a kurbo path (one subpath per piece; a closed path without corners
    /// is one closed subpath): exact for κ and εκ-cubic; εκ-trig pieces are fitted by
    /// Hermite subdivision within 1e-4 of their size (fast enough for every drag; export
    /// through [`Editor::piece_spline`] and [`Spline::fit`](crate::Spline::fit) for kurbo's fewer cubics).
    pub fn to_bezpath(&self) -> BezPath {
        let mut out = BezPath::new();
        for k in 0..self.pieces.len() {
            append(&mut out, self.piece_bezpath(k));
        }
        out
    }

    /// The path as one subpath, the pieces joined end to start, closed (`Z`) when the path
    /// is closed — what an SVG or font outline holds. A piece without a curve leaves a gap
    /// (the next piece starts a new subpath, and the path is not closed).
    pub fn outline(&self) -> BezPath {
        self.joined(|k| self.piece_bezpath(k))
    }

    /// [`outline`](Self::outline) with a node at every point and every joint of the curve,
    /// in a structure fixed by the document's topology: each piece's
    /// [`Spline::to_node_bezpath`](crate::Spline::to_node_bezpath), and a line for a piece
    /// of two points (between corners). Two documents with the same number of points,
    /// the same corners and the same closed flag give paths with the same elements in the
    /// same order, whatever the positions, shapes and tangents: the outlines of font
    /// masters drawn from them interpolate.
    pub fn node_outline(&self) -> BezPath {
        self.joined(|k| {
            let Some(s) = self.piece_spline(k) else {
                return BezPath::new();
            };
            let points = self.piece_points(k);
            if !s.is_closed() && points.len() == 2 {
                let mut line = BezPath::new();
                line.move_to(self.doc.points[points[0]].point());
                line.line_to(self.doc.points[points[1]].point());
                return line;
            }
            s.to_node_bezpath()
        })
    }

    /// The pieces' paths (`piece`) joined into one subpath, as [`outline`](Self::outline)
    /// describes.
    fn joined(&self, piece: impl Fn(usize) -> BezPath) -> BezPath {
        let mut out = BezPath::new();
        let mut joined = false;
        let mut whole = !self.pieces.is_empty();
        for k in 0..self.pieces.len() {
            let path = piece(k);
            if path.elements().is_empty() {
                joined = false;
                whole = false;
                continue;
            }
            for (j, el) in path.elements().iter().enumerate() {
                match el {
                    kurbo::PathEl::MoveTo(_) if j == 0 && joined => {}
                    kurbo::PathEl::ClosePath => {}
                    el => out.push(*el),
                }
            }
            joined = true;
        }
        if whole && self.doc.closed && self.doc.points.len() >= 3 {
            out.close_path();
        }
        out
    }

    /// Piece `k` as a kurbo path, as [`Editor::to_bezpath`] draws it (empty without a
    /// curve or for an out-of-range `k`). A page can draw the pieces flagged by
    /// [`Editor::piece_error`] in a warning style.
    pub fn piece_bezpath(&self, k: usize) -> BezPath {
        let Some(s) = self.piece_spline(k) else {
            return BezPath::new();
        };
        if s.scheme().is_polynomial() {
            return s.to_bezpath();
        }
        let options = FitOptions {
            method: FitMethod::Hermite,
            ..FitOptions::default()
        };
        // A drawn curve is finite, so fitting it cannot fail.
        s.fit(&options).map(|f| f.path).unwrap_or_default()
    }

    /// A curvature comb of the exact curve, `samples` teeth per segment.
    pub fn curvature_comb(&self, scale: f64, samples: usize) -> BezPath {
        let mut out = BezPath::new();
        for piece in &self.pieces {
            if let Some(s) = &piece.spline {
                append(&mut out, s.curvature_comb(scale, samples));
            }
        }
        out
    }

    /// The nearest point of the curve to `p`, or `None` if there is no curve (or `p` is not
    /// finite).
    pub fn hit_test(&self, p: Point) -> Option<Hit> {
        if !p.is_finite() {
            return None;
        }
        let mut best: Option<Hit> = None;
        for (k, piece) in self.pieces.iter().enumerate() {
            let Some(spline) = &piece.spline else {
                continue;
            };
            for (j, seg) in spline.segments().iter().enumerate() {
                let (t, q) = nearest_on_segment(seg, p);
                // (f64::hypot: the squares of coordinates beyond 1e154 overflow.)
                let d = (q.x - p.x).hypot(q.y - p.y);
                if d.is_nan() {
                    continue;
                }
                if best.map_or(true, |b| d < b.distance) {
                    best = Some(Hit {
                        piece: k,
                        segment: j,
                        t,
                        point: q,
                        distance: d,
                    });
                }
            }
        }
        best
    }

    /// The path as an SVG document of the given size (user units), stroked, optionally
    /// with its points.
    pub fn to_svg(&self, width: f64, height: f64, with_points: bool) -> String {
        use core::fmt::Write as _;
        let d = crate::svg_path_data(&self.to_bezpath());
        let mut out = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
             viewBox=\"0 0 {width} {height}\">\n<path d=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
            d
        );
        if with_points {
            for q in &self.doc.points {
                let _ = writeln!(
                    out,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"red\"/>",
                    q.x, q.y
                );
            }
        }
        out.push_str("</svg>\n");
        out
    }
}

/// Appends `path` to `out`, taking it whole when `out` is empty (one piece: no copy).
fn append(out: &mut BezPath, path: BezPath) {
    if out.elements().is_empty() {
        *out = path;
    } else {
        out.extend(path.elements().iter().copied());
    }
}

/// The nearest point of a segment to `p`: 64 samples, then golden-section refinement.
fn nearest_on_segment(seg: &Segment<Point>, p: Point) -> (f64, Point) {
    const SAMPLES: usize = 64;
    // Distances compared in units of the segment's extent: squared differences of
    // coordinates near 1e154 and beyond overflow.
    let [q0, q1, q2] = seg.q;
    let unit = [q1 - q0, q2 - q1, p - q0]
        .iter()
        .map(|v| v.x.abs().max(v.y.abs()))
        .fold(f64::MIN_POSITIVE, f64::max);
    let dist = |t: f64| ((seg.eval(t) - p) / unit).hypot2();
    let mut best = 0;
    let mut best_d = f64::INFINITY;
    for i in 0..=SAMPLES {
        let d = dist(i as f64 / SAMPLES as f64);
        if d < best_d {
            best = i;
            best_d = d;
        }
    }
    let (mut a, mut b) = (
        best.saturating_sub(1) as f64 / SAMPLES as f64,
        (best + 1).min(SAMPLES) as f64 / SAMPLES as f64,
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..50 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if dist(x1) < dist(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    let t = 0.5 * (a + b);
    (t, seg.eval(t))
}
