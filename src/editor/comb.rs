//! Curvature combs for an editor: teeth along the normal, scaled by a percentile of |κ| so
//! that one sharp point does not flatten the comb everywhere else.

use kurbo::{BezPath, Point, Vec2};

use crate::Spline;

/// How a comb is sampled and scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CombStyle {
    /// Teeth per segment (at least 2, ends included).
    pub samples: usize,
    /// The length of a tooth at the reference curvature, in drawing units.
    pub length: f64,
    /// Which |κ| is the reference, as a fraction of the samples in increasing |κ| order:
    /// `0.9` takes the 90th percentile, `1.0` the largest. Zero samples (straight
    /// stretches) are not counted. Values outside `[0, 1]` are clamped.
    pub percentile: f64,
    /// The longest tooth, as a multiple of `length`: longer teeth are cut to it (their
    /// direction kept) and counted in [`Comb::clipped`].
    pub clip: f64,
    /// A fixed scale (drawing units per unit of curvature) instead of the percentile's, to
    /// keep the comb steady during a drag.
    pub scale: Option<f64>,
}

impl Default for CombStyle {
    fn default() -> CombStyle {
        CombStyle {
            samples: 16,
            length: 50.0,
            percentile: 0.75,
            clip: 3.0,
            scale: None,
        }
    }
}

/// A curvature comb: for each curve, its teeth from the curve point (`base`) to the tip,
/// `tip = base − scale · κ n` (`n` the left unit normal: the teeth stand on the convex
/// side), so every tooth lies along the curve's normal.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Comb {
    /// The teeth `(base, tip)` of each curve, in curve order.
    pub teeth: Vec<Vec<(Point, Point)>>,
    /// Drawing units per unit of curvature (0 when every curve is straight).
    pub scale: f64,
    /// How many teeth were cut to the clip length.
    pub clipped: usize,
}

impl Comb {
    /// The comb of `splines` in `style` (see [`CombStyle`]). Non-finite samples are
    /// skipped; a non-finite or negative `length`, `clip` or fixed `scale` counts as zero.
    pub fn new<'a>(splines: impl IntoIterator<Item = &'a Spline>, style: &CombStyle) -> Comb {
        let samples: Vec<Vec<(Point, Vec2)>> = splines
            .into_iter()
            .map(|s| {
                s.curvature_samples(style.samples)
                    .into_iter()
                    .filter(|(p, k)| p.is_finite() && k.is_finite())
                    .collect()
            })
            .collect();
        let finite = |x: f64| if x.is_finite() && x > 0.0 { x } else { 0.0 };
        let length = finite(style.length);
        let scale = match style.scale {
            Some(s) => finite(s),
            None => {
                let reference = reference_curvature(
                    samples.iter().flatten().map(|(_, k)| k.hypot()),
                    style.percentile,
                );
                if reference > 0.0 {
                    finite(length / reference)
                } else {
                    0.0
                }
            }
        };
        let longest = length * finite(style.clip);
        let mut clipped = 0;
        let teeth = samples
            .into_iter()
            .map(|curve| {
                curve
                    .into_iter()
                    .map(|(p, k)| {
                        let mut v = scale * k;
                        let len = v.hypot();
                        if len > longest && len.is_finite() {
                            v *= longest / len;
                            clipped += 1;
                        }
                        (p, p - v)
                    })
                    .filter(|(_, tip)| tip.is_finite())
                    .collect()
            })
            .collect();
        Comb {
            teeth,
            scale,
            clipped,
        }
    }

    /// The comb as a path: each tooth a line from base to tip, then, for each curve, the
    /// outline through its tips.
    pub fn to_bezpath(&self) -> BezPath {
        let mut out = BezPath::new();
        for curve in &self.teeth {
            for &(base, tip) in curve {
                out.move_to(base);
                out.line_to(tip);
            }
        }
        for curve in &self.teeth {
            for (j, &(_, tip)) in curve.iter().enumerate() {
                if j == 0 {
                    out.move_to(tip);
                } else {
                    out.line_to(tip);
                }
            }
        }
        out
    }
}

