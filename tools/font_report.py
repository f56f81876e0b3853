#!/usr/bin/env python3
"""Outline quality of a font written from another: `font_report.py SOURCE OUTPUT`.

    python tools/font_report.py SOURCE_FONT OUTPUT [--chars STRING] [--json]

SOURCE_FONT is a .ttf/.otf (TrueType or CFF outlines); OUTPUT is a .ttf/.otf or a .ufo
directory written from it with the same glyph names (as `kappa font` writes them). For each
character of --chars (default A-Z a-z 0-9 & @ ß; characters the source lacks are skipped and
listed) the source glyph and the output glyph of the same name are compared, components
decomposed, both in font units as stored (a TrueType source is already on the integer grid;
nothing is rounded). A table goes to stdout, or with --json one JSON object
{"source", "output", "units_per_em", "skipped", "missing_in_output", "totals", "glyphs"}.
An independent measurement: nothing here reads kappa's own report.

Outlines. Every contour becomes a cycle of segments: lines, quadratics and cubics. A
TrueType qCurveTo run is expanded into single quadratics, its implied on-curve points (the
midpoints between consecutive off-curve points) becoming on-curve nodes like the stored ones;
a contour of off-curve points only starts at the implied point between its last and first.
Segments whose points all coincide are dropped (e.g. a closing line back onto the start).
The on-curve *nodes* are the segments' start points, so a closed contour has as many nodes
as segments. At a node, the incoming tangent is the direction from the previous segment's
last control point distinct from the node to the node, the outgoing one from the node to the
next segment's first control point distinct from it; the *turn* is the angle between them
(0 for a smooth node, in degrees). Contour direction plays no part (a UFO has its outer
contours the other way round from a TrueType font).

1. Fidelity: the two-sided Hausdorff distance max(h(S, O), h(O, S)) between the whole glyph
   outlines, h(A, B) = max over samples a of A of the distance from a to the polyline through
   the samples of B. Each segment is sampled at t = k/n with n = ceil(d * max control-polygon
   edge / 1 unit) for a segment of degree d, which bounds the arc length between consecutive
   samples by 1 unit (the speed of a Bezier curve never exceeds d times its longest control
   polygon edge). The polyline strays at most L^2/(8r) <= 1/(8r) units from the curve, r the
   radius of curvature. Search: a uniform grid of the polyline's pieces searched ring by ring
   around each query point (then chunks of 32 pieces, nearest box first, for points far from
   the other outline), with an early break once a sample is nearer than the largest distance
   so far (Taha and Hanbury 2015), which keeps the max exact. Reported in units and in em
   (Hausdorff / unitsPerEm); a glyph is *within* when that is <= 0.004 em. A glyph empty on one
   side only has distance infinity (null in JSON).

2. Extremum nodes kept: a source node is an *axis-aligned extremum node* when its incoming and
   outgoing tangents both lie within 1 degree of the same axis and point the same way (a
   corner or a cusp is not counted), and it is a local extremum of the other coordinate along
   the contour (y for a horizontal tangent, x for a vertical one): walking the sampled contour
   from the node forwards and backwards, the first samples that depart from the node's
   coordinate by more than 0.5 unit both lie on the same side of it (or one side never departs
   within its adjacent segments -- a straight flat stretch -- and the other does: reported
   apart as "at flat ends", e.g. where a vertical stem flows into a curve; the rest are
   "strict"). The 0.5 unit threshold keeps a tangent that is up to 1 degree off on a flat
   curve from hiding the extremum.
   It is *kept* when the output has a node within max(2 units, 0.002 em) of it whose incoming
   and outgoing tangents both lie within 1 degree of the same axis and point the same way.

3. Missing extrema: a curve segment (a quadratic or a cubic; lines cannot have any) counts
   when, for x or for y, its derivative vanishes at some t with 0 < t < 1 and the coordinate
   there lies outside the interval spanned by the segment's two end points by more than
   1 unit: the segment bulges past its end points, so an extremum node is missing there (the
   test of fontbakery-style "missing extrema" checks, with a 1 unit allowance). Each segment
   counts once, whichever axis.

4. Short segments: curve segments (not lines) whose chord, end point to end point, is shorter
   than 2 units.

5. Smooth joins: the source nodes with a turn below 0.5 degree are smooth. For each, the
   output node nearest to it within 2 units (if any) is its match; reported are how many
   matched, the largest turn at a match, and how many matches turn by more than 0.5 degree.
   Also the number of on-curve nodes (stored and implied) in source and output.

Needs fontTools (and ufoLib2 for a .ufo OUTPUT); plain Python, no numpy.
"""

