"""The Python API: inputs (pairs, lists, arrays), results, contours, B-splines, Hermite."""

import json
import math

import pytest

import kappa

POINTS = [(0.0, 0.0), (100.0, 10.0), (120.0, 90.0), (20.0, 110.0)]


class ArrayLike:
    """Stands for a NumPy array: only `tolist()`."""

    def __init__(self, rows):
        self.rows = rows

    def tolist(self):
        return [list(r) for r in self.rows]


def test_inputs_pairs_lists_arrays_give_one_curve():
    a = kappa.solve(POINTS, True, "ek-cubic", 0.8)
    b = kappa.solve([list(p) for p in POINTS], True, "ek-cubic", 0.8)
    c = kappa.solve(ArrayLike(POINTS), True, "ek-cubic", [0.8] * 4)
    d = kappa.solve(iter(POINTS), True, "ek_cubic", 0.8)
    assert a.to_svg() == b.to_svg() == c.to_svg() == d.to_svg()


def test_numpy_arrays():
    np = pytest.importorskip("numpy")
    pts = np.array(POINTS)
    a = kappa.solve(pts, True, "kappa")
    assert a.to_svg() == kappa.solve(POINTS, True).to_svg()
    # NaN rows are free points; the held direction is near the free curve's (a four-point
    # loop meets tangents only within about 15° of its own, docs/curves.md).
    tangents = np.array([[math.nan, math.nan], [1.0, 1.0], [math.nan, math.nan], [math.nan, math.nan]])
    t = kappa.solve(pts, True, "kappa", None, tangents)
    assert t.converged
    assert t.to_svg() == kappa.solve(POINTS, True, "kappa", None, [None, (1.0, 1.0), None, None]).to_svg()
    x, y = t.segments[1].derivative(t.segments[1].t_max)
    assert abs(math.atan2(y, x) - math.pi / 4) < 1e-9


def test_curve_result():
    curve = kappa.solve(POINTS, True, "ek-cubic", 0.8)
    assert curve.converged and curve.iterations > 0 and curve.residual < 1e-12
    assert curve.scheme == "ek-cubic" and curve.closed and len(curve) == 4
    for seg, p in zip(curve.segments, POINTS):
        x, y = seg.eval(seg.t_max)
        assert math.hypot(x - p[0], y - p[1]) < 1e-9
        assert len(seg.control_points) == 4 and seg.degree == 3 and seg.a == 0.8
        assert seg.extremum == "max"
    cubics = curve.cubics()
    assert len(cubics) == 4 and all(len(c) == 4 for c in cubics)
    assert [c[0] for c in cubics] == [tuple(s.control_points[0]) for s in curve.segments]
    ops = [op for op, _ in curve.elements()]
    assert ops == ["moveTo"] + ["curveTo"] * 4 + ["closePath"]
    samples = curve.curvature_samples(8)
    assert len(samples) == 32
    kmax = max(math.hypot(*k) for _, k in samples)
    assert kmax <= curve.max_abs_curvature() * (1 + 1e-12)
    assert len(curve.curvatures(8)) == 32
    fitted, distance = curve.fit()
    assert distance == 0.0 and fitted == curve.elements()


def test_kappa_curve_is_quadratic_and_open_curves_end():
    curve = kappa.solve(POINTS, False)
    ops = [op for op, _ in curve.elements()]
    assert ops == ["moveTo", "qCurveTo", "qCurveTo", "endPath"]
    assert all(len(s) == 3 for s in curve.bezier_segments())
    # Raised quadratics trace the same curve.
    (p0, q1, p2), (c0, c1, c2, c3) = curve.bezier_segments()[0], curve.cubics()[0]
    assert c1 == pytest.approx((p0[0] + 2 / 3 * (q1[0] - p0[0]), p0[1] + 2 / 3 * (q1[1] - p0[1])))


def test_trig_curve_fitted():
    curve = kappa.solve(POINTS, True, "ek-trig", 0.75)
    assert len(curve.segments[0].control_points) == 5
    elements, distance = curve.fit(1e-6)
    assert distance <= 1e-6 * 130
    assert elements[0][0] == "moveTo" and elements[-1][0] == "closePath"


def test_tangents_held():
    free = kappa.solve(POINTS, True, "ek-cubic", 0.8).segments[1]
    dx, dy = free.derivative(free.t_max)
    turn = math.radians(3)
    want = (dx * math.cos(turn) - dy * math.sin(turn), dx * math.sin(turn) + dy * math.cos(turn))
    curve = kappa.solve(POINTS, True, "ek-cubic", 0.8, [None, want, None, None])
    assert curve.converged
    seg = curve.segments[1]
    # The curve passes through point 1 along the prescribed direction.
    hit = [t for s in curve.segments for t in [0.0, s.t_max, 1.0] if math.dist(s.eval(t), POINTS[1]) < 1e-9]
    assert hit
    d = [s for s in curve.segments if math.dist(s.eval(s.t_max), POINTS[1]) < 1e-9]
    gx, gy = d[0].derivative(d[0].t_max) if d else seg.derivative(0.0)
    assert abs(gx * want[1] - gy * want[0]) < 1e-9 * math.hypot(gx, gy) * math.hypot(*want)


