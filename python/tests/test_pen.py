"""Pens: contours drawn into fontTools segment and point pens round-trip through fontTools."""

import pytest

pytest.importorskip("fontTools")

from fontTools.pens.areaPen import AreaPen  # noqa: E402
from fontTools.pens.pointPen import PointToSegmentPen  # noqa: E402
from fontTools.pens.recordingPen import RecordingPen, RecordingPointPen  # noqa: E402

import kappa  # noqa: E402
from kappa.pen import KappaPen, draw_contours, replay  # noqa: E402

OUTER = [(300, -12), (540, 250), (300, 512), (60, 250)]
INNER = [(300, 76), (450, 250), (300, 424), (150, 250)]


def contours(scheme="ek-cubic"):
    return [kappa.Contour(OUTER, True, scheme, shapes=0.8 if scheme != "kappa" else None),
            kappa.Contour(INNER, True, scheme)]


def test_segment_pen_records_the_elements():
    cs = contours()
    rec = RecordingPen()
    draw_contours(cs, rec, nodes="joints")
    assert rec.value == kappa.glyph_elements(cs, "postscript", "joints")
    # Replayed into another recording: the same.
    again = RecordingPen()
    rec.replay(again)
    assert again.value == rec.value


def test_point_pen_round_trip():
    cs = contours()
    seg = RecordingPen()
    draw_contours(cs, seg, tolerance=4.0)
    points = RecordingPointPen()
    draw_contours(cs, points, tolerance=4.0)
    back = RecordingPen()
    points.replay(PointToSegmentPen(back))
    assert _normalize(back.value) == _normalize(seg.value)
    # Every on-curve point of the anchor outline is a κ point.
    on = [pt for op, args, kw in points.value if op == "addPoint" for pt in [args[0]] if args[1]]
    assert len(on) == len(OUTER) + len(INNER)


def _normalize(value):
    """Contours as sets of segments, start point aside (point pens may rotate the start)."""
    out = []
    for op, args in value:
        if op == "moveTo":
            out.append([args[0]])
        elif op in ("lineTo", "curveTo", "qCurveTo"):
            out[-1].extend(args)
    return [sorted(c) for c in out]


def test_directions_by_format():
    cs = contours()
    for direction, sign in [("postscript", 1), ("truetype", -1)]:
        rec = RecordingPen()
        draw_contours(cs, rec, direction=direction)
        areas = []
        for c in _split(rec.value):
            pen = AreaPen()
            replay(c, pen)
            areas.append(pen.value)
        assert areas[0] * sign > 0 and areas[1] * sign < 0, (direction, areas)


def _split(value):
    out = []
    for op, args in value:
        if op == "moveTo":
            out.append([])
        out[-1].append((op, args))
    return out


def test_quadratic_output():
    rec = RecordingPen()
    draw_contours(contours(), rec, quadratic=True, direction="truetype")
    ops = {op for op, _ in rec.value}
    assert "curveTo" not in ops and "qCurveTo" in ops
    # κ contours by their joints: the solver's own quadratics, unchanged.
    cs = contours("kappa")
    exact = RecordingPen()
    draw_contours(cs, exact, quadratic=True, nodes="joints", direction=None)
    assert exact.value == cs[0].elements() + cs[1].elements()


def test_kappa_pen():
    rec = RecordingPen()
    kp = KappaPen(rec, scheme="ek-cubic", shape=0.8, nodes="joints")
    kp.beginContour()
    for i, p in enumerate(OUTER):
        kp.addAnchor(p, shape=0.9 if i == 0 else None)
    solved = kp.endContour()
    kp.beginContour()
    for p in INNER:
        kp.addAnchor(p)
    kp.endContour()
    kp.draw()
    assert solved.shapes == [0.9, 0.8, 0.8, 0.8]
    assert len(kp.contours) == 2
    assert rec.value == kappa.glyph_elements(kp.contours, "postscript", "joints")
    with pytest.raises(ValueError):
        kp.addAnchor((0, 0))


def test_kappa_pen_corners_tangents_into_point_pen():
    points = RecordingPointPen()
    kp = KappaPen(points, scheme="ek-cubic", shape=0.75)
    kp.beginContour()
    kp.addAnchor((80, 0), corner=True)
    kp.addAnchor((80, 700), corner=True)
    kp.addAnchor((300, 700), corner=True, tangent=(1, 0))
    for p in [(430, 660), (540, 520)]:
        kp.addAnchor(p)
    kp.addAnchor((580, 350), tangent=(0, -1))
    for p in [(540, 180), (430, 40)]:
        kp.addAnchor(p)
    kp.addAnchor((300, 0), corner=True, tangentIn=(-1, 0))
    kp.endContour()
    kp.draw()
    ops = [op for op, _, _ in points.value]
    assert ops[0] == "beginPath" and ops[-1] == "endPath"
    kinds = [args[1] for op, args, _ in points.value if op == "addPoint"]
    assert kinds.count("line") == 3 and kinds.count("curve") == 6