import argparse
import json
import math
import os
import sys
import time

from fontTools.pens.basePen import decomposeSuperBezierSegment
from fontTools.pens.recordingPen import DecomposingRecordingPen
from fontTools.ttLib import TTFont

DEFAULT_CHARS = ("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789&@\u00df")
SAMPLE_STEP = 1.0  # font units of arc length between samples, at most
WITHIN_EM = 0.004  # fidelity bound, em
AXIS_DEG = 1.0  # tangent within this of an axis
EXTREMUM_DEPART = 0.5  # units a walk must depart from the node to tell the side
KEEP_UNITS, KEEP_EM = 2.0, 0.002  # an extremum node is kept by a node within max of these
BULGE_UNITS = 1.0  # missing extrema: bulge past the end points' span
SHORT_UNITS = 2.0  # short curve segments: chord below this
SMOOTH_DEG = 0.5  # smooth join: turn below this
SMOOTH_MATCH_UNITS = 2.0  # smooth join: output node within this
GRID_CELL = 8.0  # font units, the spatial grid of the distance search
GRID_RINGS = 4  # rings of cells searched before the search by chunks takes over
CHUNK = 32  # pieces per chunk (a box) in that search


# ---------------------------------------------------------------------------------------------
# Reading: fonts, glyph sets, recordings into contours of segments.


class Source:
    """A font to read glyph outlines from: a .ttf/.otf file or a .ufo directory."""

    def __init__(self, path):
        self.path = path
        if os.path.isdir(path) or path.lower().endswith(".ufo"):
            import ufoLib2

            self.kind = "ufo"
            self.ufo = ufoLib2.Font.open(path)
            self.glyphset = self.ufo.layers.defaultLayer
            self.upem = self.ufo.info.unitsPerEm
            self._cmap = None  # read only when a glyph name is missing: it loads every glyph
            self.names = set(self.glyphset.keys())
        else:
            font = TTFont(path, lazy=True)
            self.kind = "glyf" if "glyf" in font else "cff"
            self.glyphset = font.getGlyphSet()
            self.upem = font["head"].unitsPerEm
            self._cmap = font.getBestCmap() or {}
            self.names = set(font.getGlyphOrder())

    @property
    def cmap(self):
        if self._cmap is None:
            self._cmap = {}
            for glyph in self.glyphset:
                for u in glyph.unicodes:
                    self._cmap.setdefault(u, glyph.name)
        return self._cmap

    def contours(self, name):
        pen = DecomposingRecordingPen(self.glyphset, skipMissingComponents=True)
        self.glyphset[name].draw(pen)
        return contours_from_recording(pen.value)


class Contour:
    """segs: [(degree, points)], points[0] the start node, points[-1] the end; closed."""

    __slots__ = ("segs", "closed", "samples", "node_sample")

    def __init__(self, segs, closed):
        self.segs = segs
        self.closed = closed
        self.samples = None
        self.node_sample = None


def _same(p, q):
    return p[0] == q[0] and p[1] == q[1]


def _mid(p, q):
    return ((p[0] + q[0]) * 0.5, (p[1] + q[1]) * 0.5)


