//! Points in and out: sequences of pairs, NumPy arrays (through `tolist()`), tuples out.

use kurbo::{BezPath, PathEl, Point, Vec2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// A point as Python returns it: `(x, y)`.
pub type Xy = (f64, f64);

/// `(x, y)` of a kurbo point.
pub fn xy(p: Point) -> Xy {
    (p.x, p.y)
}

/// One pair of numbers: a tuple, list or any sequence of length 2.
fn pair(item: &Bound<'_, PyAny>, what: &str, index: usize) -> PyResult<Xy> {
    if let Ok(t) = item.cast::<PyTuple>() {
        if t.len() == 2 {
            return Ok((t.get_item(0)?.extract()?, t.get_item(1)?.extract()?));
        }
    } else if let Ok(l) = item.cast::<PyList>() {
        if l.len() == 2 {
            return Ok((l.get_item(0)?.extract()?, l.get_item(1)?.extract()?));
        }
    } else if item.len().ok() == Some(2) {
        return Ok((item.get_item(0)?.extract()?, item.get_item(1)?.extract()?));
    }
    Err(PyValueError::new_err(format!(
        "{what} {index} is not a pair of numbers (x, y)"
    )))
}

/// A NumPy array (or anything else with `tolist()`) as nested lists; other objects as they
/// are.
fn listed<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    if obj.cast::<PyList>().is_ok() || obj.cast::<PyTuple>().is_ok() {
        return Ok(obj.clone());
    }
    if obj.hasattr("tolist")? {
        return obj.call_method0("tolist");
    }
    Ok(obj.clone())
}

