//! The JSON inputs of the `kappa` command-line tool, parsed and checked before any heavy
//! work (feature `serde`).
//!
//! Each parser reads one JSON object, rejects unknown fields, and turns the data into the
//! library's types; the curve itself is validated by the solver (too few points, repeated
//! points, shapes out of range, ...). Input size is bounded **while** parsing: a `points`
//! list longer than [`InputLimits::max_points`], a point with more than three coordinates, or
//! a list of shapes, control curvatures or weights longer than its limit is rejected as soon
//! as the parser meets the first element too many, so a hostile input of 10⁷ points costs no
//! more than reading its text. Every failure is an [`Error::InvalidInput`] with a one-line
//! message that names the problem and, for JSON errors, its line and column.
//!
//! ```
//! use kappa::input::{CurveInput, InputLimits};
//!
//! let job = CurveInput::from_json(
//!     r#"{"points": [[0, 0], [100, 0], [50, 80]], "scheme": "ek-cubic", "shape": 0.8}"#,
//!     &InputLimits::default(),
//! )?;
//! let curve = kappa::Spline::ek_cubic(&job.points, job.closed, job.shape)?;
//! assert_eq!(curve.segments().len(), 3);
//! let limits = InputLimits { max_points: 2 };
//! assert!(CurveInput::from_json(r#"{"points": [[0, 0], [1, 0], [0, 1]]}"#, &limits).is_err());
//! # Ok::<(), kappa::Error>(())
//! ```

use core::cell::Cell;
use core::fmt;

use kurbo::Point;
use serde::de::{self, Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde::Deserialize;

use crate::intrinsic::{Control, Hermite, HermiteEnd, Profile, Turning};
use crate::{Error, Point3, Scheme, Shape};

/// The default of [`InputLimits::max_points`]: a million points (a κ-curve through them takes
/// a few seconds; a B-spline, a few tens of milliseconds).
pub const DEFAULT_MAX_POINTS: usize = 1_000_000;

/// The largest degree of a Hermite curvature profile the tool accepts (the solver's cost
/// grows with the square of the degree; the splines of the library use at most 9).
pub const MAX_HERMITE_DEGREE: usize = 64;

/// Limits on the size of an input, checked while it is parsed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputLimits {
    /// The most points a curve may have (also the longest list of shape parameters).
    pub max_points: usize,
}

impl Default for InputLimits {
    fn default() -> InputLimits {
        InputLimits {
            max_points: DEFAULT_MAX_POINTS,
        }
    }
}

/// The input of `kappa curve`: `{"points": [[x, y], …], "closed"?: bool, "scheme"?: "kappa"
/// | "ek-cubic" | "ek-trig", "shape"?: a | [a₀, …]}`.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveInput {
    /// The points.
    pub points: Vec<Point>,
    /// Closed (the default) or open.
    pub closed: bool,
    /// The scheme (default κ).
    pub scheme: Scheme,
    /// The shapes (default: the scheme's neutral shape).
    pub shape: Shape,
}

/// The points of a B-spline input: all 2D or all 3D.
#[derive(Clone, Debug, PartialEq)]
pub enum BSplinePoints {
    /// `[x, y]` points.
    Plane(Vec<Point>),
    /// `[x, y, z]` points.
    Space(Vec<Point3>),
}

/// The input of `kappa bspline`: `{"points": [[x, y], …] or [[x, y, z], …], "closed"?: bool}`.
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineInput {
    /// The points.
    pub points: BSplinePoints,
    /// Closed (periodic, the default) or open (relaxed).
    pub closed: bool,
}

/// The input of `kappa space`: `{"points": [[x, y, z], …], "closed"?: bool, "replace"?: r}`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceInput {
    /// The points.
    pub points: Vec<Point3>,
    /// Closed (the default) or open.
    pub closed: bool,
    /// The replaced fraction of each quadratic at a joint, in `[0, 1]` (default 0.01).
    pub replace: f64,
}

/// The input of `kappa hermite`: `{"start": {"point": [x, y], "angle": θ, "curvature"?: κ},
/// "end": {…}, "degree": n, "control_curvatures"?: [null | κ | {"same_as": i}, …],
/// "weights"?: [w, …], "turning"?: "nearest" | "as-given"}`.
#[derive(Clone, Debug, PartialEq)]
pub struct HermiteInput {
    /// The end conditions.
    pub hermite: Hermite,
    /// The curvature profile.
    pub profile: Profile,
}