def contours_from_recording(recording):
    """Turns a segment-pen recording into Contours; zero-length segments dropped."""
    contours = []
    segs = []
    start = cur = None

    def add(points):
        if all(_same(p, points[0]) for p in points[1:]):
            return
        segs.append((len(points) - 1, tuple(points)))

    def finish(closed):
        nonlocal segs, start, cur
        if closed and cur is not None and start is not None and not _same(cur, start):
            add([cur, start])
        if segs:
            contours.append(Contour(segs, closed))
        segs = []
        start = cur = None

    for op, args in recording:
        args = [tuple(map(float, a)) if a is not None else None for a in args]
        if op == "moveTo":
            if segs or cur is not None:
                finish(False)
            start = cur = args[0]
        elif op == "lineTo":
            add([cur, args[0]])
            cur = args[0]
        elif op == "curveTo":
            if len(args) == 3:
                add([cur] + args)
            elif len(args) == 2:  # a quadratic given as curveTo
                add([cur] + args)
            elif len(args) == 1:
                add([cur, args[0]])
            else:
                for seg in decomposeSuperBezierSegment(args):
                    add([cur] + list(seg))
                    cur = seg[-1]
            cur = args[-1]
        elif op == "qCurveTo":
            offs = args[:-1]
            on = args[-1]
            if on is None:  # a contour of off-curve points only
                on = _mid(offs[-1], offs[0])
                start = cur = on  # on -> offs[0] -> ... -> offs[-1] -> on
            if not offs:
                add([cur, on])
            else:
                for i, c in enumerate(offs):
                    end = on if i == len(offs) - 1 else _mid(c, offs[i + 1])
                    add([cur, c, end])
                    cur = end
            cur = on
        elif op == "closePath":
            finish(True)
        elif op == "endPath":
            finish(False)
        elif op == "addComponent":
            raise ValueError("component left undecomposed")
    if segs:
        finish(False)
    return contours


# ---------------------------------------------------------------------------------------------
# Geometry of segments.


def bez_point(deg, p, t):
    mt = 1.0 - t
    if deg == 1:
        return (mt * p[0][0] + t * p[1][0], mt * p[0][1] + t * p[1][1])
    if deg == 2:
        a, b, c = mt * mt, 2 * mt * t, t * t
        return (a * p[0][0] + b * p[1][0] + c * p[2][0], a * p[0][1] + b * p[1][1] + c * p[2][1])
    a, b, c, d = mt * mt * mt, 3 * mt * mt * t, 3 * mt * t * t, t * t * t
    return (a * p[0][0] + b * p[1][0] + c * p[2][0] + d * p[3][0],
            a * p[0][1] + b * p[1][1] + c * p[2][1] + d * p[3][1])


def seg_samples(deg, p, step=SAMPLE_STEP):
    """Points at t = k/n, k = 0..n-1 (the end point is the next segment's start)."""
    longest = max(math.hypot(p[i + 1][0] - p[i][0], p[i + 1][1] - p[i][1]) for i in range(deg))
    n = max(1, int(math.ceil(deg * longest / step)))
    if deg == 1:
        (x0, y0), (x1, y1) = p
        return [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(n)]
    return [bez_point(deg, p, k / n) for k in range(n)]


def out_dir(deg, p):
    """Unit direction leaving the start point, or None."""
    for q in p[1:]:
        dx, dy = q[0] - p[0][0], q[1] - p[0][1]
        h = math.hypot(dx, dy)
        if h > 0:
            return (dx / h, dy / h)
    return None


def in_dir(deg, p):
    """Unit direction arriving at the end point, or None."""
    e = p[-1]
    for q in reversed(p[:-1]):
        dx, dy = e[0] - q[0], e[1] - q[1]
        h = math.hypot(dx, dy)
        if h > 0:
            return (dx / h, dy / h)
    return None


def angle_deg(u, v):
    """Angle between unit vectors, degrees, 0..180."""
    cross = u[0] * v[1] - u[1] * v[0]
    dot = u[0] * v[0] + u[1] * v[1]
    return math.degrees(math.atan2(abs(cross), dot))


def axis_of(u, tol_deg=AXIS_DEG):
    """'h' or 'v' when u lies within tol_deg of that axis (either sense), else None."""
    s = math.sin(math.radians(tol_deg))
    if abs(u[1]) <= s:
        return "h"
    if abs(u[0]) <= s:
        return "v"
    return None


class Node:
    __slots__ = ("pt", "tin", "tout", "turn", "axis", "contour", "index")

    def __init__(self, pt, tin, tout, contour, index):
        self.pt = pt
        self.tin = tin
        self.tout = tout
        self.contour = contour
        self.index = index
        if tin is None or tout is None:
            self.turn = None
            self.axis = None
        else:
            self.turn = angle_deg(tin, tout)
            a_in, a_out = axis_of(tin), axis_of(tout)
            same_sense = tin[0] * tout[0] + tin[1] * tout[1] > 0
            self.axis = a_in if (a_in is not None and a_in == a_out and same_sense) else None


