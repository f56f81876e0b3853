"""Drawing κ contours into fontTools pens.

``draft_glyph`` drafts κ contours from a fontTools glyph. ``draw_contours`` draws solved contours (``kappa.Contour``) as one glyph into any fontTools
segment pen (``moveTo``/``curveTo``/...) or point pen (``beginPath``/``addPoint``/...),
with the contour direction a font format wants and, for TrueType, quadratic curves (κ
quadratics exactly; cubics through fontTools' cu2qu). ``KappaPen`` collects contours anchor
by anchor and draws them the same way.

fontTools is needed only for point pens and quadratic output.
"""

from __future__ import annotations

from typing import Any, Iterable, Optional, Sequence, Tuple

from ._kappa import Contour, DraftedGlyph, draft_elements, glyph_elements

Point = Tuple[float, float]

__all__ = ["KappaPen", "draft_glyph", "draw_contours", "replay"]


def _is_point_pen(pen: Any) -> bool:
    return hasattr(pen, "addPoint") and hasattr(pen, "beginPath")


def replay(elements: Iterable[Tuple[str, Sequence[Point]]], pen: Any) -> None:
    """Draws path elements in fontTools' RecordingPen form (what ``Curve.elements()``,
    ``Contour.elements()`` and ``glyph_elements()`` return) into a segment pen."""
    for op, args in elements:
        getattr(pen, op)(*args)


def _target(pen: Any, quadratic: bool, max_err: float) -> Any:
    """A segment pen drawing into ``pen`` (a segment or point pen), through cu2qu when
    ``quadratic``."""
    if _is_point_pen(pen):
        from fontTools.pens.pointPen import SegmentToPointPen

        pen = SegmentToPointPen(pen)
    if quadratic:
        from fontTools.pens.cu2quPen import Cu2QuPen

        pen = Cu2QuPen(pen, max_err, reverse_direction=False)
    return pen


def draw_contours(
    contours: Iterable[Contour],
    pen: Any,
    *,
    direction: Optional[str] = "postscript",
    nodes: str = "anchors",
    quadratic: bool = False,
    max_err: float = 1.0,
    accuracy: Optional[float] = None,
    tolerance: Optional[float] = None,
    accept_unconverged: bool = False,
) -> None:
    """Draws ``contours`` as one glyph into ``pen`` (a fontTools segment pen or point pen).

    - ``direction``: "postscript" (outer contours counter-clockwise, y up: CFF, UFO),
      "truetype" (outer clockwise) or None (as drawn). Decided per contour by nesting.
    - ``nodes``: "anchors" (the contours' points are the on-curve points; every span
      between two of them is one cubic where that is within ``tolerance / 2``, default
      ``tolerance`` 4e-3 of the contour's size, else cubics within ``accuracy``, default
      1e-4 of the size), "joints" (the exact curve: κ quadratics, εκ-cubic cubics,
      fitted εκ-trig) or "compatible" (nodes at the points and the joints, in a structure
      fixed by the points, corners and closed flag: masters of the same structure
      interpolate; see docs/python.md).
    - ``quadratic``: quadratic curves for TrueType: cubics converted by fontTools' cu2qu
      within ``max_err`` font units; with ``nodes="joints"`` a κ contour is drawn with its
      own quadratics, exactly.
    - ``accept_unconverged``: draw the best curve of a piece that did not converge instead
      of raising NotConvergedError.
    """
    elements = glyph_elements(
        list(contours),
        direction=direction,
        nodes=nodes,
        accuracy=accuracy,
        tolerance=tolerance,
        accept_unconverged=accept_unconverged,
    )
    replay(elements, _target(pen, quadratic, max_err))


