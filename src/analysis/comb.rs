//! Curvature combs.

use kurbo::{BezPath, Point};

use super::bez::Sealed;
use super::subpaths;

/// A curvature comb for a 2D path, for display.
///
/// Each segment is sampled at `samples_per_segment` parameters, uniformly in `t` and including
/// both ends (`t = j/(s−1)`; a single sample is taken at `t = ½`). At each sample `p` with signed
/// curvature κ and left unit normal `n`, the tooth runs from `p` to the tip
/// `p − scale · κ · n`: with `scale > 0` the teeth point **away from the centre of curvature**
/// (outside a bend, as in most editors), and their length is `scale · |κ|`.
///
/// The result is built from `MoveTo`/`LineTo` only, one subpath per tooth:
/// `MoveTo(p_j) LineTo(tip_j) LineTo(tip_{j+1})`, where the last `LineTo` draws the outline
/// through the tips and is omitted for the last tooth of each subpath of `path`. So the number of
/// `MoveTo` elements is the number of teeth. Both ends of consecutive segments are sampled, so a
/// curvature jump at a joint shows as two teeth at the same point.
///
/// Samples where the tangent is undefined (`r′ = 0`, see
/// [`STALL_TOLERANCE`](super::STALL_TOLERANCE)) are skipped, the outline joining the tips on
/// either side. A non-finite `scale` gives an empty path.
pub fn curvature_comb(path: &BezPath, scale: f64, samples_per_segment: usize) -> BezPath {
    let mut out = BezPath::new();
    if !scale.is_finite() || samples_per_segment == 0 {
        return out;
    }
    let ts = |j: usize| -> f64 {
        if samples_per_segment == 1 {
            0.5
        } else {
            j as f64 / (samples_per_segment - 1) as f64
        }
    };
    let mut teeth: Vec<(Point, Point)> = Vec::new();
    for sp in subpaths(path) {
        teeth.clear();
        for (_, seg) in &sp.segs {
            let b = seg.to_bez();
            for j in 0..samples_per_segment {
                let t = ts(j);
                if b.is_stall(t) {
                    continue;
                }
                let p = b.eval(t);
                let k = b.curvature_vector(t);
                let base = Point::new(p.x, p.y);
                let tip = Point::new(p.x - scale * k.x, p.y - scale * k.y);
                if base.is_finite() && tip.is_finite() {
                    teeth.push((base, tip));
                }
            }
        }
        push_teeth(&mut out, &teeth);
    }
    out
}

/// A curvature comb from samples `(p, k)` of one curve in order, `k` the curvature vector
/// (`κ` times the left unit normal, see [`CurvatureAnalysis::curvature_vector`](super::CurvatureAnalysis::curvature_vector)):
/// teeth from `p` to `p − scale · k`, drawn like [`curvature_comb`]. For curves that are not
/// Bézier paths (trigonometric segments) or when the samples come from elsewhere. Non-finite
/// samples are skipped; a non-finite `scale` gives an empty path.
pub fn comb_from_samples(
    samples: impl IntoIterator<Item = (Point, kurbo::Vec2)>,
    scale: f64,
) -> BezPath {
    let mut out = BezPath::new();
    if !scale.is_finite() {
        return out;
    }
    let teeth: Vec<(Point, Point)> = samples
        .into_iter()
        .map(|(p, k)| (p, p - scale * k))
        .filter(|(p, tip)| p.is_finite() && tip.is_finite())
        .collect();
    push_teeth(&mut out, &teeth);
    out
}

/// Appends teeth `base → tip` and the outline through consecutive tips.
fn push_teeth(out: &mut BezPath, teeth: &[(Point, Point)]) {
    for (j, &(base, tip)) in teeth.iter().enumerate() {
        out.move_to(base);
        out.line_to(tip);
        if let Some(&(_, next)) = teeth.get(j + 1) {
            out.line_to(next);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::PathEl;

    #[test]
    fn comb_teeth_point_outward_on_ccw_arc() {
        // A left-turning (anticlockwise) quarter arc around the origin.
        let k = 0.551_915_024_494;
        let mut p = BezPath::new();
        p.move_to((1.0, 0.0));
        p.curve_to((1.0, k), (k, 1.0), (0.0, 1.0));
        let comb = curvature_comb(&p, 0.5, 5);
        let els = comb.elements();
        let mut n_moves = 0;
        for (i, el) in els.iter().enumerate() {
            if let PathEl::MoveTo(base) = *el {
                n_moves += 1;
                let PathEl::LineTo(tip) = els[i + 1] else {
                    panic!("tooth without tip")
                };
                // Radius 1 and κ ≈ 1 (within the 2% curvature error of this approximation):
                // the tip lies outside, about 1.5 from the centre, radially from the base.
                let (rb, rt) = (base.to_vec2().hypot(), tip.to_vec2().hypot());
                assert!((rt - rb - 0.5).abs() < 0.5 * 0.025, "{rb} {rt}");
                assert!(base.to_vec2().cross(tip.to_vec2()).abs() < 1e-3);
            }
        }
        assert_eq!(n_moves, 5);
    }

    #[test]
    fn comb_skips_cusp_sample() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.curve_to((1.0, 1.0), (0.0, 1.0), (1.0, 0.0));
        // t = 0, 0.5, 1: the middle one is the cusp.
        let comb = curvature_comb(&p, 1.0, 3);
        let moves = comb
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::MoveTo(_)))
            .count();
        assert_eq!(moves, 2);
        assert!(comb.elements().iter().all(|e| match e {
            PathEl::MoveTo(p) | PathEl::LineTo(p) => p.is_finite(),
            _ => false,
        }));
    }
}