def contour_nodes(ci, contour):
    segs = contour.segs
    n = len(segs)
    nodes = []
    for i, (deg, p) in enumerate(segs):
        if contour.closed:
            pdeg, pp = segs[i - 1]
            tin = in_dir(pdeg, pp)
        else:
            tin = in_dir(*segs[i - 1]) if i > 0 else None
        nodes.append(Node(p[0], tin, out_dir(deg, p), ci, i))
    if not contour.closed and n:
        deg, p = segs[-1]
        nodes.append(Node(p[-1], in_dir(deg, p), None, ci, n))
    return nodes


def sample_contour(contour):
    pts = []
    node_sample = []
    for deg, p in contour.segs:
        node_sample.append(len(pts))
        pts.extend(seg_samples(deg, p))
    if not contour.closed:
        node_sample.append(len(pts))
        pts.append(contour.segs[-1][1][-1])
    contour.samples = pts
    contour.node_sample = node_sample


def is_local_extremum(contour, node):
    """For an axis-aligned node: 'strict' when the walks both ways leave on the same side of
    it, 'flat' when one walk stays within EXTREMUM_DEPART over its adjacent segment (a straight
    stretch along the axis) and the other leaves, None otherwise."""
    coord = 1 if node.axis == "h" else 0
    pts = contour.samples
    m = len(pts)
    i0 = contour.node_sample[node.index]
    v0 = node.pt[coord]
    # walk no further than the adjacent segments' extent in samples, both ways
    nseg = len(contour.segs)
    if contour.closed:
        nxt = contour.node_sample[(node.index + 1) % nseg]
        fwd_len = (nxt - i0) % m or m
        prv = contour.node_sample[(node.index - 1) % nseg]
        back_len = (i0 - prv) % m or m
    else:
        fwd_len = (contour.node_sample[node.index + 1] - i0) if node.index < nseg else 0
        back_len = (i0 - contour.node_sample[node.index - 1]) if node.index > 0 else 0
    sides = []
    for direction, length in ((1, fwd_len), (-1, back_len)):
        side = 0
        for k in range(1, length + 1):
            j = i0 + direction * k
            if contour.closed:
                j %= m
            elif not 0 <= j < m:
                break
            d = pts[j][coord] - v0
            if abs(d) > EXTREMUM_DEPART:
                side = 1 if d > 0 else -1
                break
        sides.append(side)
    a, b = sides
    if a == 0 and b == 0:
        return None
    if a == b:
        return "strict"
    return "flat" if a == 0 or b == 0 else None


def quad_roots(a, b, c):
    """Real roots of a t^2 + b t + c."""
    if abs(a) < 1e-12:
        if abs(b) < 1e-12:
            return []
        return [-c / b]
    disc = b * b - 4 * a * c
    if disc < 0:
        return []
    s = math.sqrt(disc)
    q = -0.5 * (b + math.copysign(s, b))
    roots = [q / a]
    if q != 0:
        roots.append(c / q)
    return roots


def bulges(deg, p):
    """Largest distance by which the segment passes beyond its end points' span, x or y,
    at an interior stationary point (0 < t < 1); 0 when none."""
    worst = 0.0
    if deg < 2:
        return worst
    for k in (0, 1):
        c = [q[k] for q in p]
        if deg == 2:
            den = c[0] - 2 * c[1] + c[2]
            ts = [(c[0] - c[1]) / den] if den != 0 else []
        else:
            # derivative / 3 = A t^2 + B t + C
            a = -c[0] + 3 * c[1] - 3 * c[2] + c[3]
            b = 2 * (c[0] - 2 * c[1] + c[2])
            cc = c[1] - c[0]
            ts = quad_roots(a, b, cc)
        lo, hi = min(c[0], c[-1]), max(c[0], c[-1])
        for t in ts:
            if 0 < t < 1:
                v = bez_point(deg, p, t)[k]
                worst = max(worst, v - hi, lo - v)
    return worst


