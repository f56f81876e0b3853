//! Glyph outlines: drafted as κ- and εκ-curves, exported for fonts, tessellated for GPUs.
//!
//! A κ-curve is made of quadratic Béziers — what a TrueType `glyf` table stores — so a
//! κ-drafted contour goes into a font with no approximation; εκ-cubic contours go exactly
//! into cubic (UFO, CFF) outlines.
//!
//! - [`draft`]: from an outline, the points a designer would click (corners, on-curve
//!   extrema, curvature peaks) and a κ/εκ contour through them, with the Hausdorff distance
//!   to the original and the number of points; [`draft_points`] for user-given points.
//! - [`to_quadratic`], [`to_svg`]: TrueType quadratic contours and SVG documents (no
//!   feature needed).
//! - feature `font`: [`FontOutlines`] reads outlines with ttf-parser; [`to_glif`] and
//!   [`write_ufo`] write UFO sources with norad; [`compile_font`] builds a small TrueType
//!   font with write-fonts.
//! - feature `font`, whole fonts: [`rebuild_ttf`] writes a complete TrueType font from a
//!   TrueType or CFF source with some outlines replaced, [`rebuild_ufo`] a UFO 3 source with
//!   each drafted glyph's κ source in its lib ([`KAPPA_LIB_KEY`]); [`anchor_outline`] gives a
//!   drafted glyph with its anchors as the nodes; [`orient`] turns contours the way a format
//!   wants ([`Direction`]).
//! - feature `tessellate`: [`fill_mesh`] and [`stroke_mesh`] through lyon.
//!
//! # Coordinates
//!
//! Everything here is in **font units with y up**, the frame of the font's outlines (see
//! [`FontOutlines`]): x to the right, y up, the glyph origin on the baseline. Pictures in y-down
//! pixels flip y (`render::Scene` does it with `with_y_down(false)`; [`to_svg`] writes the
//! flip as a transform).
//!
//! ```
//! use kappa::glyph::{draft, DraftOptions};
//! use kurbo::BezPath;
//!
//! // A rounded square, drawn as the font would store it (quadratics with implied points).
//! let mut outline = BezPath::new();
//! outline.move_to((500.0, 0.0));
//! outline.quad_to((1000.0, 0.0), (1000.0, 500.0));
//! outline.quad_to((1000.0, 1000.0), (500.0, 1000.0));
//! outline.quad_to((0.0, 1000.0), (0.0, 500.0));
//! outline.quad_to((0.0, 0.0), (500.0, 0.0));
//! outline.close_path();
//! let drafted = draft(&outline, &DraftOptions::for_units_per_em(1000.0))?;
//! assert!(drafted.hausdorff.unwrap() <= 4.0 + 1e-9);
//! assert!(drafted.anchor_count() >= 4);
//! # Ok::<(), kappa::Error>(())
//! ```

mod direction;
mod draft;
mod export;
#[cfg(feature = "font")]
mod font;
mod grid;
#[cfg(feature = "font")]
mod import;
mod nodes;
#[cfg(feature = "render")]
mod picture;
#[cfg(feature = "font")]
mod rebuild;
#[cfg(feature = "tessellate")]
mod tessellate;
#[cfg(feature = "font")]
mod ufo;

