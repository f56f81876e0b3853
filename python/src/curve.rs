//! κ- and εκ-curves: `solve`, `Curve`, `Segment`.

use kappa::{Scheme, Shape, SolveOptions, Solver, Spline};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::IntoPy;
use crate::points::{self, xy, Element, Xy};

/// A scheme from its name: `"kappa"`, `"ek-cubic"` or `"ek-trig"` (underscores also
/// accepted).
pub fn scheme(name: &str) -> PyResult<Scheme> {
    match name.replace('_', "-").as_str() {
        "kappa" => Ok(Scheme::Kappa),
        "ek-cubic" => Ok(Scheme::EkCubic),
        "ek-trig" => Ok(Scheme::EkTrig),
        _ => Err(PyValueError::new_err(format!(
            "unknown scheme {name:?}: expected \"kappa\", \"ek-cubic\" or \"ek-trig\""
        ))),
    }
}

/// The name of a scheme, as [`scheme`] reads it.
pub fn scheme_name(s: Scheme) -> &'static str {
    match s {
        Scheme::Kappa => "kappa",
        Scheme::EkCubic => "ek-cubic",
        Scheme::EkTrig => "ek-trig",
    }
}

/// A shape argument: `None` (the scheme's neutral value), a number, or one per point.
pub fn shape(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Shape> {
    match obj {
        None => Ok(Shape::Neutral),
        Some(o) if o.is_none() => Ok(Shape::Neutral),
        Some(o) => match o.extract::<f64>() {
            Ok(a) => Ok(Shape::Global(a)),
            Err(_) => Ok(Shape::PerPoint(points::floats(o, "shape")?)),
        },
    }
}

/// One segment of a solved curve: its defining points `q` (Q0, Q1, Q2), shape `a`, peak
/// parameter `t_max` and degree; its input point lies at `eval(t_max)`.
#[pyclass(module = "kappa", frozen)]
#[derive(Clone)]
pub struct Segment {
    pub inner: kappa::Segment<kurbo::Point>,
}

#[pymethods]
impl Segment {
    /// The three defining points Q0, Q1, Q2.
    #[getter]
    fn q(&self) -> (Xy, Xy, Xy) {
        let [a, b, c] = self.inner.q;
        (xy(a), xy(b), xy(c))
    }

    /// The shape parameter (2/3 for κ-curves).
    #[getter]
    fn a(&self) -> f64 {
        self.inner.a
    }

    /// The parameter of the curvature peak, where the input point lies.
    #[getter]
    fn t_max(&self) -> f64 {
        self.inner.t_max
    }

    /// 2 (κ; εκ-trig, quadratic trigonometric) or 3 (εκ-cubic).
    #[getter]
    fn degree(&self) -> usize {
        self.inner.degree
    }

    /// The scheme name.
    #[getter]
    fn scheme(&self) -> &'static str {
        scheme_name(self.inner.scheme)
    }

    /// The control points: 3 (κ), 4 (εκ-cubic) Bézier points, or the 5 points P0..P4 of an
    /// εκ-trig segment's trigonometric curve.
    #[getter]
    fn control_points(&self) -> Vec<Xy> {
        self.inner.control_points().into_iter().map(xy).collect()
    }

    /// Whether the segment collapsed onto its input point (an inflection there).
    #[getter]
    fn is_collapsed(&self) -> bool {
        self.inner.is_collapsed()
    }

    /// "max", "min", "inflection" or "end-only": what |κ| does at `t_max`.
    #[getter]
    fn extremum(&self) -> &'static str {
        match self.inner.extremum() {
            kappa::Extremum::Max => "max",
            kappa::Extremum::Min => "min",
            kappa::Extremum::Inflection => "inflection",
            kappa::Extremum::EndOnly => "end-only",
        }
    }

    /// The point at parameter `t` in [0, 1].
    fn eval(&self, t: f64) -> Xy {
        xy(self.inner.eval(t))
    }

    /// The derivative dP/dt at `t`.
    fn derivative(&self, t: f64) -> Xy {
        let d = self.inner.derivative(t);
        (d.x, d.y)
    }

    /// The signed curvature at `t` (positive for left turns, y up).
    fn curvature(&self, t: f64) -> f64 {
        self.inner.curvature(t)
    }

    fn __repr__(&self) -> String {
        format!(
            "Segment(scheme={:?}, degree={}, a={}, t_max={})",
            self.scheme(),
            self.inner.degree,
            self.inner.a,
            self.inner.t_max
        )
    }
}

/// A solved κ- or εκ-curve.
#[pyclass(module = "kappa", frozen)]
#[derive(Clone)]
pub struct Curve {
    pub inner: Spline,
}

impl Curve {
    fn path(&self) -> kurbo::BezPath {
        self.inner.to_bezpath()
    }
}