# ---------------------------------------------------------------------------------------------
# Hausdorff distance between sampled outlines.


class Polylines:
    """The pieces between consecutive samples of all contours, in a uniform grid."""

    def __init__(self, contours, cell=GRID_CELL):
        self.cell = cell
        ax, ay, bx, by = [], [], [], []
        for c in contours:
            pts = c.samples
            m = len(pts)
            last = m if c.closed else m - 1
            if m == 1:
                last = 1
            for i in range(last):
                p = pts[i]
                q = pts[(i + 1) % m]
                ax.append(p[0])
                ay.append(p[1])
                bx.append(q[0])
                by.append(q[1])
        self.ax, self.ay, self.bx, self.by = ax, ay, bx, by
        grid = {}
        inv = 1.0 / cell
        floor = math.floor
        for i in range(len(ax)):
            ka = (int(floor(ax[i] * inv)), int(floor(ay[i] * inv)))
            if ka == (int(floor(bx[i] * inv)), int(floor(by[i] * inv))):
                lst = grid.get(ka)
                if lst is None:
                    grid[ka] = [i]
                else:
                    lst.append(i)
                continue
            x0, x1 = (ax[i], bx[i]) if ax[i] <= bx[i] else (bx[i], ax[i])
            y0, y1 = (ay[i], by[i]) if ay[i] <= by[i] else (by[i], ay[i])
            for gx in range(int(math.floor(x0 * inv)), int(math.floor(x1 * inv)) + 1):
                for gy in range(int(math.floor(y0 * inv)), int(math.floor(y1 * inv)) + 1):
                    grid.setdefault((gx, gy), []).append(i)
        self.grid = grid
        if grid:
            gxs = [k[0] for k in grid]
            gys = [k[1] for k in grid]
            self.gbox = (min(gxs), min(gys), max(gxs), max(gys))
        self.n = len(ax)
        # chunks of consecutive pieces with their boxes, for queries far from the outline
        chunks = []
        for c0 in range(0, self.n, CHUNK):
            c1 = min(self.n, c0 + CHUNK)
            xs = ax[c0:c1] + bx[c0:c1]
            ys = ay[c0:c1] + by[c0:c1]
            chunks.append((min(xs), min(ys), max(xs), max(ys), c0, c1))
        self.chunks = chunks

    def dist2(self, i, px, py):
        ax, ay = self.ax[i], self.ay[i]
        dx, dy = self.bx[i] - ax, self.by[i] - ay
        wx, wy = px - ax, py - ay
        ll = dx * dx + dy * dy
        if ll > 0:
            t = (wx * dx + wy * dy) / ll
            if t > 1:
                t = 1.0
            elif t < 0:
                t = 0.0
            wx -= t * dx
            wy -= t * dy
        return wx * wx + wy * wy

    def nearest(self, px, py, stop2):
        """(d2, index) of a piece at least as near as any, searching rings of cells; returns
        as soon as a piece within sqrt(stop2) is found (early break)."""
        cell = self.cell
        gx, gy = int(math.floor(px / cell)), int(math.floor(py / cell))
        x0, y0, x1, y1 = self.gbox
        kmax = max(gx - x0, x1 - gx, gy - y0, y1 - gy, 0)
        best, bi = math.inf, -1
        if kmax > GRID_RINGS:
            kmax = GRID_RINGS
            far = True
        else:
            far = False
        grid = self.grid
        dist2 = self.dist2
        for k in range(kmax + 1):
            if k == 0:
                cells = [(gx, gy)]
            else:
                cells = []
                for x in range(gx - k, gx + k + 1):
                    cells.append((x, gy - k))
                    cells.append((x, gy + k))
                for y in range(gy - k + 1, gy + k):
                    cells.append((gx - k, y))
                    cells.append((gx + k, y))
            for key in cells:
                lst = grid.get(key)
                if lst is None:
                    continue
                for i in lst:
                    d = dist2(i, px, py)
                    if d < best:
                        best, bi = d, i
                        if best <= stop2:
                            return best, bi
            reach = k * cell
            if best <= reach * reach:
                return best, bi
        if not far:
            return best, bi
        # not settled near the point: the chunks, nearest box first
        boxes = []
        for (bx0, by0, bx1, by1, c0, c1) in self.chunks:
            dx = bx0 - px if px < bx0 else (px - bx1 if px > bx1 else 0.0)
            dy = by0 - py if py < by0 else (py - by1 if py > by1 else 0.0)
            lb = dx * dx + dy * dy
            if lb < best:
                boxes.append((lb, c0, c1))
        boxes.sort()
        for lb, c0, c1 in boxes:
            if lb >= best:
                break
            for i in range(c0, c1):
                d = dist2(i, px, py)
                if d < best:
                    best, bi = d, i
                    if best <= stop2:
                        return best, bi
        return best, bi