impl CurveInput {
    /// Parses a `kappa curve` input.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidInput`]: malformed JSON, unknown fields, wrong types, a point without
    /// exactly two finite coordinates, too many points, a shape that is not a number or a
    /// list of numbers.
    pub fn from_json(text: &str, limits: &InputLimits) -> Result<CurveInput, Error> {
        let input: RawCurve = parse_json(text, "curve", limits)?;
        let points = input
            .points
            .iter()
            .enumerate()
            .map(|(index, p)| {
                let [x, y] = p.exact::<2>(index, "2 ([x, y])")?;
                Ok(Point::new(x, y))
            })
            .collect::<Result<Vec<Point>, Error>>()?;
        Ok(CurveInput {
            points,
            closed: input.closed.unwrap_or(true),
            scheme: input.scheme.unwrap_or_default(),
            shape: match input.shape {
                None => Shape::Neutral,
                Some(s) => s.into_shape()?,
            },
        })
    }
}

impl BSplineInput {
    /// Parses a `kappa bspline` input.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidInput`]: malformed JSON, unknown fields, wrong types, points of mixed
    /// or unusable dimensions, null coordinates, too many points.
    pub fn from_json(text: &str, limits: &InputLimits) -> Result<BSplineInput, Error> {
        let input: RawBSpline = parse_json(text, "B-spline", limits)?;
        let dim = input.points.first().map_or(2, |p| p.len);
        if dim != 2 && dim != 3 {
            return Err(invalid(format!(
                "point 0 has {dim} coordinates, expected 2 ([x, y]) or 3 ([x, y, z])"
            )));
        }
        for (index, p) in input.points.iter().enumerate() {
            if p.len != dim {
                return Err(invalid(format!(
                    "point {index} has {} coordinates, but point 0 has {dim}",
                    p.len
                )));
            }
        }
        let points = if dim == 2 {
            BSplinePoints::Plane(
                input
                    .points
                    .iter()
                    .enumerate()
                    .map(|(i, p)| p.exact::<2>(i, "2").map(|[x, y]| Point::new(x, y)))
                    .collect::<Result<_, _>>()?,
            )
        } else {
            BSplinePoints::Space(
                input
                    .points
                    .iter()
                    .enumerate()
                    .map(|(i, p)| p.exact::<3>(i, "3").map(|[x, y, z]| Point3::new(x, y, z)))
                    .collect::<Result<_, _>>()?,
            )
        };
        Ok(BSplineInput {
            points,
            closed: input.closed.unwrap_or(true),
        })
    }
}

impl SpaceInput {
    /// Parses a `kappa space` input.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidInput`]: malformed JSON, unknown fields, wrong types, a point without
    /// exactly three finite coordinates, too many points, `replace` outside `[0, 1]`.
    pub fn from_json(text: &str, limits: &InputLimits) -> Result<SpaceInput, Error> {
        let input: RawSpace = parse_json(text, "space", limits)?;
        let points = input
            .points
            .iter()
            .enumerate()
            .map(|(index, p)| {
                let [x, y, z] = p.exact::<3>(index, "3 ([x, y, z])")?;
                Ok(Point3::new(x, y, z))
            })
            .collect::<Result<Vec<Point3>, Error>>()?;
        let replace = input.replace.unwrap_or(0.01);
        if !(0.0..=1.0).contains(&replace) {
            return Err(invalid(format!(
                "replace is {replace}, expected a fraction in [0, 1]"
            )));
        }
        Ok(SpaceInput {
            points,
            closed: input.closed.unwrap_or(true),
            replace,
        })
    }
}

