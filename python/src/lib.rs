//! Python bindings of kappa: κ- and εκ-curves, B-splines, intrinsic Hermite segments and
//! glyph contours with corners and tangents, for the type-design pipeline (fontTools,
//! ufo2ft, fontmake). The Python package `kappa` wraps this module (`kappa._kappa`) and adds
//! the fontTools pen and the ufo2ft filter in pure Python.
#![forbid(unsafe_code)]

mod contour;
mod curve;
mod draft;
mod errors;
mod extra;
mod points;

use pyo3::prelude::*;

/// The names of the built-in drawings of the εκ-curve paper.
#[pyfunction]
fn builtin_designs() -> Vec<&'static str> {
    kappa::BUILTIN_DESIGNS.iter().map(|(n, _)| *n).collect()
}

/// The JSON text of a built-in drawing (`{"name", "source", "curves": [{"closed",
/// "points", "shape"?}, ...]}`), or None for an unknown name.
#[pyfunction]
fn builtin_design(name: &str) -> Option<&'static str> {
    kappa::builtin_design(name)
}

/// The compiled module.
#[pymodule]
fn _kappa(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<curve::Curve>()?;
    m.add_class::<curve::Segment>()?;
    m.add_class::<contour::Contour>()?;
    m.add_class::<extra::PyBSpline>()?;
    m.add_class::<extra::IntrinsicSegment>()?;
    m.add_class::<draft::Drafted>()?;
    m.add_function(wrap_pyfunction!(curve::solve, m)?)?;
    m.add_function(wrap_pyfunction!(contour::contours_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(contour::glyph_elements, m)?)?;
    m.add_function(wrap_pyfunction!(draft::draft_elements, m)?)?;
    m.add_function(wrap_pyfunction!(draft::contours_from_svg, m)?)?;
    m.add_function(wrap_pyfunction!(extra::hermite, m)?)?;
    m.add_function(wrap_pyfunction!(errors::_raise_error_kind, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_designs, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_design, m)?)?;
    m.add("KAPPA_LIB_KEY", "org.kappa.contours")?;
    Ok(())
}