pub use direction::{orient, Direction};
pub use draft::{
    draft, draft_points, hausdorff, Anchor, AnchorKind, DraftOptions, DraftShape, DraftedContour,
    DraftedGlyph, Piece, AUTO_MAX_SHAPE, AUTO_MIN_TRIG_SHAPE, AUTO_RELATIVE_TOLERANCE,
    AUTO_SECANT_STEPS, PEAK_MAX_RADIUS, PEAK_PROMINENCE, SPLIT_DEPTH,
};
#[cfg(feature = "font")]
pub use export::{from_glif, to_glif, to_norad_glyph, write_ufo, FontGlyph};
pub use export::{is_quadratic, to_quadratic, to_svg, Quadratic};
#[cfg(feature = "font")]
pub use font::{compile_font, FONT_FAMILY};
pub use grid::quantize;
#[cfg(feature = "font")]
pub use import::{FontOutlines, Glyph};
pub use nodes::{anchor_outline, NodeOutline, WRITTEN_HEADROOM, WRITTEN_SAMPLES};
#[cfg(all(feature = "render", feature = "font"))]
pub use picture::{word_figure, FIGURE_WORD};
#[cfg(feature = "render")]
pub use picture::{word_scene, PlacedGlyph};
#[cfg(feature = "font")]
pub use rebuild::{drawn_glyph_ids, rebuild_ttf, RebuildOptions};
#[cfg(feature = "tessellate")]
pub use tessellate::{fill_mesh, stroke_mesh, Mesh};
#[cfg(feature = "font")]
pub use ufo::{rebuild_ufo, KAPPA_LIB_KEY};

use kurbo::{BezPath, ParamCurve, PathEl, PathSeg, Point};

/// The contours of a path: the segments of each subpath (kurbo's closing line included,
/// segments of zero extent dropped) and whether it is closed. A closing line shorter than
/// rounding (1e-9 of the largest coordinate, or of 1) is dropped as well, the last segment
/// then ending exactly where the contour starts: a line of 1e-14 units has no direction,
/// and would make a kink at the start node.
pub fn contours(path: &BezPath) -> Vec<(Vec<PathSeg>, bool)> {
    let mut out = Vec::new();
    let mut current = BezPath::new();
    let mut flush = |current: &mut BezPath, closed: bool| {
        if current.elements().is_empty() {
            return;
        }
        let mut segs: Vec<PathSeg> = current.segments().filter(|s| !is_degenerate(s)).collect();
        if closed {
            close_up(&mut segs);
        }
        out.push((segs, closed));
        *current = BezPath::new();
    };
    // Where a subpath that does not begin with MoveTo (a path built without one, which kurbo
    // allows only in release builds) starts: the current point.
    let (mut start, mut at) = (Point::ZERO, Point::ZERO);
    for el in path.elements() {
        match el {
            PathEl::MoveTo(p) => {
                flush(&mut current, false);
                current.push(*el);
                (start, at) = (*p, *p);
            }
            PathEl::ClosePath => {
                if !current.elements().is_empty() {
                    current.push(*el);
                    flush(&mut current, true);
                }
                at = start;
            }
            el => {
                if current.elements().is_empty() {
                    current.move_to(at);
                    start = at;
                }
                current.push(*el);
                at = el.end_point().unwrap_or(at);
            }
        }
    }
    flush(&mut current, false);
    out
}

