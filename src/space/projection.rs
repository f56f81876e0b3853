//! Projections of space curves to 2D kurbo paths.

use core::ops::Range;

use kurbo::{BezPath, CurveFitSample, ParamCurveFit, PathEl, Point, Vec2};

use crate::analysis::SpaceBez;
use crate::fit::{fit, speed_cusp, FitOptions, FitTolerance};
use crate::{Error, Point3, Vec3};

use super::SpaceCurve;

use core::f64::consts::FRAC_1_SQRT_2;
/// `1/√3`.
const FRAC_1_SQRT_3: f64 = 0.577_350_269_189_625_8;
/// `1/√6`.
const FRAC_1_SQRT_6: f64 = 0.408_248_290_463_863;

/// A camera orientation: an orthonormal, right-handed frame `right × up = −forward` (the
/// camera looks along `forward`; `right` and `up` span the picture, y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    right: Vec3,
    up: Vec3,
    forward: Vec3,
}

impl View {
    /// Looking down the z axis (plan view): x to the right, y up.
    pub const TOP: View = View {
        right: Vec3::new(1.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        forward: Vec3::new(0.0, 0.0, -1.0),
    };
    /// Looking along +y (front elevation): x to the right, z up.
    pub const FRONT: View = View {
        right: Vec3::new(1.0, 0.0, 0.0),
        up: Vec3::new(0.0, 0.0, 1.0),
        forward: Vec3::new(0.0, 1.0, 0.0),
    };
    /// Looking along −x (side elevation): y to the right, z up.
    pub const SIDE: View = View {
        right: Vec3::new(0.0, 1.0, 0.0),
        up: Vec3::new(0.0, 0.0, 1.0),
        forward: Vec3::new(-1.0, 0.0, 0.0),
    };

    /// The isometric view: looking along `−(1, 1, 1)` with z up, so that the three axes are
    /// 120° apart in the picture (x to the lower left, y to the lower right);
    /// `View::looking(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(0.0, 0.0, 1.0))`.
    pub const ISOMETRIC: View = View {
        right: Vec3::new(-FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0),
        up: Vec3::new(-FRAC_1_SQRT_6, -FRAC_1_SQRT_6, 2.0 * FRAC_1_SQRT_6),
        forward: Vec3::new(-FRAC_1_SQRT_3, -FRAC_1_SQRT_3, -FRAC_1_SQRT_3),
    };

    /// The view looking along `forward`, with the projection of `up` pointing up in the
    /// picture.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] if either vector is zero or not finite, or they are parallel.
    pub fn looking(forward: Vec3, up: Vec3) -> Result<View, Error> {
        let bad = Error::InvalidOption("a view needs finite, non-parallel forward and up vectors");
        let f_len = forward.length();
        if !(f_len > 0.0 && f_len.is_finite()) {
            return Err(bad);
        }
        let forward = forward * (1.0 / f_len);
        let right = forward.cross(up);
        let r_len = right.length();
        if !(r_len > 1e-12 * up.length() && r_len.is_finite()) {
            return Err(bad);
        }
        let right = right * (1.0 / r_len);
        let up = right.cross(forward);
        Ok(View { right, up, forward })
    }

    /// The unit vector to the right in the picture.
    pub fn right(&self) -> Vec3 {
        self.right
    }

    /// The unit vector up in the picture.
    pub fn up(&self) -> Vec3 {
        self.up
    }

    /// The unit viewing direction.
    pub fn forward(&self) -> Vec3 {
        self.forward
    }
}

/// A map from 3D to the picture plane (y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel projection: `(p · right, p · up)`. Polynomial curves stay polynomial of the
    /// same degree.
    Orthographic(View),
    /// Central projection from `eye`:
    /// `focal · ((p − eye) · right, (p − eye) · up) / ((p − eye) · forward)`. Polynomial curves
    /// become rational ones.
    Perspective {
        /// The camera orientation.
        view: View,
        /// The centre of projection.
        eye: Point3,
        /// The distance from the eye to the picture plane.
        focal: f64,
    },
}