def directed_hausdorff(a_contours, b_poly):
    """max over the samples of A of their distance to B's polylines (exact on the samples)."""
    if b_poly.n == 0:
        return math.inf, None
    cmax2 = 0.0
    where = None
    hint = 0
    n = b_poly.n
    dist2 = b_poly.dist2
    for c in a_contours:
        for (px, py) in c.samples:
            # the pieces around the last nearest one: usually enough to beat the running max
            if dist2(hint, px, py) <= cmax2:
                continue
            d = min(dist2((hint + j) % n, px, py) for j in (-2, -1, 1, 2))
            if d <= cmax2:
                continue
            d, i = b_poly.nearest(px, py, cmax2)
            hint = i
            if d > cmax2:
                cmax2, where = d, (px, py)
    return math.sqrt(cmax2), where


# ---------------------------------------------------------------------------------------------
# One glyph.


class Outline:
    def __init__(self, contours):
        self.contours = contours
        self.nodes = []
        for ci, c in enumerate(contours):
            sample_contour(c)
            self.nodes.extend(contour_nodes(ci, c))
        self.poly = Polylines(contours)

    def curve_segments(self):
        for c in self.contours:
            for deg, p in c.segs:
                if deg >= 2:
                    yield deg, p

    def missing_extrema(self):
        return [(deg, p) for deg, p in self.curve_segments() if bulges(deg, p) > BULGE_UNITS]

    def short_segments(self):
        return [(deg, p) for deg, p in self.curve_segments()
                if math.hypot(p[-1][0] - p[0][0], p[-1][1] - p[0][1]) < SHORT_UNITS]

    def extremum_nodes(self):
        """[(node, 'strict' | 'flat')]"""
        found = []
        for n in self.nodes:
            if n.axis is not None:
                kind = is_local_extremum(self.contours[n.contour], n)
                if kind:
                    found.append((n, kind))
        return found


def compare(src, out, upem):
    row = {}
    if src.poly.n == 0 and out.poly.n == 0:
        h, where = 0.0, None
    else:
        h1, w1 = directed_hausdorff(src.contours, out.poly)
        h2, w2 = directed_hausdorff(out.contours, src.poly)
        h, where = (h1, ("source", w1)) if h1 >= h2 else (h2, ("output", w2))
    row["hausdorff"] = h
    row["hausdorff_em"] = h / upem
    row["hausdorff_at"] = None if where is None or where[1] is None else {
        "side": where[0], "point": [round(where[1][0], 2), round(where[1][1], 2)]}
    row["within"] = h / upem <= WITHIN_EM

    keep_r = max(KEEP_UNITS, KEEP_EM * upem)
    ext = src.extremum_nodes()
    lost = []
    strict = strict_kept = 0
    for n, kind in ext:
        ok = False
        for m in out.nodes:
            if m.axis == n.axis and math.hypot(m.pt[0] - n.pt[0], m.pt[1] - n.pt[1]) <= keep_r:
                ok = True
                break
        if not ok:
            lost.append((n, kind))
        if kind == "strict":
            strict += 1
            strict_kept += ok
    row["extremum_nodes"] = len(ext)
    row["extremum_kept"] = len(ext) - len(lost)
    row["extremum_strict"] = strict
    row["extremum_strict_kept"] = strict_kept
    row["extremum_lost"] = [[n.pt[0], n.pt[1], n.axis, kind] for n, kind in lost]

    row["missing_extrema"] = {"source": len(src.missing_extrema()),
                              "output": len(out.missing_extrema())}
    row["short_segments"] = {"source": len(src.short_segments()),
                             "output": len(out.short_segments())}

    smooth = [n for n in src.nodes if n.turn is not None and n.turn < SMOOTH_DEG]
    matched = 0
    worst = 0.0
    worst_at = None
    over = 0
    for n in smooth:
        best, bm = SMOOTH_MATCH_UNITS, None
        for m in out.nodes:
            d = math.hypot(m.pt[0] - n.pt[0], m.pt[1] - n.pt[1])
            if d <= best:
                best, bm = d, m
        if bm is None or bm.turn is None:
            continue
        matched += 1
        if bm.turn > worst:
            worst, worst_at = bm.turn, bm.pt
        if bm.turn > SMOOTH_DEG:
            over += 1
    row["smooth_joins"] = {"source": len(smooth), "matched": matched, "max_turn_deg": worst,
                           "over": over,
                           "max_turn_at": None if worst_at is None else list(worst_at)}
    row["nodes"] = {"source": len(src.nodes), "output": len(out.nodes)}
    return row


