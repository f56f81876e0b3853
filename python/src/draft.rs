//! Drafting κ contours from an outline (a fontTools glyph, drawn through the pen protocol)
//! and reading contours from SVG.

use kappa::editor::{extract_svg_document, import_svg_paths};
use kappa::glyph::{draft, DraftOptions, DraftShape, WRITTEN_HEADROOM};
use kappa::Scheme;
use kurbo::{BezPath, Point};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

use crate::contour::Contour;
use crate::curve::scheme;
use crate::errors::{to_py, IntoPy};

/// A glyph drafted as κ contours: the contours (one `Contour` per subpath, its pieces
/// between corners), how far the draft strays from the original, and the κ source a UFO
/// glyph lib keeps (`to_json()`, under `KAPPA_LIB_KEY`).
#[pyclass(module = "kappa", frozen, name = "DraftedGlyph")]
pub struct Drafted {
    contours: Vec<Py<Contour>>,
    source: String,
    hausdorff: f64,
    within_tolerance: bool,
    fallbacks: usize,
    anchors: usize,
    original_on_curve: usize,
}

#[pymethods]
impl Drafted {
    /// The contours, in the order of the original's subpaths.
    #[getter]
    fn contours(&self, py: Python<'_>) -> Vec<Py<Contour>> {
        self.contours.iter().map(|c| c.clone_ref(py)).collect()
    }

    /// The largest Hausdorff distance of a drafted piece from the original piece, in the
    /// outline's units.
    #[getter]
    fn hausdorff(&self) -> f64 {
        self.hausdorff
    }

    /// Whether every piece came within the tolerance.
    #[getter]
    fn within_tolerance(&self) -> bool {
        self.within_tolerance
    }

    /// How many pieces could not be solved and keep the original's segments (their
    /// contours hold the original's on-curve points as corners).
    #[getter]
    fn fallbacks(&self) -> usize {
        self.fallbacks
    }

    /// The number of anchors (the points a designer edits).
    #[getter]
    fn anchors(&self) -> usize {
        self.anchors
    }

    /// The number of on-curve points of the original outline.
    #[getter]
    fn original_on_curve(&self) -> usize {
        self.original_on_curve
    }

    /// The κ source: a JSON list of path-tool documents, one per contour — what `kappa
    /// font` writes under "org.kappa.contours" and `contours_from_json` reads.
    fn to_json(&self) -> String {
        self.source.clone()
    }

    fn __len__(&self) -> usize {
        self.contours.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "DraftedGlyph(contours={}, anchors={}, hausdorff={}, fallbacks={})",
            self.contours.len(),
            self.anchors,
            self.hausdorff,
            self.fallbacks
        )
    }
}

/// An outline from elements in fontTools' segment-pen form, one Bézier per element:
/// `("moveTo", (p,))`, `("lineTo", (p,))`, `("qCurveTo", (c, p))`, `("curveTo", (c1, c2,
/// p))`, `("closePath", ())` or `("endPath", ())`.
fn outline(elements: &Bound<'_, PyAny>) -> PyResult<BezPath> {
    let mut path = BezPath::new();
    for (i, item) in elements.try_iter()?.enumerate() {
        let (op, args): (String, Vec<(f64, f64)>) = item?.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "element {i} is not (operator, points): expected e.g. (\"lineTo\", ((x, y),))"
            ))
        })?;
        let p: Vec<Point> = args.iter().map(|&(x, y)| Point::new(x, y)).collect();
        let open = !path.elements().is_empty();
        match (op.as_str(), p.as_slice()) {
            ("moveTo", [a]) => path.move_to(*a),
            ("lineTo", [a]) if open => path.line_to(*a),
            ("qCurveTo", [a, b]) if open => path.quad_to(*a, *b),
            ("curveTo", [a, b, c]) if open => path.curve_to(*a, *b, *c),
            ("closePath", []) if open => path.close_path(),
            ("endPath", []) => {}
            _ => {
                return Err(PyValueError::new_err(format!(
                    "element {i}: cannot use {op} with {} points here (one Bézier per \
                     element, after a moveTo)",
                    p.len()
                )))
            }
        }
    }
    Ok(path)
}

