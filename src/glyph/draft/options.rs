//! The options of a draft: the scheme, the shape parameters and the tolerances.

use crate::{Error, Scheme};

/// How the εκ shape parameters of a draft are chosen.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum DraftShape {
    /// The scheme's neutral shape ([`Scheme::neutral_shape`]).
    #[default]
    Neutral,
    /// One `a` for every anchor.
    Global(f64),
    /// Per anchor, matching the original's curvature peak (see [`draft`](super::draft),
    /// step 6).
    Auto,
}

/// Options of [`draft`](super::draft). Lengths are in the outline's units (font units).
#[derive(Clone, Debug, PartialEq)]
pub struct DraftOptions {
    /// The curve scheme.
    pub scheme: Scheme,
    /// The εκ shape parameters (ignored for [`Scheme::Kappa`]).
    pub shape: DraftShape,
    /// Refine a piece until its deviation from the original is at most this.
    pub tolerance: f64,
    /// Anchors closer than this to an anchor already taken are dropped (corners excepted).
    pub min_spacing: f64,
    /// A joint turning by more than this angle (radians) is a corner.
    pub corner_angle: f64,
    /// Samples per segment for the deviation and Hausdorff measurements (clamped to 2..=256).
    pub samples: usize,
    /// At most this many anchors are added per piece by the refinement.
    pub max_refinements: usize,
    /// Mend the anchors where the draft turns the other way than the original
    /// ([`draft`](super::draft), step 4): no spurious inflections, two to three times the
    /// drafting time.
    pub fair: bool,
    /// Drop the anchors the piece does not need to stay within the tolerance
    /// ([`draft`](super::draft), step 5): fewer points, about four times the drafting time.
    pub simplify: bool,
    /// Hold the original's axis as the tangent at every extremum anchor inside a piece
    /// ([`Solver::solve_with_tangents`](crate::Solver::solve_with_tangents)): once the
    /// anchors are chosen, the piece is solved again with those tangents and kept if it
    /// stays within the tolerance. The curve is then G2 at the anchor with an exactly
    /// horizontal or vertical tangent, where the node outline would otherwise turn the
    /// handles after the solve (G1 only); the anchor is no longer a curvature peak. Off by
    /// default (`kappa font` turns it on).
    pub extremum_tangents: bool,
}

impl DraftOptions {
    /// κ-curve options scaled to a font's em: tolerance `0.004 em` (8 units at 2048),
    /// minimum spacing `0.06 em`, corners above 15°, 16 samples per segment, at most 32
    /// refinements per piece, no fairing, no simplification, no extremum tangents.
    pub fn for_units_per_em(units_per_em: f64) -> DraftOptions {
        DraftOptions {
            scheme: Scheme::Kappa,
            shape: DraftShape::Neutral,
            tolerance: 0.004 * units_per_em,
            min_spacing: 0.06 * units_per_em,
            corner_angle: 15f64.to_radians(),
            samples: 16,
            max_refinements: 32,
            fair: false,
            simplify: false,
            extremum_tangents: false,
        }
    }

    /// The same options with another scheme and shape.
    pub fn with_scheme(mut self, scheme: Scheme, shape: DraftShape) -> DraftOptions {
        self.scheme = scheme;
        self.shape = shape;
        self
    }

    pub(super) fn validate(&self) -> Result<(), Error> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(Error::InvalidOption(
                "draft tolerance must be finite and positive",
            ));
        }
        if !(self.min_spacing.is_finite() && self.min_spacing >= 0.0) {
            return Err(Error::InvalidOption(
                "draft minimum spacing must be finite and non-negative",
            ));
        }
        if !(self.corner_angle.is_finite() && self.corner_angle > 0.0) {
            return Err(Error::InvalidOption(
                "corner angle must be finite and positive",
            ));
        }
        if let DraftShape::Global(a) = self.shape {
            let (min, max) = self.scheme.shape_range();
            if self.scheme != Scheme::Kappa && !(a >= min && a < max) {
                return Err(Error::ShapeOutOfRange {
                    index: 0,
                    value: a,
                    min,
                    max,
                });
            }
        }
        Ok(())
    }
}

impl Default for DraftOptions {
    /// The options for a 1000-unit em: see [`DraftOptions::for_units_per_em`].
    fn default() -> DraftOptions {
        DraftOptions::for_units_per_em(1000.0)
    }
}