/// Points from a sequence of pairs or an `(n, 2)` array.
pub fn points(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Point>> {
    let obj = listed(obj)?;
    if obj.is_instance_of::<pyo3::types::PyString>() {
        return Err(PyTypeError::new_err(
            "points must be a sequence of (x, y) pairs",
        ));
    }
    let mut out = Vec::new();
    if let Ok(l) = obj.cast::<PyList>() {
        out.reserve(l.len());
        for (i, item) in l.iter().enumerate() {
            let (x, y) = pair(&item, "point", i)?;
            out.push(Point::new(x, y));
        }
        return Ok(out);
    }
    let iter = obj
        .try_iter()
        .map_err(|_| PyTypeError::new_err("points must be a sequence of (x, y) pairs"))?;
    for (i, item) in iter.enumerate() {
        let (x, y) = pair(&item?, "point", i)?;
        out.push(Point::new(x, y));
    }
    Ok(out)
}

/// Optional directions `(dx, dy)` per point (`None` entries: free), from a sequence or an
/// array (NaN rows of an array count as `None`).
pub fn directions(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Option<Vec2>>> {
    let obj = listed(obj)?;
    let iter = obj
        .try_iter()
        .map_err(|_| PyTypeError::new_err(format!("{what} must be a sequence")))?;
    let mut out = Vec::new();
    for (i, item) in iter.enumerate() {
        let item = item?;
        if item.is_none() {
            out.push(None);
            continue;
        }
        let (x, y) = pair(&item, what, i)?;
        out.push(if x.is_nan() && y.is_nan() {
            None
        } else {
            Some(Vec2::new(x, y))
        });
    }
    Ok(out)
}

/// A sequence of floats (or a 1-D array).
pub fn floats(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let obj = listed(obj)?;
    let iter = obj
        .try_iter()
        .map_err(|_| PyTypeError::new_err(format!("{what} must be a number or a sequence")))?;
    iter.map(|item| item?.extract::<f64>()).collect()
}

/// A sequence of booleans (or a 1-D array).
pub fn flags(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<bool>> {
    let obj = listed(obj)?;
    let iter = obj
        .try_iter()
        .map_err(|_| PyTypeError::new_err(format!("{what} must be a sequence of booleans")))?;
    iter.map(|item| item?.is_truthy()).collect()
}

/// A path element in fontTools' RecordingPen form: `(operator, (points...))`, a tuple of
/// a string and a tuple of `(x, y)` tuples in Python.
pub struct Element(pub &'static str, pub Vec<Xy>);

impl<'py> IntoPyObject<'py> for Element {
    type Target = PyTuple;
    type Output = Bound<'py, PyTuple>;
    type Error = PyErr;

    fn into_pyobject(self, py: Python<'py>) -> Result<Self::Output, Self::Error> {
        let pts = PyTuple::new(py, self.1)?;
        PyTuple::new(py, [self.0.into_pyobject(py)?.into_any(), pts.into_any()])
    }
}

/// The elements of a kurbo path, as a fontTools RecordingPen records them: `moveTo`,
/// `lineTo`, `qCurveTo` (one off-curve point), `curveTo`, and `closePath` or, for an open
/// subpath, `endPath`. A closed subpath's last line back to its start is left to
/// `closePath`, as fontTools pens imply it. A closed subpath whose last point misses its start by rounding only
/// (within [`CLOSE_SNAP`] of the coordinates' magnitude) ends exactly at the start, so that
/// point pens see one on-curve point there, not two.
pub fn elements(path: &BezPath) -> Vec<Element> {
    let mut out: Vec<Element> = Vec::with_capacity(path.elements().len() + 1);
    let mut open = false;
    let mut start = Point::ZERO;
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                if open {
                    out.push(Element("endPath", vec![]));
                }
                open = true;
                start = p;
                out.push(Element("moveTo", vec![xy(p)]));
            }
            PathEl::LineTo(p) => out.push(Element("lineTo", vec![xy(p)])),
            PathEl::QuadTo(p1, p2) => out.push(Element("qCurveTo", vec![xy(p1), xy(p2)])),
            PathEl::CurveTo(p1, p2, p3) => {
                out.push(Element("curveTo", vec![xy(p1), xy(p2), xy(p3)]))
            }
            PathEl::ClosePath => {
                // A closing line back to the start is implied by `closePath`.
                if matches!(out.last(), Some(Element("lineTo", p)) if p[0] == xy(start)) {
                    out.pop();
                }
                if let Some(last) = out.last_mut().and_then(|e| e.1.last_mut()) {
                    let scale = 1.0 + start.x.abs().max(start.y.abs());
                    let (dx, dy) = (last.0 - start.x, last.1 - start.y);
                    if dx.abs().max(dy.abs()) <= CLOSE_SNAP * scale {
                        *last = xy(start);
                    }
                }
                open = false;
                out.push(Element("closePath", vec![]));
            }
        }
    }
    if open {
        out.push(Element("endPath", vec![]));
    }
    out
}

/// How far (relative to the coordinates' magnitude) a closed subpath's last point may miss
/// its start and still count as ending there: rounding in the outline's arithmetic, far
/// below any font unit.
const CLOSE_SNAP: f64 = 1e-9;

/// Every segment of a path as a cubic `(p0, p1, p2, p3)`: cubics as they are, quadratics
/// raised exactly, lines with their handles at the thirds.
pub fn cubics(path: &BezPath) -> Vec<[Xy; 4]> {
    path.segments()
        .map(|seg| {
            let c = match seg {
                kurbo::PathSeg::Line(l) => kurbo::CubicBez::new(
                    l.p0,
                    l.p0.lerp(l.p1, 1.0 / 3.0),
                    l.p0.lerp(l.p1, 2.0 / 3.0),
                    l.p1,
                ),
                kurbo::PathSeg::Quad(q) => q.raise(),
                kurbo::PathSeg::Cubic(c) => c,
            };
            [xy(c.p0), xy(c.p1), xy(c.p2), xy(c.p3)]
        })
        .collect()
}

/// The control points of every segment of a path, exact: 2 for a line, 3 for a quadratic,
/// 4 for a cubic.
pub fn bezier_segments(path: &BezPath) -> Vec<Vec<Xy>> {
    path.segments()
        .map(|seg| match seg {
            kurbo::PathSeg::Line(l) => vec![xy(l.p0), xy(l.p1)],
            kurbo::PathSeg::Quad(q) => vec![xy(q.p0), xy(q.p1), xy(q.p2)],
            kurbo::PathSeg::Cubic(c) => vec![xy(c.p0), xy(c.p1), xy(c.p2), xy(c.p3)],
        })
        .collect()
}
