"""Curves whose curvature is under control: κ-curves, εκ-curves, B-splines, intrinsic
Hermite segments, and glyph contours with corners and tangents.

The solving is the Rust library's (the compiled module ``kappa._kappa``); results are the
same, bit for bit. ``kappa.pen`` draws contours into fontTools pens, ``kappa.ufo2ft`` is a
ufo2ft filter that builds fonts from κ sources kept in UFO glyph libs.
"""

from ._kappa import (
    KAPPA_LIB_KEY,
    BSpline,
    CollinearError,
    Contour,
    Curve,
    DraftedGlyph,
    ExtentOverflowError,
    FontError,
    GammaOutOfRangeError,
    IntrinsicSegment,
    InvalidInputError,
    InvalidOptionError,
    InvalidSvgError,
    InvalidTangentError,
    KappaError,
    MissingGlyphError,
    NoHermiteSolutionError,
    NonFiniteCurveError,
    NonFinitePointError,
    NotConvergedError,
    RepeatedPointError,
    Segment,
    ShapeCountError,
    ShapeOutOfRangeError,
    TangentConflictError,
    TessellationError,
    TooFewPointsError,
    builtin_design,
    builtin_designs,
    contours_from_json,
    contours_from_svg,
    draft_elements,
    glyph_elements,
    hermite,
    solve,
)

__all__ = [
    "KAPPA_LIB_KEY",
    "BSpline",
    "CollinearError",
    "Contour",
    "Curve",
    "DraftedGlyph",
    "ExtentOverflowError",
    "FontError",
    "GammaOutOfRangeError",
    "IntrinsicSegment",
    "InvalidInputError",
    "InvalidOptionError",
    "InvalidSvgError",
    "InvalidTangentError",
    "KappaError",
    "MissingGlyphError",
    "NoHermiteSolutionError",
    "NonFiniteCurveError",
    "NonFinitePointError",
    "NotConvergedError",
    "RepeatedPointError",
    "Segment",
    "ShapeCountError",
    "ShapeOutOfRangeError",
    "TangentConflictError",
    "TessellationError",
    "TooFewPointsError",
    "builtin_design",
    "builtin_designs",
    "contours_from_json",
    "contours_from_svg",
    "draft_elements",
    "draft_glyph",
    "glyph_elements",
    "hermite",
    "solve",
]

from .pen import draft_glyph  # noqa: E402  (fontTools is imported when it is called)

__version__ = "0.1.0"
