"""One exception class per library error kind, subclasses of KappaError, with the
library's messages and the variant's fields as attributes."""

import math

import pytest

import kappa

SQUARE = [(0, 0), (100, 0), (100, 100), (0, 100)]

KINDS = [
    "TooFewPointsError", "NonFinitePointError", "RepeatedPointError", "ExtentOverflowError",
    "CollinearError", "ShapeOutOfRangeError", "ShapeCountError", "InvalidTangentError",
    "TangentConflictError", "GammaOutOfRangeError", "InvalidOptionError",
    "NonFiniteCurveError", "InvalidInputError", "InvalidSvgError", "NoHermiteSolutionError",
    "FontError", "MissingGlyphError", "TessellationError", "NotConvergedError",
]


def test_every_kind_is_a_kappa_error():
    for name in KINDS:
        cls = getattr(kappa, name)
        assert issubclass(cls, kappa.KappaError), name
        assert cls.__doc__
    assert issubclass(kappa.KappaError, Exception)


def test_too_few_points():
    with pytest.raises(kappa.TooFewPointsError) as e:
        kappa.solve([(0, 0), (1, 1)], True)
    assert str(e.value) == "too few points: a closed curve needs at least 3, got 2"
    assert (e.value.needed, e.value.got) == (3, 2)


def test_non_finite_point():
    with pytest.raises(kappa.NonFinitePointError) as e:
        kappa.solve([(0, 0), (math.nan, 1), (2, 0)], False)
    assert str(e.value) == "point 1 has a coordinate that is NaN or infinite"
    assert e.value.index == 1


def test_repeated_point():
    with pytest.raises(kappa.RepeatedPointError) as e:
        kappa.solve([(0, 0), (5, 5), (5, 5), (0, 9)], True)
    assert str(e.value) == "points 1 and 2 coincide"
    assert (e.value.index, e.value.next) == (1, 2)


def test_extent_overflow():
    with pytest.raises(kappa.ExtentOverflowError) as e:
        kappa.solve([(-1.7e308, 0), (1.7e308, 0), (0, 1e308)], True)
    assert str(e.value) == "the points span more than the largest finite number"


def test_collinear():
    with pytest.raises(kappa.CollinearError) as e:
        kappa.solve([(0, 0), (1, 0), (2, 0)], True)
    assert "collinear" in str(e.value)


def test_shape_out_of_range():
    with pytest.raises(kappa.ShapeOutOfRangeError) as e:
        kappa.solve(SQUARE, True, "ek-cubic", 1.5)
    assert e.value.value == 1.5 and e.value.max == 1.0
    assert str(e.value).startswith("shape parameter 0 is 1.5, outside [0.6666")


def test_shape_count():
    with pytest.raises(kappa.ShapeCountError) as e:
        kappa.solve(SQUARE, True, "ek-cubic", [0.8, 0.8])
    assert str(e.value) == "expected 4 shape parameters (one per point), got 2"


def test_invalid_tangent():
    with pytest.raises(kappa.InvalidTangentError) as e:
        kappa.solve(SQUARE, True, "kappa", None, [None, (0, 0), None, None])
    assert e.value.index == 1
    with pytest.raises(kappa.InvalidTangentError):
        kappa.solve(SQUARE, True, "kappa", None, [None])


def test_tangent_conflict():
    with pytest.raises(kappa.TangentConflictError) as e:
        kappa.solve([(0, 0), (10, 5), (20, 0)], False, "kappa", None, [(1, 0), None, (1, -1)])
    assert (e.value.first, e.value.second) == (0, 2)


def test_invalid_option():
    with pytest.raises(kappa.InvalidOptionError) as e:
        kappa.solve(SQUARE, True, tolerance=-1.0)
    assert str(e.value).startswith("invalid option: ")


def test_invalid_input():
    with pytest.raises(kappa.InvalidInputError):
        kappa.contours_from_json("[{\"points\": 3}]")
    with pytest.raises(kappa.InvalidInputError):
        kappa.Contour.from_json("not json")


def test_invalid_svg():
    with pytest.raises(kappa.InvalidSvgError) as e:
        kappa.contours_from_svg("<svg><path d='M0 0 L1 1'/>")
    assert str(e.value).startswith("invalid SVG: ")