/// The |κ| at `percentile` of the nonzero values (clamped to `[0, 1]`; the largest for
/// 1), or 0 when there are none.
fn reference_curvature(values: impl Iterator<Item = f64>, percentile: f64) -> f64 {
    let mut v: Vec<f64> = values.filter(|k| k.is_finite() && *k > 0.0).collect();
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let q = if percentile.is_nan() {
        1.0
    } else {
        percentile.clamp(0.0, 1.0)
    };
    let i = ((v.len() - 1) as f64 * q).round() as usize;
    v[i.min(v.len() - 1)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Scheme, Shape, Solver};

    fn curve(shapes: &[f64]) -> Spline {
        let pts: Vec<Point> = (0..shapes.len())
            .map(|i| {
                let th = i as f64 / shapes.len() as f64 * std::f64::consts::TAU;
                Point::new(100.0 * th.cos(), 80.0 * th.sin())
            })
            .collect();
        Solver::new()
            .solve(
                &pts,
                true,
                Scheme::EkCubic,
                &Shape::PerPoint(shapes.to_vec()),
            )
            .unwrap()
    }

    #[test]
    fn percentile_ignores_one_sharp_point() {
        let smooth = curve(&[0.7; 8]);
        let mut shapes = [0.7; 8];
        shapes[3] = 0.99;
        let sharp = curve(&shapes);
        let style = CombStyle::default();
        let a = Comb::new([&smooth], &style);
        let b = Comb::new([&sharp], &style);
        // The largest |κ| grows several times; the comb's scale barely changes.
        assert!(sharp.max_abs_curvature() > 3.0 * smooth.max_abs_curvature());
        assert!(b.scale > 0.9 * a.scale, "{} vs {}", b.scale, a.scale);
        // The sharp point's teeth are cut to the clip length.
        assert!(b.clipped > 0);
        let longest = b
            .teeth
            .iter()
            .flatten()
            .map(|(p, q)| (*p - *q).hypot())
            .fold(0.0, f64::max);
        assert!(longest <= style.length * style.clip * (1.0 + 1e-12));
    }

    #[test]
    fn teeth_are_normal_to_the_curve() {
        let s = curve(&[0.8; 6]);
        let comb = Comb::new([&s], &CombStyle::default());
        let seg = &s.segments()[0];
        // Tooth j of segment 0 at t = j / 15.
        for (j, &(base, tip)) in comb.teeth[0][..16].iter().enumerate() {
            let t = j as f64 / 15.0;
            let d = seg.eval(t + 1e-6) - seg.eval(t - 1e-6);
            let tooth = tip - base;
            if tooth.hypot() > 1e-9 {
                let cos = d.dot(tooth) / (d.hypot() * tooth.hypot());
                assert!(cos.abs() < 1e-6, "tooth {j}: cos {cos}");
            }
            assert_eq!(base, seg.eval(t));
        }
    }

    #[test]
    fn bad_styles_give_finite_combs() {
        let s = curve(&[0.8; 5]);
        for style in [
            CombStyle {
                length: f64::NAN,
                ..CombStyle::default()
            },
            CombStyle {
                scale: Some(f64::INFINITY),
                ..CombStyle::default()
            },
            CombStyle {
                percentile: f64::NAN,
                clip: -1.0,
                samples: 0,
                ..CombStyle::default()
            },
        ] {
            let c = Comb::new([&s], &style);
            assert!(c.scale.is_finite());
            assert!(c
                .teeth
                .iter()
                .flatten()
                .all(|(a, b)| a.is_finite() && b.is_finite()));
        }
        assert_eq!(Comb::new([], &CombStyle::default()).scale, 0.0);
        assert_eq!(reference_curvature([0.0, 0.0].into_iter(), 0.9), 0.0);
        assert_eq!(reference_curvature([1.0, 2.0, 3.0].into_iter(), 1.0), 3.0);
    }
}