impl HermiteInput {
    /// Parses a `kappa hermite` input.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidInput`]: malformed JSON, unknown fields, wrong types, null
    /// coordinates, a degree above [`MAX_HERMITE_DEGREE`], a list of control curvatures
    /// whose length is not `degree + 1`.
    pub fn from_json(text: &str) -> Result<HermiteInput, Error> {
        let input: RawHermite = parse_json(text, "hermite", &InputLimits::default())?;
        let end = |e: &RawEnd, name: &str| -> Result<HermiteEnd, Error> {
            let [Some(x), Some(y)] = e.point else {
                return Err(invalid(format!(
                    "the {name} point has a null coordinate (JSON has no NaN or infinity; \
                     coordinates must be finite numbers)"
                )));
            };
            Ok(HermiteEnd {
                point: Point::new(x, y),
                angle: e.angle,
                curvature: e.curvature,
            })
        };
        let n = input.degree;
        if n > MAX_HERMITE_DEGREE {
            return Err(invalid(format!(
                "degree {n} is above the limit of {MAX_HERMITE_DEGREE}"
            )));
        }
        let controls = match input.control_curvatures {
            None => vec![Control::Free; n + 1],
            Some(list) => {
                if list.len() != n + 1 {
                    return Err(invalid(format!(
                        "control_curvatures has {} entries, degree {n} needs {}",
                        list.len(),
                        n + 1
                    )));
                }
                list.into_iter()
                    .map(|c| match c {
                        None => Control::Free,
                        Some(RawControl::Given(v)) => Control::Given(v),
                        Some(RawControl::Same(s)) => Control::Same(s.same_as),
                    })
                    .collect()
            }
        };
        let hermite = Hermite {
            start: end(&input.start, "start")?,
            end: end(&input.end, "end")?,
            turning: match input.turning {
                None | Some(RawTurning::Nearest) => Turning::Nearest,
                Some(RawTurning::AsGiven) => Turning::AsGiven,
            },
        };
        Ok(HermiteInput {
            hermite,
            profile: Profile {
                controls,
                weights: input.weights,
            },
        })
    }
}

/// The error for `message`, with control characters (which the input may bring in, in a
/// field name or a string) escaped, so that it stays one printable line.
fn invalid(message: String) -> Error {
    let mut clean = String::with_capacity(message.len());
    for c in message.chars() {
        if c.is_control() {
            clean.extend(c.escape_default());
        } else {
            clean.push(c);
        }
    }
    Error::InvalidInput(clean)
}

std::thread_local! {
    /// The point limit of the parse running on this thread (read by [`capped_points`]).
    static MAX_POINTS: Cell<usize> = const { Cell::new(DEFAULT_MAX_POINTS) };
}

/// `serde_json::from_str` with the point limit in force; errors name the input.
fn parse_json<T: for<'de> Deserialize<'de>>(
    text: &str,
    what: &str,
    limits: &InputLimits,
) -> Result<T, Error> {
    let previous = MAX_POINTS.with(|m| m.replace(limits.max_points));
    let result = serde_json::from_str(text);
    MAX_POINTS.with(|m| m.set(previous));
    result.map_err(|e| invalid(format!("invalid {what} JSON: {e}")))
}

/// A point as read: up to three coordinates kept, all of them counted.
#[derive(Clone, Copy, Debug, Default)]
struct RawPoint {
    coords: [Option<f64>; 3],
    len: usize,
}

impl RawPoint {
    /// The coordinates of a point that must have exactly `D`.
    fn exact<const D: usize>(&self, index: usize, expected: &str) -> Result<[f64; D], Error> {
        if self.len != D {
            return Err(invalid(format!(
                "point {index} has {} coordinates, expected {expected}",
                self.len
            )));
        }
        let mut out = [0.0; D];
        for (o, c) in out.iter_mut().zip(&self.coords) {
            *o = c.ok_or_else(|| {
                invalid(format!(
                    "point {index} has a null coordinate (JSON has no NaN or infinity; \
                     coordinates must be finite numbers)"
                ))
            })?;
        }
        Ok(out)
    }
}

impl<'de> Deserialize<'de> for RawPoint {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<RawPoint, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = RawPoint;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a point: a list of coordinates")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RawPoint, A::Error> {
                let mut p = RawPoint::default();
                while p.len < 3 {
                    match seq.next_element::<Option<f64>>()? {
                        Some(c) => p.coords[p.len] = c,
                        None => return Ok(p),
                    }
                    p.len += 1;
                }
                // Count the rest without keeping it.
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    p.len += 1;
                }
                Ok(p)
            }
        }
        d.deserialize_seq(V)
    }
}

