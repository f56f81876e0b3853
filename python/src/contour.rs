//! Contours of the path tool and of glyph κ sources: points with shapes, corners and
//! tangents, solved piece by piece by the library's editing engine.

use kappa::editor::{EditPoint, Editor, PathDoc};
use kappa::glyph::{
    anchor_outline, orient, Anchor, AnchorKind, Direction, DraftedContour, DraftedGlyph, Piece,
};
use kurbo::{BezPath, Shape as _};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

use crate::curve::{scheme, scheme_name, Curve};
use crate::errors::to_py;
use crate::points::{self, Element};

/// Default accuracy of the anchor-node outline where a span needs several cubics, relative
/// to the contour's size.
const NODE_ACCURACY: f64 = 1e-4;

/// Default tolerance of the anchor-node outline: a span between two anchors is one cubic
/// where that cubic is within half of it, relative to the contour's size.
/// 4e-3 is `kappa font`'s default drafting tolerance (0.004 em): on a four-point κ "o" one
/// cubic per quarter is 1–2.7 units of a 600-unit glyph off the exact curve.
const NODE_TOLERANCE: f64 = 4e-3;

/// A contour: points with a shape each, corner flags and optional tangents, open or
/// closed, solved as the path tool solves it — one curve per piece between corners, or
/// one closed curve when a closed contour has no corner.
///
/// Construct it from points (`Contour(points, closed, ...)`) or read glyph κ sources with
/// `contours_from_json`. Pieces that did not converge keep their best curve; `errors`
/// lists them and `check()` raises the first.
#[pyclass(module = "kappa", frozen)]
pub struct Contour {
    pub editor: Editor,
}

/// A per-point list argument: `None`, or a sequence of the contour's length.
fn per_point<T>(v: Option<Vec<T>>, n: usize, what: &str) -> PyResult<Option<Vec<T>>> {
    match v {
        Some(v) if v.len() != n => Err(PyValueError::new_err(format!(
            "expected {n} {what} (one per point), got {}",
            v.len()
        ))),
        v => Ok(v),
    }
}

impl Contour {
    /// A contour from a path-tool document.
    pub fn from_doc(doc: PathDoc) -> Contour {
        let (editor, _) = Editor::from_doc(doc);
        Contour { editor }
    }

    /// Piece `k` as a path: a straight line for a piece of two points (the solver's
    /// segment there is a straight Bézier), else the piece's exact curve (εκ-trig fitted).
    fn piece_path(&self, k: usize) -> BezPath {
        let idx = self.editor.piece_points(k);
        let straight =
            idx.len() == 2 && self.editor.piece_spline(k).is_some_and(|s| !s.is_closed());
        if straight {
            let pts = &self.editor.doc().points;
            let mut p = BezPath::new();
            p.move_to(pts[idx[0]].point());
            p.line_to(pts[idx[1]].point());
            return p;
        }
        self.editor.piece_bezpath(k)
    }