def test_invalid_option_of_a_draft():
    with pytest.raises(kappa.InvalidOptionError):
        kappa.draft_elements([("moveTo", ((0, 0),)), ("lineTo", ((9, 0),)), ("closePath", ())], 0.0)
    with pytest.raises(kappa.InvalidOptionError):
        kappa.draft_elements([("moveTo", ((0, 0),))], 1000.0, tolerance=-1.0)


#: The kinds no Python call reaches (κ-space curves, the fitting adapter, font files and
#: tessellation are not exposed), raised from sample fields through the same mapping.
UNREACHABLE = {
    "GammaOutOfRangeError": ("gamma of joint 2 is 0.9, outside (0.25, 0.75)",
                             {"joint": 2, "value": 0.9, "min": 0.25, "max": 0.75}),
    "NonFiniteCurveError": ("segment 3 of the curve to fit is not finite", {"segment": 3}),
    "FontError": ("font: cannot read the font: bad magic", {}),
    "MissingGlyphError": ("the font has no glyph for 'ß'", {"char": "ß"}),
    "TessellationError": ("tessellation failed: too many vertices", {}),
}


@pytest.mark.parametrize("kind", sorted(UNREACHABLE))
def test_kinds_python_cannot_reach(kind):
    from kappa import _kappa

    message, attrs = UNREACHABLE[kind]
    with pytest.raises(getattr(kappa, kind)) as e:
        _kappa._raise_error_kind(kind)
    assert str(e.value) == message
    for name, value in attrs.items():
        assert getattr(e.value, name) == value
    assert isinstance(e.value, kappa.KappaError)


def test_every_kind_is_tested():
    # Each kind either has a call that raises it in this file or a sample above.
    import inspect
    import sys

    text = inspect.getsource(sys.modules[__name__])
    for name in KINDS:
        assert name in UNREACHABLE or text.count(f"kappa.{name}") >= 1, name


def test_no_hermite_solution():
    # A straight chord with both tangents turned 90° the same way and a clothoid profile
    # given a curvature it cannot have.
    with pytest.raises(kappa.KappaError) as e:
        kappa.hermite((0, 0), 0.0, (10, 0), 0.0, controls=[5.0, None])
    assert isinstance(e.value, (kappa.InvalidOptionError, kappa.NoHermiteSolutionError))
    with pytest.raises(kappa.NoHermiteSolutionError):
        kappa.hermite((0, 0), 3.0, (10, 0), -3.0, 0.0, 0.0, degree=3, turning="as-given")


def test_not_converged_and_best_curve():
    star = [(math.cos(k * 2.4) * (100 + 60 * (k % 2)), math.sin(k * 2.4) * (100 + 60 * (k % 2))) for k in range(9)]
    with pytest.raises(kappa.NotConvergedError) as e:
        kappa.solve(star, True, "ek-cubic", 0.9, max_iterations=1)
    assert e.value.iterations >= 1 and e.value.residual > 0
    assert str(e.value).startswith("did not converge in ")
    best = kappa.solve(star, True, "ek-cubic", 0.9, max_iterations=1, accept_unconverged=True)
    assert not best.converged and best.residual > 0 and len(best.segments) == 9


def test_python_argument_errors_are_python_errors():
    with pytest.raises(ValueError):
        kappa.solve(SQUARE, True, "bezier")
    with pytest.raises(ValueError):
        kappa.solve([(0, 0, 0), (1, 1, 1), (2, 0, 0)], True)
    with pytest.raises(TypeError):
        kappa.solve(3, True)
    with pytest.raises(ValueError):
        kappa.Contour(SQUARE, True, corners=[True])


def test_contour_errors_are_listed_and_raised():
    # Two points in one place: the piece holding them has no curve.
    c = kappa.Contour([(0, 0), (50, 0), (50, 0), (0, 50)], True, corners=[True, False, False, True])
    assert c.errors and isinstance(c.errors[0][1], kappa.RepeatedPointError)
    with pytest.raises(kappa.RepeatedPointError):
        c.check()
    with pytest.raises(kappa.RepeatedPointError):
        kappa.glyph_elements([c])