impl Projection {
    /// A perspective camera at `eye` looking at `target`, with `up` up and the picture plane
    /// at distance `focal`.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] for a non-finite eye or target, `eye == target`, `up` parallel
    /// to the viewing direction, or a focal distance that is not positive and finite.
    pub fn perspective(
        eye: Point3,
        target: Point3,
        up: Vec3,
        focal: f64,
    ) -> Result<Projection, Error> {
        if !(eye.is_finite() && target.is_finite()) {
            return Err(Error::InvalidOption(
                "the camera's eye and target must be finite",
            ));
        }
        if !(focal > 0.0 && focal.is_finite()) {
            return Err(Error::InvalidOption(
                "the focal distance must be positive and finite",
            ));
        }
        Ok(Projection::Perspective {
            view: View::looking(target - eye, up)?,
            eye,
            focal,
        })
    }

    /// The camera orientation.
    pub fn view(&self) -> View {
        match self {
            Projection::Orthographic(v) => *v,
            Projection::Perspective { view, .. } => *view,
        }
    }

    /// The image of a point; `None` in perspective for a point not in front of the eye.
    pub fn point(&self, p: Point3) -> Option<Point> {
        match *self {
            Projection::Orthographic(v) => {
                let q = p.to_vec3();
                Some(Point::new(q.dot(v.right), q.dot(v.up)))
            }
            Projection::Perspective { view, eye, focal } => {
                let d = p - eye;
                let depth = d.dot(view.forward);
                (depth > 0.0).then(|| {
                    let s = focal / depth;
                    Point::new(s * d.dot(view.right), s * d.dot(view.up))
                })
            }
        }
    }

    /// The image of a point and of a tangent vector `d` at it (the derivative of the
    /// projected curve); `None` as for [`point`](Self::point).
    pub fn point_deriv(&self, p: Point3, d: Vec3) -> Option<(Point, Vec2)> {
        match *self {
            Projection::Orthographic(v) => {
                Some((self.point(p)?, Vec2::new(d.dot(v.right), d.dot(v.up))))
            }
            Projection::Perspective { view, eye, focal } => {
                let rel = p - eye;
                let depth = rel.dot(view.forward);
                if depth.is_nan() || depth <= 0.0 {
                    return None;
                }
                // Quotient rule on focal · (x/w, y/w).
                let (x, y) = (rel.dot(view.right), rel.dot(view.up));
                let (dx, dy, dw) = (d.dot(view.right), d.dot(view.up), d.dot(view.forward));
                let s = focal / depth;
                let point = Point::new(s * x, s * y);
                let deriv = Vec2::new(dx - x * dw / depth, dy - y * dw / depth) * s;
                Some((point, deriv))
            }
        }
    }
}

/// A projected space curve.
#[derive(Clone, Debug)]
pub struct Projected {
    /// The picture (y up): exact `QuadTo`s for the quadratics under orthographic projection,
    /// fitted `CurveTo`s elsewhere, `ClosePath` for closed curves.
    pub path: BezPath,
    /// How many segments went through [`crate::fit`] (the quartics, or every segment under
    /// perspective).
    pub fitted: usize,
    /// The absolute fitting tolerance used.
    pub tolerance: f64,
    /// The largest distance measured between a fitted segment and the exact projection
    /// (see [`crate::fit::Fitted::max_distance`]); 0 if nothing was fitted.
    pub max_distance: f64,
}

/// One segment seen through a projection, for the fitter.
struct ProjectedBez {
    bez: SpaceBez,
    hodograph: SpaceBez,
    projection: Projection,
}

impl ProjectedBez {
    fn new(bez: SpaceBez, projection: Projection) -> ProjectedBez {
        ProjectedBez {
            bez,
            hodograph: bez.deriv(),
            projection,
        }
    }

    fn sample(&self, t: f64) -> (Point, Vec2) {
        let p = self.bez.eval(t);
        let d = self.hodograph.eval(t).to_vec3();
        // Every control point is in front of the eye (checked before fitting), so the convex
        // hull, and with it every curve point, is too.
        self.projection.point_deriv(p, d).unwrap_or((
            Point::new(f64::NAN, f64::NAN),
            Vec2::new(f64::NAN, f64::NAN),
        ))
    }
}