# ---------------------------------------------------------------------------------------------
# Report.


def report(source_path, output_path, chars):
    t0 = time.time()
    src_font = Source(source_path)
    out_font = Source(output_path)
    upem = src_font.upem
    rows = []
    skipped = []
    missing = []
    for ch in chars:
        name = src_font.cmap.get(ord(ch))
        if name is None:
            skipped.append(ch)
            continue
        oname = name if name in out_font.names else out_font.cmap.get(ord(ch))
        if oname is None:
            missing.append(ch)
            continue
        src = Outline(src_font.contours(name))
        out = Outline(out_font.contours(oname))
        row = {"char": ch, "name": name}
        row.update(compare(src, out, upem))
        rows.append(row)

    def total(key, side):
        return sum(r[key][side] for r in rows)

    hs = [r["hausdorff"] for r in rows]
    finite = [h for h in hs if math.isfinite(h)]
    totals = {
        "glyphs": len(rows),
        "within": sum(r["within"] for r in rows),
        "hausdorff_max": max(hs) if hs else 0.0,
        "hausdorff_mean": sum(finite) / len(finite) if finite else 0.0,
        "extremum_nodes": sum(r["extremum_nodes"] for r in rows),
        "extremum_kept": sum(r["extremum_kept"] for r in rows),
        "extremum_strict": sum(r["extremum_strict"] for r in rows),
        "extremum_strict_kept": sum(r["extremum_strict_kept"] for r in rows),
        "missing_extrema": {"source": total("missing_extrema", "source"),
                            "output": total("missing_extrema", "output")},
        "short_segments": {"source": total("short_segments", "source"),
                           "output": total("short_segments", "output")},
        "smooth_joins": {"source": total("smooth_joins", "source"),
                         "matched": total("smooth_joins", "matched"),
                         "over": total("smooth_joins", "over"),
                         "max_turn_deg": max((r["smooth_joins"]["max_turn_deg"] for r in rows),
                                             default=0.0)},
        "nodes": {"source": total("nodes", "source"), "output": total("nodes", "output")},
    }
    totals["hausdorff_max_em"] = totals["hausdorff_max"] / upem
    if out_font.upem != upem:
        totals["warning"] = f"unitsPerEm differ: source {upem}, output {out_font.upem}"
    return {
        "source": source_path,
        "output": output_path,
        "output_format": out_font.kind,
        "units_per_em": upem,
        "definitions": {
            "sample_step_units": SAMPLE_STEP, "within_em": WITHIN_EM, "axis_deg": AXIS_DEG,
            "keep_radius_units": max(KEEP_UNITS, KEEP_EM * upem), "bulge_units": BULGE_UNITS,
            "short_units": SHORT_UNITS, "smooth_deg": SMOOTH_DEG,
            "smooth_match_units": SMOOTH_MATCH_UNITS},
        "skipped": "".join(skipped),
        "missing_in_output": "".join(missing),
        "totals": totals,
        "glyphs": rows,
        "seconds": round(time.time() - t0, 3),
    }


