//! The auto shape: per-anchor εκ shape parameters that match the original's curvature
//! peaks ([`draft`](super::draft), step 6).

use kurbo::Point;

use super::Drafter;
use crate::{Error, Scheme, Shape, SolvedState, Spline};

/// Secant steps of the auto shape after its two start-up solves.
pub const AUTO_SECANT_STEPS: usize = 4;

/// The auto shape stops when every drafted peak is within this relative error of its target.
pub const AUTO_RELATIVE_TOLERANCE: f64 = 0.02;

/// The largest shape parameter the auto shape uses (the peak grows without bound as `a → 1`).
pub const AUTO_MAX_SHAPE: f64 = 0.98;

/// The smallest εκ-trig shape parameter the auto shape uses.
pub const AUTO_MIN_TRIG_SHAPE: f64 = 0.62;

impl Drafter<'_> {
    /// The auto shape ([`draft`](super::draft), step 6).
    pub(super) fn auto_shape(
        &mut self,
        points: &[Point],
        closed: bool,
        targets: &[f64],
    ) -> Result<(Spline, Option<SolvedState>), Error> {
        let scheme = self.options.scheme;
        let lo = match scheme {
            Scheme::EkTrig => AUTO_MIN_TRIG_SHAPE,
            _ => 2.0 / 3.0,
        };
        let m = points.len();
        let off = usize::from(!closed);
        // Peak |κ| of each point (None for the ends of an open curve).
        let peaks = |spline: &Spline| -> Vec<Option<f64>> {
            (0..m)
                .map(|i| {
                    i.checked_sub(off)
                        .and_then(|j| spline.segments().get(j))
                        .filter(|_| closed || (i > 0 && i + 1 < m))
                        .map(|s| s.curvature(s.t_max).abs())
                })
                .collect()
        };
        // The lowest shape first; should that system not be solvable (εκ-trig near its
        // peak/minimum fold), the scheme's neutral shape.
        let mut a0 = vec![lo; m];
        let s0 = match self.solve_points(points, closed, &Shape::PerPoint(a0.clone())) {
            Ok(s) => s,
            Err(e) => {
                let neutral = scheme.neutral_shape();
                if neutral == lo {
                    return Err(e);
                }
                a0 = vec![neutral; m];
                self.solve_points(points, closed, &Shape::PerPoint(a0.clone()))?
            }
        };
        let st0 = self.solver.state();
        let mut k0 = peaks(&s0);
        let mut a1: Vec<f64> = (0..m)
            .map(|i| match k0[i] {
                Some(k) if k < targets[i] => (a0[i] + 0.1).min(AUTO_MAX_SHAPE),
                _ => a0[i],
            })
            .collect();
        if a1 == a0 {
            return Ok((s0, st0));
        }
        let mut s1 = match self
            .solver
            .resolve_shapes(scheme, &Shape::PerPoint(a1.clone()))
        {
            Ok(s) => s,
            Err(_) => return Ok((s0, st0)),
        };
        let mut st1 = self.solver.state();
        for _ in 0..AUTO_SECANT_STEPS {
            let k1 = peaks(&s1);
            let mut a2 = a1.clone();
            let mut done = true;
            for i in 0..m {
                let (Some(ka), Some(kb)) = (k0[i], k1[i]) else {
                    continue;
                };
                let target = targets[i];
                if !(target > 0.0 && ka > 0.0 && kb > 0.0) {
                    continue;
                }
                let err = target.ln() - kb.ln();
                if err.abs() <= AUTO_RELATIVE_TOLERANCE
                    || (a1[i] <= lo && err < 0.0)
                    || (a1[i] >= AUTO_MAX_SHAPE && err > 0.0)
                {
                    continue;
                }
                let da = a1[i] - a0[i];
                let dk = kb.ln() - ka.ln();
                let step = if da != 0.0 && dk > 0.0 {
                    err * da / dk
                } else {
                    0.05 * err.signum()
                };
                a2[i] = (a1[i] + step.clamp(-0.15, 0.15)).clamp(lo, AUTO_MAX_SHAPE);
                if a2[i] != a1[i] {
                    done = false;
                }
            }
            if done {
                break;
            }
            match self
                .solver
                .resolve_shapes(scheme, &Shape::PerPoint(a2.clone()))
            {
                Ok(s2) => {
                    a0 = core::mem::replace(&mut a1, a2);
                    s1 = s2;
                    st1 = self.solver.state();
                    k0 = k1;
                }
                Err(_) => break,
            }
        }
        Ok((s1, st1))
    }
}