/// A list of points, rejected at the first point beyond the limit of the running parse.
fn capped_points<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<RawPoint>, D::Error> {
    struct V(usize);
    impl<'de> Visitor<'de> for V {
        type Value = Vec<RawPoint>;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a list of points")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<RawPoint>, A::Error> {
            let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(self.0).min(4096));
            while let Some(p) = seq.next_element::<RawPoint>()? {
                if out.len() == self.0 {
                    return Err(de::Error::custom(format!(
                        "more than {} points (the limit; see --max-points)",
                        self.0
                    )));
                }
                out.push(p);
            }
            Ok(out)
        }
    }
    d.deserialize_seq(V(MAX_POINTS.with(Cell::get)))
}

/// A list of at most `N` elements, rejected at the first one beyond.
fn capped_list<'de, D: Deserializer<'de>, T: Deserialize<'de>, const N: usize>(
    d: D,
) -> Result<Option<Vec<T>>, D::Error> {
    struct V<T, const N: usize>(core::marker::PhantomData<T>);
    impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for V<T, N> {
        type Value = Option<Vec<T>>;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a list")
        }
        fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
            Ok(None)
        }
        fn visit_none<E: de::Error>(self) -> Result<Self::Value, E> {
            Ok(None)
        }
        fn visit_some<D2: Deserializer<'de>>(self, d: D2) -> Result<Self::Value, D2::Error> {
            d.deserialize_seq(self)
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut out = Vec::new();
            while let Some(x) = seq.next_element::<T>()? {
                if out.len() == N {
                    return Err(de::Error::custom(format!("more than {N} entries")));
                }
                out.push(x);
            }
            Ok(Some(out))
        }
    }
    d.deserialize_option(V::<T, N>(core::marker::PhantomData))
}

/// A `"shape"` value as read: a number, or a list of entries (each a number or what it was
/// instead), at most as long as the point limit.
#[derive(Debug)]
enum RawShape {
    Global(f64),
    PerPoint(Vec<Entry>),
    Other(String),
}

/// An entry that should be a number.
#[derive(Debug)]
enum Entry {
    Number(f64),
    Other(String),
}

impl RawShape {
    fn into_shape(self) -> Result<Shape, Error> {
        match self {
            RawShape::Global(a) => Ok(Shape::Global(a)),
            RawShape::PerPoint(list) => list
                .into_iter()
                .enumerate()
                .map(|(index, e)| match e {
                    Entry::Number(a) => Ok(a),
                    Entry::Other(v) => Err(invalid(format!(
                        "shape parameter {index} is {v}, expected a number"
                    ))),
                })
                .collect::<Result<Vec<f64>, Error>>()
                .map(Shape::PerPoint),
            RawShape::Other(v) => Err(invalid(format!(
                "shape is {v}, expected a number or a list of numbers (one per point)"
            ))),
        }
    }
}

/// Describes a non-number JSON value in a few words, reading past it.
macro_rules! describe_others {
    ($out:ty, $wrap:expr) => {
        fn visit_bool<E: de::Error>(self, v: bool) -> Result<$out, E> {
            Ok($wrap(v.to_string()))
        }
        fn visit_str<E: de::Error>(self, v: &str) -> Result<$out, E> {
            Ok($wrap(format!("{v:?}")))
        }
        fn visit_unit<E: de::Error>(self) -> Result<$out, E> {
            Ok($wrap("null".to_owned()))
        }
        fn visit_map<A: de::MapAccess<'de>>(self, mut map: A) -> Result<$out, A::Error> {
            while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
            Ok($wrap("an object".to_owned()))
        }
    };
}