def test_contour_corners_tangents_json_round_trip():
    pts = [(0, 0), (0, 300), (150, 300), (260, 240), (300, 150), (260, 60), (150, 0)]
    c = kappa.Contour(
        pts, True, "ek-cubic", shapes=0.8,
        corners=[True, True, True, False, False, False, True],
        tangents=[None, None, (1, 0), None, (0, -1), None, None],
        tangents_in=[None, None, None, None, None, None, (-1, 0)],
    )
    assert not c.errors
    c.check()
    assert [c.piece_points(k) for k in range(len(c.pieces))] == [[0, 1], [1, 2], [2, 3, 4, 5, 6], [6, 0]]
    assert c.corners == [True, True, True, False, False, False, True]
    assert c.tangents[4] == (0.0, -1.0)
    again = kappa.Contour.from_json(c.to_json())
    assert again.to_svg() == c.to_svg()
    doc = json.loads(c.to_json())
    assert doc["points"][2]["tangent"] == [1.0, 0.0] and "solution" not in doc
    assert "solution" in json.loads(c.to_json(solution=True))
    both = kappa.contours_from_json(json.dumps([doc, doc]))
    assert len(both) == 2
    # The joint outline is the pieces' exact curves; the anchor outline has the points as
    # its on-curve nodes.
    anchors = c.elements(nodes="anchors")
    on_curve = [args[-1] for op, args in anchors if op in ("moveTo", "lineTo", "curveTo")]
    for p in pts:
        assert any(math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9 for q in on_curve)
    # Tangent at the held extremum: vertical handles on both sides of (300, 150).
    for op, args in anchors:
        if op == "curveTo" and args[-1] == (300.0, 150.0):
            assert args[1][0] == pytest.approx(300.0, abs=1e-9)


def test_glyph_direction():
    from_area = lambda els: _area(els)  # noqa: E731
    outer = kappa.Contour([(0, 0), (0, 100), (100, 100), (100, 0)], True)  # clockwise
    inner = kappa.Contour([(30, 30), (70, 30), (70, 70), (30, 70)], True)  # counter-clockwise
    ps = kappa.glyph_elements([outer, inner], "postscript")
    tt = kappa.glyph_elements([outer, inner], "truetype")
    areas_ps = [from_area(c) for c in _split(ps)]
    areas_tt = [from_area(c) for c in _split(tt)]
    assert areas_ps[0] > 0 and areas_ps[1] < 0
    assert areas_tt[0] < 0 and areas_tt[1] > 0


def _split(elements):
    out = []
    for op, args in elements:
        if op == "moveTo":
            out.append([])
        out[-1].append((op, args))
    return out


def _area(elements):
    """Shoelace area of the polygon of a contour's sampled points (y up: CCW positive)."""
    pts = []
    cur = None
    for op, args in elements:
        if op == "moveTo":
            cur = args[0]
            pts.append(cur)
        elif op in ("lineTo", "qCurveTo", "curveTo"):
            ctrl = [cur, *args]
            for i in range(1, 9):
                pts.append(_bez(ctrl, i / 8))
            cur = args[-1]
    return 0.5 * sum(pts[i - 1][0] * pts[i][1] - pts[i][0] * pts[i - 1][1] for i in range(len(pts)))


def _bez(ctrl, t):
    while len(ctrl) > 1:
        ctrl = [((1 - t) * a[0] + t * b[0], (1 - t) * a[1] + t * b[1]) for a, b in zip(ctrl, ctrl[1:])]
    return ctrl[0]


def test_bspline():
    pts = [(2.0, 1.5), (0.75, 3.0), (2.5, 4.0), (3.5, 3.0), (5.0, 1.5), (5.5, 3.5), (4.0, 4.0)]
    s = kappa.BSpline(pts, True)
    value, params = s.max_curvature()
    assert params == [4.0] and value > 0
    assert s.eval(4.0) == pytest.approx(pts[4])
    assert len(s.cubics()) == 7 and len(s) == 7
    assert len(s.control_points) == 7 and s.closed
    assert abs(kappa.BSpline(pts, False).curvature(0.0)) < 1e-12


def test_hermite():
    clothoid = kappa.hermite((0, 0), 0.3, (10, 4), 1.6)
    assert clothoid.degree == 1 and clothoid.length > 10
    assert clothoid.eval(1.0) == pytest.approx((10, 4), abs=1e-9)
    assert clothoid.angle_at(0.0) == pytest.approx(0.3)
    flat = kappa.hermite((0, 0), 0.3, (10, 4), 1.6, controls=[None, {"same_as": 0}, {"same_as": 3}, None])
    assert flat.degree == 3
    g2 = kappa.hermite((0, 0), 0.3, (10, 4), 1.6, -0.1, 0.3)
    assert g2.degree == 5
    assert g2.curvature_at(0.0) == pytest.approx(-0.1, abs=1e-9)
    cubics, distance = g2.cubics(1e-6)
    assert cubics and distance <= 1e-6 * 12
    seg = kappa.IntrinsicSegment((0, 0), 0.0, 5.0, [0.0, 0.2, 1.0])
    assert seg.curvatures == [0.0, 0.2, 1.0] and seg.is_monotone()


def test_builtin_designs():
    names = kappa.builtin_designs()
    assert "bear" in names
    bear = json.loads(kappa.builtin_design("bear"))
    assert bear["curves"]
    assert kappa.builtin_design("unicorn") is None
