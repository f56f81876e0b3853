//! Uniform cubic B-splines and intrinsic Hermite segments.

use kappa::fit::FitOptions;
use kappa::intrinsic::{Control, Hermite, IntrinsicSeg, Profile, Turning};
use kappa::{BSpline, SolveOptions};
use kurbo::{ParamCurve, Point};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::IntoPy;
use crate::points::{self, xy, Element, Xy};

/// The uniform cubic B-spline through points: relaxed (zero end curvature) when open,
/// periodic when closed; segment k is an exact cubic on [k, k+1] and passes through point
/// k at t = k.
#[pyclass(module = "kappa", name = "BSpline", frozen)]
pub struct PyBSpline {
    inner: BSpline,
}

#[pymethods]
impl PyBSpline {
    /// Interpolates `points` (pairs or an (n, 2) array), closed (periodic) or open (relaxed).
    #[new]
    fn new(points: &Bound<'_, PyAny>, closed: bool) -> PyResult<PyBSpline> {
        let pts = points::points(points)?;
        Ok(PyBSpline {
            inner: BSpline::new(&pts, closed).py_err()?,
        })
    }

    /// Whether the spline is closed (periodic).
    #[getter]
    fn closed(&self) -> bool {
        self.inner.is_closed()
    }

    /// The interpolated points.
    #[getter]
    fn points(&self) -> Vec<Xy> {
        self.inner.points().iter().copied().map(xy).collect()
    }

    /// The B-spline control points.
    #[getter]
    fn control_points(&self) -> Vec<Xy> {
        self.inner
            .control_points()
            .iter()
            .copied()
            .map(xy)
            .collect()
    }

    /// The point at global parameter `t`.
    fn eval(&self, t: f64) -> Xy {
        xy(self.inner.eval(t))
    }

    /// The signed curvature at global parameter `t`.
    fn curvature(&self, t: f64) -> f64 {
        self.inner.curvature(t)
    }

    /// The exact maximum of |κ| and every global parameter where it is attained.
    fn max_curvature(&self) -> (f64, Vec<f64>) {
        let m = self.inner.max_curvature();
        (m.value, m.params)
    }

    /// The segments as cubic Béziers (p0, p1, p2, p3), exact.
    fn cubics(&self) -> Vec<[Xy; 4]> {
        points::cubics(&self.inner.to_bezpath())
    }

    /// The spline as path elements in fontTools' RecordingPen form.
    fn elements(&self) -> Vec<Element> {
        points::elements(&self.inner.to_bezpath())
    }

    /// SVG path data.
    fn to_svg(&self) -> String {
        kappa::svg_path_data(&self.inner.to_bezpath())
    }

    fn __len__(&self) -> usize {
        self.inner.segment_count()
    }
}

/// A curve whose curvature is an explicit (rational) Bézier function of arc length:
/// κ(s) = K(s / L) with control curvatures κ_0..κ_n.
#[pyclass(module = "kappa", frozen)]
pub struct IntrinsicSegment {
    inner: IntrinsicSeg,
}

#[pymethods]
impl IntrinsicSegment {
    /// A segment from its start point, start angle (radians), arc length and control
    /// curvatures, with optional positive weights (a rational curvature function).
    #[new]
    #[pyo3(signature = (start, angle, length, curvatures, weights = None))]
    fn new(
        start: (f64, f64),
        angle: f64,
        length: f64,
        curvatures: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> PyResult<IntrinsicSegment> {
        let p = Point::new(start.0, start.1);
        let inner = match weights {
            Some(w) => IntrinsicSeg::rational(p, angle, length, &curvatures, &w),
            None => IntrinsicSeg::new(p, angle, length, &curvatures),
        }
        .py_err()?;
        Ok(IntrinsicSegment { inner })
    }

    /// The degree n of the curvature function.
    #[getter]
    fn degree(&self) -> usize {
        self.inner.degree()
    }

    /// The control curvatures κ_0..κ_n.
    #[getter]
    fn curvatures(&self) -> Vec<f64> {
        self.inner.curvatures().to_vec()
    }

    /// The weights of a rational curvature function (None: polynomial).
    #[getter]
    fn weights(&self) -> Option<Vec<f64>> {
        self.inner.weights().map(<[f64]>::to_vec)
    }

    /// The arc length.
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }

    /// The tangent angle at the start (radians).
    #[getter]
    fn start_angle(&self) -> f64 {
        self.inner.start_angle()
    }

    /// The tangent angle at the end (radians).
    #[getter]
    fn end_angle(&self) -> f64 {
        self.inner.end_angle()
    }

    /// The total turning (end angle − start angle).
    #[getter]
    fn turning(&self) -> f64 {
        self.inner.turning()
    }

    /// The point at parameter `t` in [0, 1] (t = s / L).
    fn eval(&self, t: f64) -> Xy {
        xy(self.inner.eval(t))
    }

    /// The signed curvature at `t` (positive for left turns).
    fn curvature_at(&self, t: f64) -> f64 {
        self.inner.curvature_at(t)
    }

