//! Curvature analysis.