    /// The outline: pieces joined end to start, closed when the contour is (as
    /// `Editor::outline`, with pieces of two points as lines). A piece without a curve
    /// leaves a gap.
    pub fn outline(&self) -> BezPath {
        let mut out = BezPath::new();
        let (mut joined, mut whole) = (false, self.editor.pieces() > 0);
        for k in 0..self.editor.pieces() {
            let path = self.piece_path(k);
            if path.elements().is_empty() {
                (joined, whole) = (false, false);
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
        let doc = self.editor.doc();
        if whole && doc.closed && doc.points.len() >= 3 {
            out.close_path();
        }
        out
    }

    /// The outline with the anchors (the contour's points) as its nodes (the library's
    /// `glyph::anchor_outline`, as `kappa font` writes UFO outlines): each span between two
    /// anchors one cubic where one is within `tolerance / 2`, else cubics within
    /// `accuracy`; with the largest distance measured from the exact curve. Open contours
    /// and contours with a piece that has no curve give their joint outline (distance 0).
    pub fn anchor_path(&self, accuracy: Option<f64>, tolerance: Option<f64>) -> (BezPath, f64) {
        let exact = self.outline();
        let doc = self.editor.doc();
        let n = self.editor.pieces();
        if !doc.closed || doc.points.len() < 3 || n == 0 {
            return (exact, 0.0);
        }
        let mut pieces = Vec::with_capacity(n);
        for k in 0..n {
            let Some(spline) = self.editor.piece_spline(k) else {
                return (exact, 0.0);
            };
            let anchors = self
                .editor
                .piece_points(k)
                .iter()
                .map(|&i| {
                    let p = &doc.points[i];
                    Anchor {
                        point: p.point(),
                        kind: AnchorKind::User,
                        a: p.shape,
                        target_curvature: 0.0,
                        tangent: p.tangent.map(|[x, y]| kurbo::Vec2::new(x, y)),
                    }
                })
                .collect();
            pieces.push(Piece {
                anchors,
                closed: spline.is_closed(),
                spline: spline.clone(),
                path: self.piece_path(k),
                // The room a span's single cubic gets is the tolerance less this.
                hausdorff: Some(0.0),
                within_tolerance: true,
                fallback: false,
                state: None,
            });
        }
        let glyph = DraftedGlyph {
            contours: vec![DraftedContour {
                pieces,
                path: exact.clone(),
                original_on_curve: 0,
            }],
            path: exact.clone(),
            hausdorff: None,
        };
        let bbox = exact.bounding_box();
        let size = bbox.width().max(bbox.height());
        let accuracy = accuracy.unwrap_or(NODE_ACCURACY * size);
        let tolerance = tolerance.unwrap_or(NODE_TOLERANCE * size);
        let nodes = anchor_outline(&glyph, &exact, accuracy, tolerance);
        (nodes.path, nodes.max_error)
    }

    /// The outline by node choice: "joints" (exact), "anchors" or "compatible".
    pub fn path_by(
        &self,
        nodes: &str,
        accuracy: Option<f64>,
        tolerance: Option<f64>,
    ) -> PyResult<BezPath> {
        match nodes {
            "joints" => Ok(self.outline()),
            "anchors" => Ok(self.anchor_path(accuracy, tolerance).0),
            "compatible" => Ok(self.editor.node_outline()),
            _ => Err(PyValueError::new_err(format!(
                "unknown nodes {nodes:?}: expected \"joints\", \"anchors\" or \"compatible\""
            ))),
        }
    }
}

#[pymethods]
impl Contour {
    /// A contour through `points` (pairs or an (n, 2) array).
    ///
    /// - `closed`: whether the contour is closed.
    /// - `scheme`: "kappa", "ek-cubic" or "ek-trig".
    /// - `shapes`: None (the scheme's neutral value), one number, or one per point.
    /// - `corners`: None, or one boolean per point: a tangent break there.
    /// - `tangents`: None, or per point None or a direction (dx, dy) the curve leaves along
    ///   (at a corner: the direction of the piece that starts there).
    /// - `tangents_in`: None, or per point None or, at a corner, the direction in which the
    ///   piece that ends there arrives.
    #[new]
    #[pyo3(signature = (points, closed, scheme = "kappa", shapes = None, corners = None, tangents = None, tangents_in = None))]
    fn new(
        points: &Bound<'_, PyAny>,
        closed: bool,
        scheme: &str,
        shapes: Option<&Bound<'_, PyAny>>,
        corners: Option<&Bound<'_, PyAny>>,
        tangents: Option<&Bound<'_, PyAny>>,
        tangents_in: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Contour> {
        let pts = points::points(points)?;
        let n = pts.len();
        let scheme = self::scheme(scheme)?;
        let shapes: Vec<f64> = match shapes {
            None => vec![scheme.neutral_shape(); n],
            Some(s) if s.is_none() => vec![scheme.neutral_shape(); n],
            Some(s) => match s.extract::<f64>() {
                Ok(a) => vec![a; n],
                Err(_) => {
                    per_point(Some(points::floats(s, "shape")?), n, "shapes")?.unwrap_or_default()
                }
            },
        };
        let corners = per_point(
            corners
                .filter(|o| !o.is_none())
                .map(|c| points::flags(c, "corners"))
                .transpose()?,
            n,
            "corner flags",
        )?;
        let tangents = per_point(
            tangents
                .filter(|o| !o.is_none())
                .map(|t| points::directions(t, "tangent"))
                .transpose()?,
            n,
            "tangents",
        )?;
        let tangents_in = per_point(
            tangents_in
                .filter(|o| !o.is_none())
                .map(|t| points::directions(t, "tangent"))
                .transpose()?,
            n,
            "incoming tangents",
        )?;
        let dir = |v: &Option<Vec<Option<kurbo::Vec2>>>, i: usize| {
            v.as_ref().and_then(|v| v[i]).map(|d| [d.x, d.y])
        };
        let points = (0..n)
            .map(|i| EditPoint {
                x: pts[i].x,
                y: pts[i].y,
                shape: shapes[i],
                corner: corners.as_ref().is_some_and(|c| c[i]),
                tangent: dir(&tangents, i),
                tangent_in: dir(&tangents_in, i),
            })
            .collect();
        Ok(Contour::from_doc(PathDoc {
            points,
            closed,
            scheme,
            solution: Vec::new(),
        }))
    }

    /// A contour from one path-tool document in JSON (the objects of a glyph's
    /// "org.kappa.contours" list, or a document the path tool saved).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Contour> {
        let doc: PathDoc = serde_json::from_str(text)
            .map_err(|e| to_py(kappa::Error::InvalidInput(format!("contour JSON: {e}"))))?;
        Ok(Contour::from_doc(doc))
    }

    /// The contour as a path-tool document in JSON: points (x, y, shape, corner, tangent,
    /// tangent_in), closed, scheme — what a glyph's "org.kappa.contours" list holds — and,
    /// with `solution`, the solutions the pieces show (the path tool reopens a document
    /// with them).
    #[pyo3(signature = (solution = false))]
    fn to_json(&self, solution: bool) -> PyResult<String> {
        let mut doc = self.editor.doc().clone();
        if !solution {
            doc.solution.clear();
        }
        serde_json::to_string(&doc)
            .map_err(|e| PyValueError::new_err(format!("cannot write JSON: {e}")))
    }

    /// The scheme name.
    #[getter]
    fn scheme(&self) -> &'static str {
        scheme_name(self.editor.doc().scheme)
    }

    /// Whether the contour is closed.
    #[getter]
    fn closed(&self) -> bool {
        self.editor.doc().closed
    }

    /// The points (x, y).
    #[getter]
    fn points(&self) -> Vec<(f64, f64)> {
        self.editor
            .doc()
            .points
            .iter()
            .map(|p| (p.x, p.y))
            .collect()
    }

    /// The shape of each point.
    #[getter]
    fn shapes(&self) -> Vec<f64> {
        self.editor.doc().points.iter().map(|p| p.shape).collect()
    }

    /// The corner flag of each point.
    #[getter]
    fn corners(&self) -> Vec<bool> {
        self.editor.doc().points.iter().map(|p| p.corner).collect()
    }

    /// The prescribed tangent of each point (None: free).
    #[getter]
    fn tangents(&self) -> Vec<Option<(f64, f64)>> {
        let d = self.editor.doc();
        d.points
            .iter()
            .map(|p| p.tangent.map(|[x, y]| (x, y)))
            .collect()
    }

    /// The prescribed incoming tangent of each point (None: free; used at corners).
    #[getter]
    fn tangents_in(&self) -> Vec<Option<(f64, f64)>> {
        let d = self.editor.doc();
        d.points
            .iter()
            .map(|p| p.tangent_in.map(|[x, y]| (x, y)))
            .collect()
    }

    /// The solved curve of each piece (None for a piece that has no curve).
    #[getter]
    fn pieces(&self) -> Vec<Option<Curve>> {
        (0..self.editor.pieces())
            .map(|k| {
                self.editor
                    .piece_spline(k)
                    .map(|s| Curve { inner: s.clone() })
            })
            .collect()
    }

    /// The point indices of piece `k`.
    fn piece_points(&self, k: usize) -> Vec<usize> {
        self.editor.piece_points(k).to_vec()
    }

    /// The pieces that did not solve, as (piece, exception): NotConvergedError for a piece
    /// that shows its best unconverged curve, another KappaError for one with no curve.
    #[getter]
    fn errors(&self, py: Python<'_>) -> Vec<(usize, Py<PyAny>)> {
        (0..self.editor.pieces())
            .filter_map(|k| {
                let e = self.editor.piece_error(k)?;
                Some((k, to_py(e.clone()).value(py).clone().into_any().unbind()))
            })
            .collect()
    }

    /// Raises the first piece's error, if any (an unconverged piece only when
    /// `accept_unconverged` is False).
    #[pyo3(signature = (accept_unconverged = false))]
    fn check(&self, accept_unconverged: bool) -> PyResult<()> {
        for k in 0..self.editor.pieces() {
            match self.editor.piece_error(k) {
                Some(kappa::Error::NotConverged { .. })
                    if accept_unconverged && self.editor.piece_spline(k).is_some() => {}
                Some(e) => return Err(to_py(e.clone())),
                None => {}
            }
        }
        Ok(())
    }

    /// The outline as path elements in fontTools' RecordingPen form.
    ///
    /// - `nodes="joints"`: the exact curve (κ quadratics as `qCurveTo`, εκ-cubic cubics;
    ///   εκ-trig fitted), its on-curve points the joints between segments.
    /// - `nodes="anchors"`: the contour's own points as the on-curve points, each span
    ///   between two of them one cubic where that is within `tolerance / 2` (default
    ///   `tolerance` 4e-3 of the contour's size), else cubics within `accuracy` (default
    ///   1e-4 of the size). Closed contours only; open ones give joints.
    /// - `nodes="compatible"`: on-curve points at the contour's points and at the joints,
    ///   in a structure that depends only on the number of points, the corners and the
    ///   closed flag (two parts per segment, a line between two corners; κ quadratics and
    ///   εκ-cubic cubics exact, εκ-trig two Hermite cubics per part), so that contours of
    ///   the same structure in several masters interpolate.
    #[pyo3(signature = (nodes = "joints", accuracy = None, tolerance = None))]
    fn elements(
        &self,
        nodes: &str,
        accuracy: Option<f64>,
        tolerance: Option<f64>,
    ) -> PyResult<Vec<Element>> {
        Ok(points::elements(&self.path_by(nodes, accuracy, tolerance)?))
    }

    /// The anchor-node outline (see `elements`) and its largest distance from the exact
    /// curve, measured: `(elements, max_error)`.
    #[pyo3(signature = (accuracy = None, tolerance = None))]
    fn anchor_outline(&self, accuracy: Option<f64>, tolerance: Option<f64>) -> (Vec<Element>, f64) {
        let (path, error) = self.anchor_path(accuracy, tolerance);
        (points::elements(&path), error)
    }

    /// SVG path data of the outline (see `elements` for `nodes`).
    #[pyo3(signature = (nodes = "joints", accuracy = None, tolerance = None))]
    fn to_svg(
        &self,
        nodes: &str,
        accuracy: Option<f64>,
        tolerance: Option<f64>,
    ) -> PyResult<String> {
        Ok(kappa::svg_path_data(
            &self.path_by(nodes, accuracy, tolerance)?,
        ))
    }

    fn __len__(&self) -> usize {
        self.editor.doc().points.len()
    }

    fn __repr__(&self) -> String {
        let d = self.editor.doc();
        format!(
            "Contour(scheme={:?}, closed={}, points={}, pieces={})",
            scheme_name(d.scheme),
            crate::curve::py_bool(d.closed),
            d.points.len(),
            self.editor.pieces()
        )
    }
}

/// The contours of a glyph's κ source: a JSON list of path-tool documents (what `kappa
/// font` writes under "org.kappa.contours"), or a single document.
#[pyfunction]
pub fn contours_from_json(text: &str) -> PyResult<Vec<Contour>> {
    let value: serde_json::Value = serde_json::from_str(text)
        .map_err(|e| to_py(kappa::Error::InvalidInput(format!("κ source JSON: {e}"))))?;
    let docs: Vec<PathDoc> = if value.is_array() {
        serde_json::from_value(value)
    } else {
        serde_json::from_value(value).map(|d| vec![d])
    }
    .map_err(|e| to_py(kappa::Error::InvalidInput(format!("κ source JSON: {e}"))))?;
    Ok(docs.into_iter().map(Contour::from_doc).collect())
}

/// The outline of several contours as one glyph: path elements in fontTools' RecordingPen
/// form, every closed contour turned the way `direction` wants ("postscript": outer
/// contours counter-clockwise, as CFF and UFO expect; "truetype": outer clockwise; None:
/// as drawn), nodes as in `Contour.elements`. Raises the first piece error unless
/// `accept_unconverged` (and then only errors other than NotConvergedError).
#[pyfunction]
#[pyo3(signature = (contours, direction = Some("postscript"), nodes = "joints", accuracy = None, tolerance = None, accept_unconverged = false))]
pub fn glyph_elements(
    contours: &Bound<'_, PyAny>,
    direction: Option<&str>,
    nodes: &str,
    accuracy: Option<f64>,
    tolerance: Option<f64>,
    accept_unconverged: bool,
) -> PyResult<Vec<Element>> {
    let direction = match direction {
        None => None,
        Some("postscript") => Some(Direction::PostScript),
        Some("truetype") => Some(Direction::TrueType),
        Some(d) => {
            return Err(PyValueError::new_err(format!(
                "unknown direction {d:?}: expected \"postscript\", \"truetype\" or None"
            )))
        }
    };
    let mut path = BezPath::new();
    for item in contours.try_iter()? {
        let item = item?;
        let c = item
            .cast::<Contour>()
            .map_err(|_| PyTypeError::new_err("contours must be Contour objects"))?;
        let c = c.get();
        c.check(accept_unconverged)?;
        path.extend(
            c.path_by(nodes, accuracy, tolerance)?
                .elements()
                .iter()
                .copied(),
        );
    }
    let path = match direction {
        Some(d) => orient(&path, d),
        None => path,
    };
    Ok(points::elements(&path))
}
