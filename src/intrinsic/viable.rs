//! Which end curvatures admit a G2 segment of monotone curvature: the "viable region" of
//! seed 003 (Fig. 4), sampled.

use core::ops::Range;

use super::{Hermite, Profile};
use crate::Error;

/// What a G2 Hermite problem gives for one pair of end curvatures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Viability {
    /// No segment of the profile meets the data ([`Error::NoHermiteSolution`]), or the
    /// solver's iteration cap ran out before one was found ([`Error::NotConverged`]).
    NoSolution,
    /// A segment meets the data, but its curvature is not monotone or changes sign.
    Solved,
    /// A segment meets the data with monotone curvature and no inflection point.
    Monotone,
}

/// A sampled viable region: [`Viability`] on a grid of start curvatures `κ_s` (columns) and
/// end curvatures `κ_e` (rows).
#[derive(Clone, Debug, PartialEq)]
pub struct ViableRegion {
    /// The sampled start curvatures, increasing.
    pub k_start: Vec<f64>,
    /// The sampled end curvatures, increasing.
    pub k_end: Vec<f64>,
    /// Row-major: `cells[j * k_start.len() + i]` is the result for `(k_start[i], k_end[j])`.
    pub cells: Vec<Viability>,
}

impl ViableRegion {
    /// The result for `(k_start[i], k_end[j])`.
    pub fn at(&self, i: usize, j: usize) -> Viability {
        self.cells[j * self.k_start.len() + i]
    }

    /// How many samples have this result.
    pub fn count(&self, v: Viability) -> usize {
        self.cells.iter().filter(|&&c| c == v).count()
    }
}

/// Samples, for the G1 data `g1` (its curvatures are ignored), which end curvatures
/// `(κ_s, κ_e)` in `k_start × k_end` (`samples × samples` points, ends included) admit a G2
/// segment of degree `degree` with the profile of seed 003 Fig. 4 — unknowns `κ_1`,
/// `κ_{n−1}`, linear interpolation between ([`Profile::free`]) — and whether its curvature
/// is monotone without inflection.
///
/// # Errors
///
/// [`Error::InvalidOption`] for fewer than 2 samples, an empty or non-finite range or a
/// degree below 3, and the data errors of [`Hermite::solve`] (coincident or non-finite
/// points).
pub fn viable_region(
    g1: &Hermite,
    degree: usize,
    k_start: Range<f64>,
    k_end: Range<f64>,
    samples: usize,
) -> Result<ViableRegion, Error> {
    if samples < 2 {
        return Err(Error::InvalidOption(
            "a viable region needs at least 2 samples",
        ));
    }
    if degree < 3 {
        return Err(Error::InvalidOption("G2 segments need degree 3 or more"));
    }
    let grid = |r: &Range<f64>| -> Result<Vec<f64>, Error> {
        if !(r.start.is_finite() && r.end.is_finite() && r.start < r.end) {
            return Err(Error::InvalidOption(
                "curvature ranges must be finite and not empty",
            ));
        }
        Ok((0..samples)
            .map(|i| r.start + (r.end - r.start) * i as f64 / (samples - 1) as f64)
            .collect())
    };
    let (ks, ke) = (grid(&k_start)?, grid(&k_end)?);
    let profile = Profile::free(degree);
    let mut cells = Vec::with_capacity(samples * samples);
    for &k1 in &ke {
        for &k0 in &ks {
            let mut h = *g1;
            h.start.curvature = Some(k0);
            h.end.curvature = Some(k1);
            cells.push(match h.solve(&profile) {
                Ok(seg) if seg.is_monotone() && seg.inflections().is_empty() => Viability::Monotone,
                Ok(_) => Viability::Solved,
                Err(Error::NoHermiteSolution { .. } | Error::NotConverged { .. }) => {
                    Viability::NoSolution
                }
                Err(e) => return Err(e),
            });
        }
    }
    Ok(ViableRegion {
        k_start: ks,
        k_end: ke,
        cells,
    })
}