impl<'de> Deserialize<'de> for Entry {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Entry, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Entry;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Entry, E> {
                Ok(Entry::Number(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Entry, E> {
                Ok(Entry::Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Entry, E> {
                Ok(Entry::Number(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Entry, A::Error> {
                while seq.next_element::<IgnoredAny>()?.is_some() {}
                Ok(Entry::Other("a list".to_owned()))
            }
            describe_others!(Entry, Entry::Other);
        }
        d.deserialize_any(V)
    }
}

impl<'de> Deserialize<'de> for RawShape {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<RawShape, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = RawShape;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or a list of numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<RawShape, E> {
                Ok(RawShape::Global(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<RawShape, E> {
                Ok(RawShape::Global(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<RawShape, E> {
                Ok(RawShape::Global(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RawShape, A::Error> {
                let max = MAX_POINTS.with(Cell::get);
                let mut out = Vec::new();
                while let Some(e) = seq.next_element::<Entry>()? {
                    if out.len() == max {
                        return Err(de::Error::custom(format!(
                            "more than {max} shape parameters (the point limit; see --max-points)"
                        )));
                    }
                    out.push(e);
                }
                Ok(RawShape::PerPoint(out))
            }
            describe_others!(RawShape, RawShape::Other);
        }
        d.deserialize_any(V)
    }
}

/// `kappa curve` as read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCurve {
    #[serde(deserialize_with = "capped_points")]
    points: Vec<RawPoint>,
    #[serde(default)]
    closed: Option<bool>,
    #[serde(default)]
    scheme: Option<Scheme>,
    #[serde(default)]
    shape: Option<RawShape>,
}

/// `kappa bspline` as read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBSpline {
    #[serde(deserialize_with = "capped_points")]
    points: Vec<RawPoint>,
    #[serde(default)]
    closed: Option<bool>,
}

/// `kappa space` as read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpace {
    #[serde(deserialize_with = "capped_points")]
    points: Vec<RawPoint>,
    #[serde(default)]
    closed: Option<bool>,
    #[serde(default)]
    replace: Option<f64>,
}

/// One end of `kappa hermite` as read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEnd {
    point: [Option<f64>; 2],
    angle: f64,
    #[serde(default)]
    curvature: Option<f64>,
}

/// An entry of "control_curvatures".
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawControl {
    Given(f64),
    Same(SameAs),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SameAs {
    same_as: usize,
}

/// The turning names.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum RawTurning {
    Nearest,
    AsGiven,
}

/// `kappa hermite` as read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHermite {
    start: RawEnd,
    end: RawEnd,
    degree: usize,
    #[serde(default, deserialize_with = "capped_list::<_, Option<RawControl>, 65>")]
    control_curvatures: Option<Vec<Option<RawControl>>>,
    #[serde(default, deserialize_with = "capped_list::<_, f64, 65>")]
    weights: Option<Vec<f64>>,
    #[serde(default)]
    turning: Option<RawTurning>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(text: &str) -> Result<CurveInput, Error> {
        CurveInput::from_json(text, &InputLimits::default())
    }

    #[test]
    fn curve_input_defaults_and_shapes() {
        let job = curve(r#"{"points": [[0, 0], [1, 0], [0, 1]]}"#).unwrap();
        assert!(job.closed);
        assert_eq!(job.scheme, Scheme::Kappa);
        assert_eq!(job.shape, Shape::Neutral);
        let job = curve(r#"{"points": [], "scheme": "ek-cubic", "shape": 0.8}"#).unwrap();
        assert_eq!(job.shape, Shape::Global(0.8));
        let job = curve(r#"{"points": [], "shape": [0.7, 1]}"#).unwrap();
        assert_eq!(job.shape, Shape::PerPoint(vec![0.7, 1.0]));
        for (bad, needle) in [
            (r#"{"points": [], "shape": "x"}"#, r#"shape is "x""#),
            (
                r#"{"points": [], "shape": [0.7, null]}"#,
                "parameter 1 is null",
            ),
            (r#"{"points": [], "shape": [[1]]}"#, "parameter 0 is a list"),
            (r#"{"points": [], "shape": {"a": 1}}"#, "an object"),
            (r#"{"points": [[0, null]]}"#, "null coordinate"),
            (r#"{"points": [[0, 1, 2]]}"#, "point 0 has 3 coordinates"),
            (
                r#"{"points": [[0, 1, 2, 3, 4]]}"#,
                "point 0 has 5 coordinates",
            ),
            (
                r#"{"points": [], "colsed": true}"#,
                "unknown field `colsed`",
            ),
            (r#"{"points": [[0, NaN]]}"#, "invalid curve JSON"),
            (r#"{"points": {"x": 1}}"#, "a list of points"),
        ] {
            let e = curve(bad).unwrap_err();
            assert!(matches!(e, Error::InvalidInput(_)), "{bad}");
            assert!(e.to_string().contains(needle), "{bad}: {e}");
        }
    }

    #[test]
    fn point_limit_is_checked_while_parsing() {
        let limits = InputLimits { max_points: 3 };
        let ok = r#"{"points": [[0, 0], [1, 0], [0, 1]]}"#;
        assert_eq!(CurveInput::from_json(ok, &limits).unwrap().points.len(), 3);
        // The fourth point is rejected before the rest of the text is even valid JSON.
        let e = CurveInput::from_json(
            r#"{"points": [[0, 0], [1, 0], [0, 1], [1, 1], oops"#,
            &limits,
        )
        .unwrap_err();
        assert!(e.to_string().contains("more than 3 points"), "{e}");
        let e =
            CurveInput::from_json(r#"{"points": [], "shape": [1, 1, 1, 1]}"#, &limits).unwrap_err();
        assert!(
            e.to_string().contains("more than 3 shape parameters"),
            "{e}"
        );
        let e = BSplineInput::from_json(r#"{"points": [[0,0],[0,0],[0,0],[0,0]]}"#, &limits)
            .unwrap_err();
        assert!(e.to_string().contains("more than 3 points"), "{e}");
        let e = SpaceInput::from_json(r#"{"points": [[0,0,0],[0,0,0],[0,0,0],[0,0,0]]}"#, &limits)
            .unwrap_err();
        assert!(e.to_string().contains("more than 3 points"), "{e}");
    }

    #[test]
    fn bspline_and_space_inputs() {
        let l = InputLimits::default();
        let b =
            BSplineInput::from_json(r#"{"points": [[0, 0, 1], [1, 0, 2]], "closed": false}"#, &l)
                .unwrap();
        assert_eq!(
            b.points,
            BSplinePoints::Space(vec![Point3::new(0.0, 0.0, 1.0), Point3::new(1.0, 0.0, 2.0)])
        );
        assert!(!b.closed);
        for bad in [
            r#"{"points": [[0, 0], [1, 0, 2]]}"#,
            r#"{"points": [[0]]}"#,
            r#"{"points": [[0, null]]}"#,
            r#"{"points": [], "open": true}"#,
        ] {
            assert!(BSplineInput::from_json(bad, &l).is_err(), "{bad}");
        }
        let s = SpaceInput::from_json(r#"{"points": [[0, 0, 0]], "replace": 0.2}"#, &l).unwrap();
        assert_eq!(s.replace, 0.2);
        assert!(s.closed);
        for bad in [
            r#"{"points": [[0, 0]]}"#,
            r#"{"points": [], "replace": -1}"#,
            r#"{"points": [], "replace": 2}"#,
            r#"{"points": [], "replace": "a"}"#,
        ] {
            assert!(SpaceInput::from_json(bad, &l).is_err(), "{bad}");
        }
    }

    #[test]
    fn hermite_input() {
        let h = HermiteInput::from_json(
            r#"{"start": {"point": [0, 0], "angle": 0.5}, "end": {"point": [1, 2], "angle": 1},
                "degree": 3, "control_curvatures": [null, {"same_as": 0}, 2.5, null],
                "turning": "as-given"}"#,
        )
        .unwrap();
        assert_eq!(h.hermite.turning, Turning::AsGiven);
        assert_eq!(
            h.profile.controls,
            vec![
                Control::Free,
                Control::Same(0),
                Control::Given(2.5),
                Control::Free
            ]
        );
        let huge = r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 0}, "degree": 1000000000000}"#;
        let e = HermiteInput::from_json(huge).unwrap_err();
        assert!(e.to_string().contains("above the limit"), "{e}");
        let long = format!(
            r#"{{"start": {{"point": [0, 0], "angle": 0}}, "end": {{"point": [1, 0], "angle": 0}}, "degree": 1, "weights": [{}]}}"#,
            vec!["1"; 100].join(",")
        );
        let e = HermiteInput::from_json(&long).unwrap_err();
        assert!(e.to_string().contains("more than 65 entries"), "{e}");
    }
}
