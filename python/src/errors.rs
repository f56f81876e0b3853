//! One Python exception class per `kappa::Error` variant, all subclasses of `KappaError`.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    kappa,
    KappaError,
    PyException,
    "Base class of every error the kappa library reports (one subclass per kind)."
);

/// Declares the subclasses of `KappaError`, the list of (name, class) pairs the module
/// registers, and the mapping from `kappa::Error` to them.
macro_rules! kinds {
    ($($name:ident: $doc:literal),* $(,)?) => {
        $(create_exception!(kappa, $name, KappaError, $doc);)*

        /// Registers `KappaError` and its subclasses in the module.
        pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
            let py = m.py();
            m.add("KappaError", py.get_type::<KappaError>())?;
            $(m.add(stringify!($name), py.get_type::<$name>())?;)*
            Ok(())
        }
    };
}

kinds! {
    TooFewPointsError: "Fewer input points than the curve type needs.",
    NonFinitePointError: "A coordinate is NaN or infinite.",
    RepeatedPointError: "Two consecutive input points coincide.",
    ExtentOverflowError: "The points span more than the largest finite number.",
    CollinearError: "All points lie on one line and the curve would have to turn back along it.",
    ShapeOutOfRangeError: "A shape parameter is outside its admissible range or not finite.",
    ShapeCountError: "A per-point shape list whose length does not match the number of points.",
    InvalidTangentError: "A tangent list of the wrong length, or a tangent that is zero or not finite.",
    TangentConflictError: "Two tangents fall on one segment.",
    GammaOutOfRangeError: "The gamma of a κ-space curve's joint is outside its interval.",
    InvalidOptionError: "A solver option (tolerance, iteration cap, ...) is not usable.",
    NonFiniteCurveError: "A curve handed to the fitting adapter is not finite.",
    InvalidInputError: "A JSON input could not be used.",
    InvalidSvgError: "An SVG document could not be read.",
    NoHermiteSolutionError: "No curve with the requested curvature profile meets the Hermite end conditions.",
    FontError: "A font could not be read or written.",
    MissingGlyphError: "The font maps no glyph to a character.",
    TessellationError: "lyon could not tessellate a path.",
    NotConvergedError: "The solver stopped at its iteration cap before reaching the tolerance.",
}

/// The Python exception for a library error: the class of its kind, the library's message,
/// and the variant's fields as attributes (`index`, `iterations`, `residual`, ...).
pub fn to_py(e: kappa::Error) -> PyErr {
    use kappa::Error as E;
    let msg = e.to_string();
    let (err, attrs): (PyErr, Vec<(&str, Attr)>) = match e {
        E::TooFewPoints { kind, needed, got } => (
            TooFewPointsError::new_err(msg),
            vec![
                ("kind", Attr::Str(kind.into())),
                ("needed", Attr::Int(needed)),
                ("got", Attr::Int(got)),
            ],
        ),
        E::NonFinitePoint { index } => (
            NonFinitePointError::new_err(msg),
            vec![("index", Attr::Int(index))],
        ),
        E::RepeatedPoint { index, next } => (
            RepeatedPointError::new_err(msg),
            vec![("index", Attr::Int(index)), ("next", Attr::Int(next))],
        ),
        E::ExtentOverflow => (ExtentOverflowError::new_err(msg), vec![]),
        E::Collinear => (CollinearError::new_err(msg), vec![]),
        E::ShapeOutOfRange {
            index,
            value,
            min,
            max,
        } => (
            ShapeOutOfRangeError::new_err(msg),
            vec![
                ("index", Attr::Int(index)),
                ("value", Attr::Float(value)),
                ("min", Attr::Float(min)),
                ("max", Attr::Float(max)),
            ],
        ),
        E::ShapeCount { expected, got } => (
            ShapeCountError::new_err(msg),
            vec![("expected", Attr::Int(expected)), ("got", Attr::Int(got))],
        ),
        E::InvalidTangent { index, reason } => (
            InvalidTangentError::new_err(msg),
            vec![
                ("index", Attr::Int(index)),
                ("reason", Attr::Str(reason.into())),
            ],
        ),
        E::TangentConflict { first, second } => (
            TangentConflictError::new_err(msg),
            vec![("first", Attr::Int(first)), ("second", Attr::Int(second))],
        ),
        E::GammaOutOfRange {
            joint,
            value,
            min,
            max,
        } => (
            GammaOutOfRangeError::new_err(msg),
            vec![
                ("joint", Attr::Int(joint)),
                ("value", Attr::Float(value)),
                ("min", Attr::Float(min)),
                ("max", Attr::Float(max)),
            ],
        ),
        E::InvalidOption(_) => (InvalidOptionError::new_err(msg), vec![]),
        E::NonFiniteCurve { segment } => (
            NonFiniteCurveError::new_err(msg),
            vec![("segment", Attr::Int(segment))],
        ),
        E::InvalidInput(_) => (InvalidInputError::new_err(msg), vec![]),
        E::InvalidSvg(_) => (InvalidSvgError::new_err(msg), vec![]),
        E::NoHermiteSolution { reason } => (
            NoHermiteSolutionError::new_err(msg),
            vec![("reason", Attr::Str(reason.into()))],
        ),
        E::Font(_) => (FontError::new_err(msg), vec![]),
        E::MissingGlyph { ch } => (
            MissingGlyphError::new_err(msg),
            vec![("char", Attr::Str(ch.to_string()))],
        ),
        E::Tessellation(_) => (TessellationError::new_err(msg), vec![]),
        E::NotConverged {
            iterations,
            residual,
        } => (
            NotConvergedError::new_err(msg),
            vec![
                ("iterations", Attr::Int(iterations)),
                ("residual", Attr::Float(residual)),
            ],
        ),
        // A kind added to the library later: the base class, the same message.
        _ => (KappaError::new_err(msg), vec![]),
    };
    if attrs.is_empty() {
        return err;
    }
    Python::attach(|py| {
        let value = err.value(py);
        for (name, attr) in attrs {
            let set = match attr {
                Attr::Int(v) => value.setattr(name, v),
                Attr::Float(v) => value.setattr(name, v),
                Attr::Str(v) => value.setattr(name, v),
            };
            // An attribute that cannot be set leaves the message, which says it all.
            drop(set);
        }
    });
    err
}

/// A field of an error variant, as a Python attribute.
enum Attr {
    Int(usize),
    Float(f64),
    Str(String),
}

/// `Result<T, kappa::Error>` as a `PyResult`.
pub trait IntoPy<T> {
    /// The same value, or the Python exception of the error.
    fn py_err(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for Result<T, kappa::Error> {
    fn py_err(self) -> PyResult<T> {
        self.map_err(to_py)
    }
}

/// Raises the exception of a library error kind the Python API cannot reach (the κ-space,
/// fitting, font-file and tessellation kinds), built from sample fields, so that tests can
/// check the mapping of every kind: `kind` is the exception's name. Not part of the API.
#[pyfunction]
pub fn _raise_error_kind(kind: &str) -> PyResult<()> {
    use kappa::Error as E;
    let e = match kind {
        "GammaOutOfRangeError" => E::GammaOutOfRange {
            joint: 2,
            value: 0.9,
            min: 0.25,
            max: 0.75,
        },
        "NonFiniteCurveError" => E::NonFiniteCurve { segment: 3 },
        "FontError" => E::Font("cannot read the font: bad magic".into()),
        "MissingGlyphError" => E::MissingGlyph { ch: 'ß' },
        "TessellationError" => E::Tessellation("too many vertices".into()),
        _ => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "no sample for {kind:?}"
            )))
        }
    };
    Err(to_py(e))
}