class KappaPen:
    """Collects κ contours anchor by anchor and draws them into another pen.

    ::

        kp = KappaPen(glyph.getPen(), scheme="ek-cubic", shape=0.8)
        kp.beginContour()
        kp.addAnchor((100, 0), tangent=(1, 0))
        kp.addAnchor((300, 200), corner=True)
        kp.addAnchor((100, 400))
        kp.endContour()
        kp.draw()                # all contours, as one glyph, into glyph.getPen()

    ``outPen`` may be a segment pen or a point pen; the keyword options are those of
    ``draw_contours``.
    """

    def __init__(
        self,
        outPen: Any,
        scheme: str = "kappa",
        shape: Optional[float] = None,
        *,
        direction: Optional[str] = "postscript",
        nodes: str = "anchors",
        quadratic: bool = False,
        max_err: float = 1.0,
        accuracy: Optional[float] = None,
        tolerance: Optional[float] = None,
        accept_unconverged: bool = False,
    ) -> None:
        self.outPen = outPen
        self.scheme = scheme
        self.shape = shape
        self.options = dict(
            direction=direction,
            nodes=nodes,
            quadratic=quadratic,
            max_err=max_err,
            accuracy=accuracy,
            tolerance=tolerance,
            accept_unconverged=accept_unconverged,
        )
        self.contours: list = []
        self._current: Optional[list] = None
        self._closed = True

    def beginContour(self, closed: bool = True) -> None:
        """Starts a contour (closed unless told otherwise)."""
        if self._current is not None:
            raise ValueError("beginContour: the previous contour was not ended")
        self._current = []
        self._closed = closed

    def addAnchor(
        self,
        pt: Point,
        shape: Optional[float] = None,
        corner: bool = False,
        tangent: Optional[Point] = None,
        tangentIn: Optional[Point] = None,
    ) -> None:
        """Adds a point the curve passes through: its shape (default the pen's), whether it
        is a corner, and optional tangent directions (leaving; arriving, at a corner)."""
        if self._current is None:
            raise ValueError("addAnchor: no contour was begun")
        self._current.append((tuple(pt), shape, corner, tangent, tangentIn))

    def endContour(self) -> Contour:
        """Ends the contour and solves it; returns the solved ``Contour``."""
        if self._current is None:
            raise ValueError("endContour: no contour was begun")
        anchors, self._current = self._current, None
        shapes = [self.shape if a[1] is None else a[1] for a in anchors]
        if all(s is None for s in shapes):
            shapes = None
        else:
            neutral = 0.7 if self.scheme.replace("_", "-") == "ek-trig" else 2.0 / 3.0
            shapes = [neutral if s is None else s for s in shapes]
        contour = Contour(
            [a[0] for a in anchors],
            self._closed,
            self.scheme,
            shapes=shapes,
            corners=[a[2] for a in anchors],
            tangents=[a[3] for a in anchors],
            tangents_in=[a[4] for a in anchors],
        )
        self.contours.append(contour)
        return contour

    def addContour(self, contour: Contour) -> None:
        """Adds a contour solved elsewhere."""
        self.contours.append(contour)

    def draw(self, pen: Any = None) -> None:
        """Draws every contour collected into ``pen`` (default the pen given at creation)."""
        if self._current is not None:
            raise ValueError("draw: a contour was begun and not ended")
        draw_contours(self.contours, self.outPen if pen is None else pen, **self.options)


def _one_bezier_elements(draw: Any, glyph_set: Any) -> list:
    """The outline ``draw(pen)`` draws, as elements of one Bézier each: TrueType runs of
    implied on-curve points and contours without on-curve points are split by fontTools'
    BasePen; components are drawn from ``glyph_set``."""
    from fontTools.pens.basePen import BasePen

    class _Elements(BasePen):
        def __init__(self) -> None:
            super().__init__(glyph_set)
            self.value: list = []

        def _moveTo(self, pt):
            self.value.append(("moveTo", (pt,)))

        def _lineTo(self, pt):
            self.value.append(("lineTo", (pt,)))

        def _curveToOne(self, p1, p2, p3):
            self.value.append(("curveTo", (p1, p2, p3)))

        def _qCurveToOne(self, p1, p2):
            self.value.append(("qCurveTo", (p1, p2)))

        def _closePath(self):
            self.value.append(("closePath", ()))

        def _endPath(self):
            self.value.append(("endPath", ()))

    pen = _Elements()
    draw(pen)
    return pen.value


def draft_glyph(
    glyph: Any,
    glyph_set: Any = None,
    *,
    units_per_em: float = 1000.0,
    scheme: str = "kappa",
    shape: Any = None,
    tolerance: Optional[float] = None,
    fair: bool = False,
    simplify: bool = False,
    extremum_tangents: bool = True,
) -> DraftedGlyph:
    """Drafts κ contours from a glyph, as ``kappa font`` drafts each glyph.

    ``glyph`` is anything with ``draw(pen)`` (a fontTools glyph-set glyph, a ufoLib2 or
    defcon glyph) or a list of elements in RecordingPen form; components are decomposed
    through ``glyph_set`` (e.g. ``TTFont.getGlyphSet()`` or a ufoLib2 font). The result
    holds one ``Contour`` per closed subpath (``contours``), ``hausdorff`` (the largest
    distance of a drafted piece from the original, font units), ``within_tolerance``,
    ``fallbacks``, and ``to_json()``: the κ source to keep under ``KAPPA_LIB_KEY``.

    - ``units_per_em`` scales the defaults: ``tolerance`` 0.004 em less 5 % (room for the
      written outline, as ``kappa font`` drafts a UFO), anchors at least 0.06 em apart.
    - ``scheme`` and ``shape``: for the εκ schemes None (neutral), a number, or "auto"
      (per anchor, matching the original's curvature peak).
    - ``fair``, ``simplify``: mend spurious inflections; drop anchors not needed.
    - ``extremum_tangents``: hold horizontal and vertical tangents at extremum anchors.
    """
    if hasattr(glyph, "draw"):
        draw = glyph.draw
    else:

        def draw(pen):
            replay(glyph, pen)

    return draft_elements(
        _one_bezier_elements(draw, glyph_set),
        units_per_em,
        scheme,
        shape,
        tolerance,
        fair,
        simplify,
        extremum_tangents,
    )