def fmt_table(rep):
    out = []
    t = rep["totals"]
    upem = rep["units_per_em"]
    out.append(f"source {rep['source']}  output {rep['output']} ({rep['output_format']})  "
               f"unitsPerEm {upem}")
    head = (f"{'char':<5}{'glyph':<12}{'hausd':>8}{'em':>8} {'ok':<3}{'extrema':>8}"
            f"{'missing':>9}{'short':>8}{'smooth':>8}{'>0.5':>5}{'maxturn':>8}{'nodes':>10}")
    out.append(head)
    out.append("(hausd: Hausdorff, units; em: / unitsPerEm; ok: within 0.004 em; extrema: extremum "
               "nodes kept/total; missing, short: source>output segments; smooth: smooth source "
               "joins matched/total, >0.5: matches turning over 0.5 deg, maxturn: their largest "
               "turn; nodes: on-curve nodes source>output)")
    for r in rep["glyphs"]:
        h = r["hausdorff"]
        hs = f"{h:8.2f}" if math.isfinite(h) else f"{'inf':>8}"
        hem = f"{r['hausdorff_em']:8.5f}" if math.isfinite(h) else f"{'inf':>8}"
        sj = r["smooth_joins"]
        out.append(
            f"{r['char']:<5}{r['name'][:11]:<12}{hs}{hem} {'y' if r['within'] else 'N':<3}"
            f"{str(r['extremum_kept']) + '/' + str(r['extremum_nodes']):>8}"
            f"{str(r['missing_extrema']['source']) + '>' + str(r['missing_extrema']['output']):>9}"
            f"{str(r['short_segments']['source']) + '>' + str(r['short_segments']['output']):>8}"
            f"{str(sj['matched']) + '/' + str(sj['source']):>8}{sj['over']:>5}"
            f"{sj['max_turn_deg']:8.2f}"
            f"{str(r['nodes']['source']) + '>' + str(r['nodes']['output']):>10}")
    sj = t["smooth_joins"]
    out.append("")
    out.append(f"glyphs within {WITHIN_EM} em: {t['within']}/{t['glyphs']}   "
               f"Hausdorff max {t['hausdorff_max']:.2f} units ({t['hausdorff_max_em']:.5f} em), "
               f"mean {t['hausdorff_mean']:.2f}")
    out.append(f"extremum nodes kept: {t['extremum_kept']}/{t['extremum_nodes']} (strict "
               f"{t['extremum_strict_kept']}/{t['extremum_strict']}, at flat ends "
               f"{t['extremum_kept'] - t['extremum_strict_kept']}/"
               f"{t['extremum_nodes'] - t['extremum_strict']})   "
               f"missing extrema (segments) source > output: "
               f"{t['missing_extrema']['source']} > {t['missing_extrema']['output']}   "
               f"short curve segments: {t['short_segments']['source']} > "
               f"{t['short_segments']['output']}")
    out.append(f"smooth joins: {sj['source']} in source, {sj['matched']} matched within "
               f"{SMOOTH_MATCH_UNITS} units, {sj['over']} turn over {SMOOTH_DEG} deg "
               f"(max {sj['max_turn_deg']:.2f})   on-curve nodes source > output: "
               f"{t['nodes']['source']} > {t['nodes']['output']}")
    if rep["skipped"]:
        out.append(f"skipped (not in source): {rep['skipped']}")
    if rep["missing_in_output"]:
        out.append(f"missing in output: {rep['missing_in_output']}")
    if "warning" in t:
        out.append("warning: " + t["warning"])
    out.append(f"({rep['seconds']} s)")
    return "\n".join(out)


def _json_safe(x):
    if isinstance(x, float):
        return None if not math.isfinite(x) else float(f"{x:.6g}")
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    return x


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("source", help="the source font, .ttf or .otf")
    ap.add_argument("output", help="the font written from it: .ttf, .otf or .ufo")
    ap.add_argument("--chars", default=DEFAULT_CHARS, help="characters to compare")
    ap.add_argument("--json", action="store_true", help="print one JSON object instead")
    args = ap.parse_args(argv)
    rep = report(args.source, args.output, args.chars)
    if args.json:
        print(json.dumps(_json_safe(rep)))
    else:
        print(fmt_table(rep))
    return 0


if __name__ == "__main__":
    sys.exit(main())