    /// The tangent angle at `t` (radians).
    fn angle_at(&self, t: f64) -> f64 {
        self.inner.angle_at(t)
    }

    /// The parameters of the inflections (sign changes of the curvature).
    fn inflections(&self) -> Vec<f64> {
        self.inner.inflections()
    }

    /// The parameters of the curvature extrema inside the segment.
    fn curvature_extrema(&self) -> Vec<f64> {
        self.inner.curvature_extrema()
    }

    /// Whether the curvature is monotone along the segment.
    fn is_monotone(&self) -> bool {
        self.inner.is_monotone()
    }

    /// The largest |κ|.
    fn max_abs_curvature(&self) -> f64 {
        self.inner.max_abs_curvature()
    }

    /// Cubic Béziers within `tolerance` (relative to the segment's size unless
    /// `absolute`): `(cubics, max_distance)`.
    #[pyo3(signature = (tolerance = 1e-6, absolute = false))]
    fn cubics(&self, tolerance: f64, absolute: bool) -> PyResult<(Vec<[Xy; 4]>, f64)> {
        let options = if absolute {
            FitOptions::absolute(tolerance)
        } else {
            FitOptions::relative(tolerance)
        };
        let fitted = self.inner.to_bezpath(&options).py_err()?;
        Ok((points::cubics(&fitted.path), fitted.max_distance))
    }

    fn __repr__(&self) -> String {
        format!(
            "IntrinsicSegment(degree={}, length={}, curvatures={:?})",
            self.inner.degree(),
            self.inner.length(),
            self.inner.curvatures()
        )
    }
}

/// One entry of a profile: None (free), a number (given) or {"same_as": i}.
fn control(obj: &Bound<'_, PyAny>) -> PyResult<Control> {
    if obj.is_none() {
        return Ok(Control::Free);
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        if let Some(i) = d.get_item("same_as")? {
            return Ok(Control::Same(i.extract()?));
        }
        return Err(PyValueError::new_err(
            "a control curvature dict must be {\"same_as\": index}",
        ));
    }
    obj.extract::<f64>().map(Control::Given).map_err(|_| {
        PyTypeError::new_err("a control curvature is None, a number or {\"same_as\": i}")
    })
}

/// Solves a G1 or G2 Hermite problem with one intrinsic segment.
///
/// - `start`, `end`: the end points; `start_angle`, `end_angle`: tangent angles (radians).
/// - `start_curvature`, `end_curvature`: both given for G2 data, both None for G1.
/// - `degree`: the degree of the curvature function (default 1 for G1, the clothoid; 5 for
///   G2), every control free; or `controls`: one entry per control curvature, None (free),
///   a number (given) or {"same_as": i}; optional `weights` (rational).
/// - `turning`: "nearest" (the short way round) or "as-given".
#[pyfunction]
#[pyo3(signature = (start, start_angle, end, end_angle, start_curvature = None, end_curvature = None, degree = None, controls = None, weights = None, turning = "nearest", max_iterations = 2000))]
#[allow(clippy::too_many_arguments)]
pub fn hermite(
    start: (f64, f64),
    start_angle: f64,
    end: (f64, f64),
    end_angle: f64,
    start_curvature: Option<f64>,
    end_curvature: Option<f64>,
    degree: Option<usize>,
    controls: Option<&Bound<'_, PyAny>>,
    weights: Option<Vec<f64>>,
    turning: &str,
    max_iterations: usize,
) -> PyResult<IntrinsicSegment> {
    let (p0, p1) = (Point::new(start.0, start.1), Point::new(end.0, end.1));
    let data = match (start_curvature, end_curvature) {
        (None, None) => Hermite::g1(p0, start_angle, p1, end_angle),
        (Some(k0), Some(k1)) => Hermite::g2(p0, start_angle, k0, p1, end_angle, k1),
        _ => {
            return Err(PyValueError::new_err(
                "give both end curvatures (G2) or neither (G1)",
            ))
        }
    };
    let data = match turning {
        "nearest" => data.with_turning(Turning::Nearest),
        "as-given" | "as_given" => data.with_turning(Turning::AsGiven),
        t => {
            return Err(PyValueError::new_err(format!(
                "unknown turning {t:?}: expected \"nearest\" or \"as-given\""
            )))
        }
    };
    let mut profile = match controls {
        Some(c) if !c.is_none() => Profile::new(
            c.try_iter()?
                .map(|item| control(&item?))
                .collect::<PyResult<Vec<_>>>()?,
        ),
        _ => Profile::free(degree.unwrap_or(if data.is_g2() { 5 } else { 1 })),
    };
    if let Some(w) = weights {
        profile = profile.with_weights(w);
    }
    let options = SolveOptions {
        max_iterations,
        ..SolveOptions::default()
    };
    let inner = data.solve_with(&profile, &options).py_err()?;
    Ok(IntrinsicSegment { inner })
}