impl ParamCurveFit for ProjectedBez {
    fn sample_pt_tangent(&self, t: f64, sign: f64) -> CurveFitSample {
        let (p, d) = self.sample(t);
        let tangent = if d.hypot2() > 0.0 {
            d
        } else {
            // A stall (the tangent along the viewing direction): step off it.
            let (_, d2) = self.sample((t + sign * 1e-9).clamp(0.0, 1.0));
            d2
        };
        CurveFitSample { p, tangent }
    }

    fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
        self.sample(t)
    }

    fn break_cusp(&self, range: Range<f64>) -> Option<f64> {
        // Where the space tangent points along the viewing direction the picture has a cusp.
        speed_cusp(|t| self.sample(t).1, range)
    }
}

impl SpaceCurve {
    /// The curve as seen through `projection`, as a kurbo path (y up).
    ///
    /// Under orthographic projection a quadratic is again a quadratic (exact `QuadTo`); the
    /// quartics become planar quartics, which kurbo has no element for, and are fitted with
    /// cubics by [`crate::fit`]. Under perspective projection every segment becomes a
    /// rational curve and every segment is fitted. A relative tolerance is relative to the
    /// size of the whole projected curve; the fitted cubics keep the G1 joints.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] if a control point is not in front of a perspective eye (then
    /// part of the curve may be behind it) or the tolerance is not positive and finite; the
    /// errors of [`crate::fit::fit`].
    pub fn project(
        &self,
        projection: &Projection,
        options: &FitOptions,
    ) -> Result<Projected, Error> {
        let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
        let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        for s in self.segments() {
            for &p in s.control_points() {
                let q = projection.point(p).ok_or(Error::InvalidOption(
                    "the curve must lie in front of the perspective eye",
                ))?;
                lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
                hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
            }
        }
        let tolerance = match options.tolerance {
            FitTolerance::Absolute(v) => v,
            FitTolerance::Relative(v) => {
                let size = (0.5 * hi.x - 0.5 * lo.x).max(0.5 * hi.y - 0.5 * lo.y) * 2.0;
                if !size.is_finite() {
                    return Err(Error::ExtentOverflow);
                }
                v * if size > 0.0 { size } else { 1.0 }
            }
        };
        if !(tolerance > 0.0 && tolerance.is_finite()) {
            return Err(Error::InvalidOption(
                "fit tolerance must be finite and positive",
            ));
        }
        let fit_options = FitOptions {
            tolerance: FitTolerance::Absolute(tolerance),
            ..*options
        };
        let exact_quads = matches!(projection, Projection::Orthographic(_));
        let mut path = BezPath::new();
        let mut fitted = 0;
        let mut max_distance: f64 = 0.0;
        for (i, s) in self.segments().iter().enumerate() {
            let pts = s.control_points();
            let start = projection.point(pts[0]).unwrap_or_default();
            if i == 0 {
                path.move_to(start);
            }
            if exact_quads && pts.len() <= 3 {
                let img: Vec<Point> = pts.iter().filter_map(|&p| projection.point(p)).collect();
                match img.len() {
                    3 => path.quad_to(img[1], img[2]),
                    2 => path.line_to(img[1]),
                    _ => {}
                }
                continue;
            }
            let piece = ProjectedBez::new(*s, *projection);
            let f =
                fit(core::slice::from_ref(&piece), false, &fit_options).map_err(|e| match e {
                    Error::NonFiniteCurve { .. } => Error::NonFiniteCurve { segment: i },
                    other => other,
                })?;
            fitted += 1;
            max_distance = max_distance.max(f.max_distance);
            for el in f.path.elements() {
                match *el {
                    PathEl::CurveTo(a, b, c) => path.curve_to(a, b, c),
                    PathEl::LineTo(a) => path.line_to(a),
                    PathEl::QuadTo(a, b) => path.quad_to(a, b),
                    PathEl::MoveTo(_) | PathEl::ClosePath => {}
                }
            }
            // End exactly on the projected end point, which the next segment starts from.
            if let (Some(end), Some(PathEl::CurveTo(_, _, p))) =
                (projection.point(s.end()), path.elements_mut().last_mut())
            {
                *p = end;
            }
        }
        if self.is_closed() && !self.segments().is_empty() {
            path.close_path();
        }
        Ok(Projected {
            path,
            fitted,
            tolerance,
            max_distance,
        })
    }
}