/// Drafts κ contours from an outline given as one-Bézier elements (see `kappa.draft`, which
/// takes a fontTools glyph): `kappa::glyph::draft`, as `kappa font` drafts each glyph.
///
/// - `units_per_em`: scales the defaults (tolerance 0.004 em, anchors at least 0.06 em
///   apart).
/// - `scheme`, `shape`: the curve scheme; for εκ schemes None (neutral), a number, or
///   "auto" (per anchor, matching the original's curvature peak).
/// - `tolerance`: refine each piece until it is within this distance (font units; by
///   default 0.004 em less `kappa::glyph::WRITTEN_HEADROOM`, 5 %, as `kappa font` drafts a
///   UFO, so that the written outline stays within 0.004 em).
/// - `fair`, `simplify`: mend spurious inflections; drop anchors not needed.
/// - `extremum_tangents`: hold horizontal and vertical tangents at extremum anchors (on,
///   as in `kappa font`).
#[pyfunction]
#[pyo3(signature = (elements, units_per_em = 1000.0, scheme = "kappa", shape = None, tolerance = None, fair = false, simplify = false, extremum_tangents = true))]
#[allow(clippy::too_many_arguments)]
pub fn draft_elements(
    py: Python<'_>,
    elements: &Bound<'_, PyAny>,
    units_per_em: f64,
    scheme: &str,
    shape: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
    fair: bool,
    simplify: bool,
    extremum_tangents: bool,
) -> PyResult<Drafted> {
    if !(units_per_em.is_finite() && units_per_em > 0.0) {
        return Err(to_py(kappa::Error::InvalidOption(
            "units_per_em must be a positive number",
        )));
    }
    let scheme = self::scheme(scheme)?;
    let shape = draft_shape(shape, scheme)?;
    let mut options = DraftOptions::for_units_per_em(units_per_em).with_scheme(scheme, shape);
    // As `kappa font` drafts a UFO: room for the written outline within the tolerance.
    options.tolerance = tolerance.unwrap_or(options.tolerance * (1.0 - WRITTEN_HEADROOM));
    options.fair = fair;
    options.simplify = simplify;
    options.extremum_tangents = extremum_tangents;
    let path = outline(elements)?;
    let drafted = py.detach(|| draft(&path, &options)).py_err()?;
    let docs = drafted.path_docs(scheme);
    let source = serde_json::to_string(&docs)
        .map_err(|e| PyValueError::new_err(format!("cannot write JSON: {e}")))?;
    let contours = docs
        .into_iter()
        .map(|d| Py::new(py, Contour::from_doc(d)))
        .collect::<PyResult<_>>()?;
    Ok(Drafted {
        contours,
        source,
        hausdorff: drafted.hausdorff.unwrap_or(0.0),
        within_tolerance: drafted.within_tolerance(),
        fallbacks: drafted.fallback_count(),
        anchors: drafted.anchor_count(),
        original_on_curve: drafted.original_on_curve(),
    })
}

/// A draft's shape: None (neutral), a number, or "auto"; none for κ-curves.
fn draft_shape(obj: Option<&Bound<'_, PyAny>>, scheme: Scheme) -> PyResult<DraftShape> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(DraftShape::Neutral);
    };
    if scheme == Scheme::Kappa {
        return Err(PyValueError::new_err(
            "shape applies to the ek-cubic and ek-trig schemes only (κ-curves have none)",
        ));
    }
    if let Ok(a) = obj.extract::<f64>() {
        return Ok(DraftShape::Global(a));
    }
    match obj.extract::<String>() {
        Ok(s) if s.eq_ignore_ascii_case("auto") => Ok(DraftShape::Auto),
        _ => Err(PyValueError::new_err(
            "shape must be None, a number or \"auto\"",
        )),
    }
}

/// The contours of an SVG document: the editable drawing an SVG saved by the path tool
/// keeps, or else the vertices of every path, polygon, polyline, line, rect, circle and
/// ellipse of an SVG from another tool (in user space, after transforms; a vertex where a
/// curve meets another segment at an angle is a corner). Shapes are `scheme`'s neutral
/// value. Raises InvalidSvgError for text that is not SVG.
#[pyfunction]
#[pyo3(signature = (text, scheme = "kappa"))]
pub fn contours_from_svg(text: &str, scheme: &str) -> PyResult<Vec<Contour>> {
    let scheme = self::scheme(scheme)?;
    let doc = extract_svg_document(text)
        .or_else(|_| import_svg_paths(text, scheme))
        .py_err()?;
    Ok(doc.contours.into_iter().map(Contour::from_doc).collect())
}