#[pymethods]
impl Curve {
    /// The scheme name.
    #[getter]
    fn scheme(&self) -> &'static str {
        scheme_name(self.inner.scheme())
    }

    /// Whether the curve is closed.
    #[getter]
    fn closed(&self) -> bool {
        self.inner.is_closed()
    }

    /// The segments in order: one per input point (closed) or per interior point (open).
    #[getter]
    fn segments(&self) -> Vec<Segment> {
        self.inner
            .segments()
            .iter()
            .map(|s| Segment { inner: *s })
            .collect()
    }

    /// Whether the solver reached its tolerance (False only with `accept_unconverged`).
    #[getter]
    fn converged(&self) -> bool {
        self.inner.converged()
    }

    /// Iterations performed (classic start-up iterations plus Newton steps).
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations()
    }

    /// How many of the iterations were Newton steps.
    #[getter]
    fn newton_steps(&self) -> usize {
        self.inner.report().newton_steps
    }

    /// The largest residual left, relative to the drawing size.
    #[getter]
    fn residual(&self) -> f64 {
        self.inner.report().residual
    }

    /// The curve as path elements in fontTools' RecordingPen form (`moveTo`, `qCurveTo`
    /// for κ, `curveTo` for εκ-cubic and the fitted εκ-trig, `closePath` or `endPath`).
    fn elements(&self) -> Vec<Element> {
        points::elements(&self.path())
    }

    /// The exact control points of every path segment (3 per κ quadratic, 4 per cubic).
    fn bezier_segments(&self) -> Vec<Vec<Xy>> {
        points::bezier_segments(&self.path())
    }

    /// Every path segment as a cubic (p0, p1, p2, p3); κ quadratics raised exactly.
    fn cubics(&self) -> Vec<[Xy; 4]> {
        points::cubics(&self.path())
    }

    /// SVG path data (absolute commands, shortest round-trip numbers).
    fn to_svg(&self) -> String {
        self.inner.to_svg()
    }

    /// Samples `((x, y), (kx, ky))` of the exact curve, `samples_per_segment` (at least 2)
    /// per segment, ends included: the point and the curvature vector κ·n (n the left unit
    /// normal).
    #[pyo3(signature = (samples_per_segment = 16))]
    fn curvature_samples(&self, samples_per_segment: usize) -> Vec<(Xy, Xy)> {
        self.inner
            .curvature_samples(samples_per_segment)
            .into_iter()
            .map(|(p, k)| (xy(p), (k.x, k.y)))
            .collect()
    }

    /// Signed curvatures at `samples_per_segment` parameters per segment (ends included).
    #[pyo3(signature = (samples_per_segment = 16))]
    fn curvatures(&self, samples_per_segment: usize) -> Vec<f64> {
        let m = samples_per_segment.max(2);
        self.inner
            .segments()
            .iter()
            .flat_map(|s| (0..m).map(move |i| s.curvature(i as f64 / (m - 1) as f64)))
            .collect()
    }

    /// The largest |κ| of the curve.
    fn max_abs_curvature(&self) -> f64 {
        self.inner.max_abs_curvature()
    }

    /// The curve as cubics within `tolerance` (relative to the drawing size unless
    /// `absolute`): `(elements, max_distance)`. Exact (distance 0) for κ and εκ-cubic.
    #[pyo3(signature = (tolerance = 1e-4, absolute = false))]
    fn fit(&self, tolerance: f64, absolute: bool) -> PyResult<(Vec<Element>, f64)> {
        let options = if absolute {
            kappa::fit::FitOptions::absolute(tolerance)
        } else {
            kappa::fit::FitOptions::relative(tolerance)
        };
        let fitted = self.inner.fit(&options).py_err()?;
        Ok((points::elements(&fitted.path), fitted.max_distance))
    }

    fn __len__(&self) -> usize {
        self.inner.segments().len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Curve(scheme={:?}, closed={}, segments={}, converged={}, iterations={})",
            self.scheme(),
            py_bool(self.inner.is_closed()),
            self.inner.segments().len(),
            py_bool(self.inner.converged()),
            self.inner.iterations()
        )
    }
}

/// Solves a κ- or εκ-curve through `points`.
///
/// - `points`: a sequence of (x, y) pairs or an (n, 2) NumPy array.
/// - `closed`: a closed curve (one segment per point) or an open one.
/// - `scheme`: "kappa", "ek-cubic" or "ek-trig".
/// - `shape`: None (the scheme's neutral value), one number, or one per point.
/// - `tangents`: None, or one entry per point: None (free) or a direction (dx, dy) the
///   curve must leave the point along.
/// - `tolerance`, `max_iterations`: the solver's options (relative tolerance 1e-12, 4000
///   iterations).
/// - `accept_unconverged`: return the best curve found (`converged` False) instead of
///   raising NotConvergedError.
///
/// Raises a subclass of KappaError on bad input (the library's message).
#[pyfunction]
#[pyo3(signature = (points, closed, scheme = "kappa", shape = None, tangents = None, *, tolerance = 1e-12, max_iterations = 4000, accept_unconverged = false))]
#[allow(clippy::too_many_arguments)]
pub fn solve(
    points: &Bound<'_, PyAny>,
    closed: bool,
    scheme: &str,
    shape: Option<&Bound<'_, PyAny>>,
    tangents: Option<&Bound<'_, PyAny>>,
    tolerance: f64,
    max_iterations: usize,
    accept_unconverged: bool,
) -> PyResult<Curve> {
    let pts = points::points(points)?;
    let scheme = self::scheme(scheme)?;
    let shape = self::shape(shape)?;
    let tangents = match tangents {
        Some(t) if !t.is_none() => Some(points::directions(t, "tangent")?),
        _ => None,
    };
    let options = SolveOptions {
        tolerance,
        max_iterations,
        accept_unconverged,
    };
    let mut solver = Solver::with_options(options);
    let spline = match tangents {
        Some(t) => solver.solve_with_tangents(&pts, closed, scheme, &shape, &t),
        None => solver.solve(&pts, closed, scheme, &shape),
    }
    .py_err()?;
    Ok(Curve { inner: spline })
}

/// A boolean as Python prints it.
pub fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}