/// Drops the closing line of a closed contour if it is shorter than rounding, and ends the
/// segment before it at the contour's start.
fn close_up(segs: &mut Vec<PathSeg>) {
    let (Some(PathSeg::Line(l)), true) = (segs.last().copied(), segs.len() > 1) else {
        return;
    };
    let scale = segs
        .iter()
        .flat_map(|s| [s.start(), s.end()])
        .fold(1.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    if (l.p1 - l.p0).hypot() > 1e-9 * scale {
        return;
    }
    segs.pop();
    let start = segs[0].start();
    if let Some(last) = segs.last_mut() {
        match last {
            PathSeg::Line(x) => x.p1 = start,
            PathSeg::Quad(x) => x.p2 = start,
            PathSeg::Cubic(x) => x.p3 = start,
        }
    }
}

/// Whether all control points of a segment coincide.
fn is_degenerate(seg: &PathSeg) -> bool {
    let pts: &[Point] = match seg {
        PathSeg::Line(l) => &[l.p0, l.p1],
        PathSeg::Quad(q) => &[q.p0, q.p1, q.p2],
        PathSeg::Cubic(c) => &[c.p0, c.p1, c.p2, c.p3],
    };
    pts.iter().all(|p| *p == pts[0])
}

/// The on-curve points a designer placed on an outline (see [`on_curve_points`] for the
/// counting rule), without the font feature.
pub fn on_curve_points(path: &BezPath) -> usize {
    contours(path)
        .iter()
        .map(|(segs, closed)| on_curve_points_of(segs, *closed))
        .sum()
}

/// The on-curve points of one contour: the segment end points, minus the TrueType *implied*
/// ones — a joint of two quadratics exactly midway between their off-curve points is not
/// stored in a `glyf` table (the reader puts it back), so no designer placed it. Open
/// contours count both ends.
pub(crate) fn on_curve_points_of(segs: &[PathSeg], closed: bool) -> usize {
    let n = segs.len();
    if n == 0 {
        return 0;
    }
    let joints = if closed { n } else { n - 1 };
    let implied = (0..joints)
        .filter(|&j| {
            let (prev, next) = if closed {
                (segs[(j + n - 1) % n], segs[j])
            } else {
                (segs[j], segs[j + 1])
            };
            is_implied(prev, next)
        })
        .count();
    joints - implied + if closed { 0 } else { 2 }
}

/// The on-curve points of an outline: those a designer placed, and the TrueType *implied*
/// ones — joints of two quadratics exactly midway between their off-curve points, by the rule
/// of [`on_curve_points`] (a font may also store such a point; the outline cannot tell).
/// Open contours list both ends with the placed ones.
pub fn on_curve_split(path: &BezPath) -> (Vec<Point>, Vec<Point>) {
    let (mut placed, mut implied) = (Vec::new(), Vec::new());
    for (segs, closed) in contours(path) {
        let n = segs.len();
        if n == 0 {
            continue;
        }
        if !closed {
            placed.push(segs[0].start());
        }
        let joints = if closed { n } else { n - 1 };
        for j in 0..joints {
            let (prev, next) = (segs[j], segs[(j + 1) % n]);
            let p = prev.end();
            if is_implied(prev, next) {
                implied.push(p);
            } else {
                placed.push(p);
            }
        }
        if !closed {
            placed.push(segs[n - 1].end());
        }
    }
    (placed, implied)
}

/// Whether the joint of two quadratics is the midpoint of their off-curve points.
fn is_implied(prev: PathSeg, next: PathSeg) -> bool {
    match (prev, next) {
        (PathSeg::Quad(a), PathSeg::Quad(b)) => {
            let mid: Point = a.p1.midpoint(b.p1);
            let scale = a.p1.to_vec2().hypot().max(b.p1.to_vec2().hypot()).max(1.0);
            (mid - a.p2).hypot() <= 1e-9 * scale
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_closing_line_shorter_than_rounding_is_dropped() {
        // A closed contour whose last curve ends 3e-14 off its start (as an outline drafted
        // piece by piece can): no closing line, and the last curve ends at the start.
        let mut p = BezPath::new();
        p.move_to((45.00000000000006, 320.0));
        p.curve_to((45.0, 100.0), (300.0, 0.0), (400.0, 0.0));
        p.curve_to((600.0, 0.0), (45.0, 500.0), (45.000000000000085, 320.0));
        p.close_path();
        let c = contours(&p);
        assert_eq!(c.len(), 1);
        let (segs, closed) = &c[0];
        assert!(*closed);
        assert_eq!(segs.len(), 2);
        assert_eq!(segs[1].end(), segs[0].start());
        // A real closing line stays.
        let mut q = BezPath::new();
        q.move_to((0.0, 0.0));
        q.curve_to((10.0, 0.0), (10.0, 10.0), (0.0, 10.0));
        q.close_path();
        let c = contours(&q);
        assert_eq!(c[0].0.len(), 2);
        assert!(matches!(c[0].0[1], PathSeg::Line(_)));
    }
}
