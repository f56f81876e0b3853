#!/usr/bin/env python3
"""External validation of the fonts kappa's tests write: `check_fonts.py DIR`.

Checks every *.ttf, *.otf and *.ufo under DIR (a .ufo is not descended into) and prints one
line per problem, one summary line per file and a closing `N passed, M failed`. Exits 1 when
any file fails or when DIR holds nothing to check, 0 otherwise.

Compiled fonts (.ttf: glyf outlines, .otf: CFF outlines):
- the OpenType Sanitizer (OTS, as browsers run it) accepts the file;
- fontTools loads it, decompiles every table, and a ttx XML round trip (saveXML, importXML,
  compile) works, as fontbakery's ttx round-trip check does;
- tables head, hhea, maxp, OS/2, hmtx, cmap, name, post and glyf+loca (.ttf) or CFF (.otf);
- OS/2 version >= 4; post format 2.0 (.ttf) with unique, non-empty names for all
  maxp.numGlyphs glyphs;
- head.created and head.modified set (after 1970); head's bounding box is the union of the
  glyphs' boxes (glyf: control points, as the glyf headers define it; CFF: exact curve
  bounds, as fontTools computes the CFF FontBBox); each glyf header box and each hmtx left
  side bearing matches the outline; all within 1 unit;
- hhea advanceWidthMax, minLeftSideBearing, minRightSideBearing and xMaxExtent match hmtx
  and the outlines, within 1 unit;
- name IDs 1-6 for Windows, Unicode BMP, English (US);
- contour direction: glyf outer contours clockwise, inner counter-clockwise; CFF the
  opposite. A contour is outer when an even number of the glyph's other contours contain it.
  Components are not checked here (their base glyphs are); one-point contours (anchors) are
  skipped, other contours of zero area are reported.

UFO sources (.ufo):
- ufoLib2 opens it and every glyph of every layer draws through a RecordingPen;
- fontinfo has unitsPerEm, ascender, descender, xHeight, capHeight, familyName, styleName;
- lib public.glyphOrder lists every glyph of the default layer;
- closed contours only, outer ones counter-clockwise and inner ones clockwise;
- with KAPPA_FONTMAKE=1: `fontmake -u UFO -o ttf` (fontmake of this Python) exits 0 and the
  TTF it builds passes the checks above.

Python >= 3.9; needs fonttools, opentype-sanitizer and ufoLib2 (and fontmake for
KAPPA_FONTMAKE=1).
"""

import io
import logging
import math
import os
import subprocess
import sys
import tempfile

import ots
import ufoLib2
from fontTools.pens.areaPen import AreaPen
from fontTools.pens.basePen import BasePen
from fontTools.pens.boundsPen import BoundsPen
from fontTools.pens.recordingPen import RecordingPen, replayRecording
from fontTools.ttLib import TTFont

TOLERANCE = 1  # font units, for boxes and metrics
EPOCH_1970 = 0x7C259DC0  # 1970-01-01 in head's seconds since 1904-01-01
MAX_CONTOUR_REPORTS = 100  # per file; the rest are counted
CURVE_STEPS = 16  # line segments per curve when flattening for containment tests
COMMON_TABLES = ["head", "hhea", "maxp", "OS/2", "hmtx", "cmap", "name", "post"]
REQUIRED_NAME_IDS = [1, 2, 3, 4, 5, 6]
UFO_INFO = ["unitsPerEm", "ascender", "descender", "xHeight", "capHeight", "familyName",
            "styleName"]


class LogCollector(logging.Handler):
    """Collects fontTools' log records so that errors it only logs still count."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.records = []

    def emit(self, record):
        self.records.append(record)


# ---------------------------------------------------------------------------------------------
# Contours: split a glyph drawing into contours, their signed areas, their nesting.


class FlattenPen(BasePen):
    """Flattens one contour into a polygon (curves sampled at CURVE_STEPS points)."""

    def __init__(self):
        super().__init__(None)
        self.points = []

    def _moveTo(self, p):
        self.points.append(p)

    def _lineTo(self, p):
        self.points.append(p)

    def _curveToOne(self, p1, p2, p3):
        x0, y0 = self._getCurrentPoint()
        for i in range(1, CURVE_STEPS + 1):
            t = i / CURVE_STEPS
            u = 1 - t
            a, b, c, d = u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t
            self.points.append((a * x0 + b * p1[0] + c * p2[0] + d * p3[0],
                                a * y0 + b * p1[1] + c * p2[1] + d * p3[1]))

    def _qCurveToOne(self, p1, p2):
        x0, y0 = self._getCurrentPoint()
        for i in range(1, CURVE_STEPS + 1):
            t = i / CURVE_STEPS
            u = 1 - t
            a, b, c = u * u, 2 * u * t, t * t
            self.points.append((a * x0 + b * p1[0] + c * p2[0], a * y0 + b * p1[1] + c * p2[1]))

    def _closePath(self):
        pass

    def _endPath(self):
        pass


def split_contours(recording):
    """The contours of a RecordingPen value (components dropped): (ops, closed) pairs."""
    contours, current = [], []
    for op, args in recording:
        if op == "addComponent" or op == "addVarComponent":
            continue
        current.append((op, args))
        if op in ("closePath", "endPath"):
            contours.append((current, op == "closePath"))
            current = []
    if current:
        contours.append((current, False))
    return contours


def point_in_polygon(x, y, poly):
    inside = False
    n = len(poly)
    for i in range(n):
        x1, y1 = poly[i]
        x2, y2 = poly[(i + 1) % n]
        if (y1 > y) != (y2 > y):
            xc = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
            if xc > x:
                inside = not inside
    return inside


def polygon_box(poly):
    xs = [p[0] for p in poly]
    ys = [p[1] for p in poly]
    return min(xs), min(ys), max(xs), max(ys)


def contained(poly, other, other_box):
    """Whether contour `poly` lies inside contour `other`: a majority of up to 9 of its points
    are (so that a point where the two touch does not decide)."""
    step = max(1, len(poly) // 9)
    samples = poly[::step][:9]
    votes = 0
    for x, y in samples:
        if (other_box[0] <= x <= other_box[2] and other_box[1] <= y <= other_box[3]
                and point_in_polygon(x, y, other)):
            votes += 1
    return 2 * votes > len(samples)


def direction_problems(name, recording, outer_ccw):
    """Problems with the direction of a glyph's own contours (not its components')."""
    problems = []
    contours = []  # (index, area, polygon, box)
    for index, (ops, closed) in enumerate(split_contours(recording)):
        if not closed:
            problems.append(f"glyph {name!r} contour {index}: open contour")
            continue
        area_pen = AreaPen()
        flat = FlattenPen()
        try:
            replayRecording(ops, area_pen)
            replayRecording(ops, flat)
        except Exception as e:  # noqa: BLE001 - any drawing failure is the font's problem
            problems.append(f"glyph {name!r} contour {index}: cannot measure: {e!r}")
            continue
        if len(set(flat.points)) < 2:
            continue  # a lone point: no outline (TrueType fonts use them as anchors)
        if abs(area_pen.value) < 1e-6:
            problems.append(f"glyph {name!r} contour {index}: zero area, no direction")
            continue
        contours.append((index, area_pen.value, flat.points, polygon_box(flat.points)))
    for index, area, poly, _ in contours:
        depth = sum(1 for j, _, other, box in contours
                    if j != index and contained(poly, other, box))
        outer = depth % 2 == 0
        ccw = area > 0  # fontTools' AreaPen: counter-clockwise positive (y up)
        want_ccw = outer_ccw if outer else not outer_ccw
        if ccw != want_ccw:
            problems.append(
                f"glyph {name!r} contour {index}: {'outer' if outer else 'inner'} contour "
                f"(nesting depth {depth}) runs {'counter-clockwise' if ccw else 'clockwise'}, "
                f"expected {'counter-clockwise' if want_ccw else 'clockwise'}")
    return problems


def capped(problems, limit, what):
    if len(problems) <= limit:
        return problems
    return problems[:limit] + [f"... and {len(problems) - limit} more {what}"]


# ---------------------------------------------------------------------------------------------
# Compiled fonts


def ots_problems(path):
    result = ots.sanitize(path, os.devnull, capture_output=True)
    if result.returncode == 0:
        return []
    text = (result.stderr or b"").decode("utf-8", "replace").strip()
    out = (result.stdout or b"").decode("utf-8", "replace").strip()
    lines = [line.strip() for line in (text + "\n" + out).splitlines() if line.strip()]
    return [f"OTS rejects it (exit {result.returncode}): " + " | ".join(lines[:8])]


def ttx_round_trip_problems(font):
    with tempfile.TemporaryDirectory() as tmp:
        xml = os.path.join(tmp, "font.ttx")
        try:
            font.saveXML(xml)
        except Exception as e:  # noqa: BLE001
            return [f"ttx export fails: {e!r}"]
        try:
            again = TTFont()
            again.importXML(xml)
            again.save(io.BytesIO())
        except Exception as e:  # noqa: BLE001
            return [f"ttx import and compile fails: {e!r}"]
    return []


def near(a, b):
    return abs(a - b) <= TOLERANCE


def box_text(box):
    return "(" + ", ".join(f"{v:g}" for v in box) + ")"


def union(a, b):
    if a is None:
        return b
    return min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3])


def glyph_boxes_glyf(font, problems):
    """Per glyph with outlines: the control-point box (as glyf headers define it), checking the
    stored glyf header against it."""
    glyf = font["glyf"]
    boxes = {}
    bad = []
    for name in font.getGlyphOrder():
        glyph = glyf[name]
        if glyph.numberOfContours == 0:
            continue
        coords, _, _ = glyph.getCoordinates(glyf)
        if len(coords) == 0:
            continue
        box = tuple(coords.calcIntBounds())
        boxes[name] = box
        stored = (glyph.xMin, glyph.yMin, glyph.xMax, glyph.yMax)
        if not all(near(s, c) for s, c in zip(stored, box)):
            bad.append(f"glyph {name!r}: glyf header box {box_text(stored)} but its points span "
                       f"{box_text(box)}")
    problems.extend(capped(bad, MAX_CONTOUR_REPORTS, "glyph boxes"))
    return boxes


def glyph_boxes_cff(font):
    """Per glyph with outlines: the exact bounds of its curves (as fontTools computes the CFF
    FontBBox and hhea from them)."""
    glyphset = font.getGlyphSet()
    boxes = {}
    for name in font.getGlyphOrder():
        pen = BoundsPen(glyphset)
        glyphset[name].draw(pen)
        if pen.bounds is not None:
            boxes[name] = pen.bounds
    return boxes


def metrics_problems(font, boxes):
    problems = []
    head = font["head"]
    # fontTools reads a timestamp before 1970 as a Unix one, so read the stored bytes.
    raw = font.reader["head"]
    for field, offset in (("created", 20), ("modified", 28)):
        stamp = int.from_bytes(raw[offset:offset + 8], "big")
        if stamp == 0:
            problems.append(f"head.{field} is 0")
        elif stamp < EPOCH_1970:
            problems.append(f"head.{field} is {stamp}, before 1970: seconds since 1970, not 1904?")

    total = None
    for box in boxes.values():
        total = union(total, box)
    if total is not None:
        stored = (head.xMin, head.yMin, head.xMax, head.yMax)
        if not all(near(s, t) for s, t in zip(stored, total)):
            problems.append(f"head box {box_text(stored)} but the glyphs span {box_text(total)}")

    hmtx = font["hmtx"]
    bad_lsb = []
    for name, box in boxes.items():
        _, lsb = hmtx[name]
        if not near(lsb, box[0]):
            bad_lsb.append(f"glyph {name!r}: hmtx left side bearing {lsb} but outline xMin "
                           f"{box[0]:g}")
    problems.extend(capped(bad_lsb, MAX_CONTOUR_REPORTS, "side bearings"))

    hhea = font["hhea"]
    expect = {"advanceWidthMax": max(adv for adv, _ in hmtx.metrics.values())}
    if boxes:
        expect["minLeftSideBearing"] = min(box[0] for box in boxes.values())
        expect["minRightSideBearing"] = min(hmtx[n][0] - box[2] for n, box in boxes.items())
        expect["xMaxExtent"] = max(box[2] for box in boxes.values())
    else:
        expect.update(minLeftSideBearing=0, minRightSideBearing=0, xMaxExtent=0)
    for field, value in expect.items():
        stored = getattr(hhea, field)
        if not near(stored, value):
            problems.append(f"hhea.{field} is {stored} but hmtx and the outlines give {value:g}")
    return problems


def post_problems(font, truetype):
    problems = []
    post = font["post"]
    num_glyphs = font["maxp"].numGlyphs
    if truetype:
        if post.formatType != 2.0:
            problems.append(f"post format {post.formatType:g}, expected 2.0 (glyph names)")
            return problems
        raw = font.reader["post"]
        declared = int.from_bytes(raw[32:34], "big") if len(raw) >= 34 else None
        if declared != num_glyphs:
            problems.append(f"post names {declared} glyphs, maxp.numGlyphs is {num_glyphs}")
        # fontTools renames empty and duplicate names on reading and records the original.
        for new, original in sorted(getattr(post, "mapping", {}).items()):
            what = "empty" if original == "" else "duplicate"
            problems.append(f"post: {what} glyph name {original!r} (read as {new!r})")
    order = font.getGlyphOrder()
    if len(order) != num_glyphs:
        problems.append(f"{len(order)} glyph names for maxp.numGlyphs {num_glyphs}")
    if len(set(order)) != len(order):
        problems.append("glyph names are not unique")
    return problems


def name_problems(font):
    name = font["name"]
    missing = []
    for name_id in REQUIRED_NAME_IDS:
        record = name.getName(name_id, 3, 1, 0x409)
        if record is None or not record.toUnicode().strip():
            missing.append(str(name_id))
    if missing:
        return [f"name table lacks IDs {', '.join(missing)} for Windows/Unicode BMP/English"]
    return []


def sfnt_direction_problems(font, truetype):
    problems = []
    if truetype:
        glyf = font["glyf"]
        for name in font.getGlyphOrder():
            glyph = glyf[name]
            if glyph.numberOfContours <= 0:
                continue
            pen = RecordingPen()
            glyph.draw(pen, glyf, 0)
            problems.extend(direction_problems(name, pen.value, outer_ccw=False))
    else:
        glyphset = font.getGlyphSet()
        for name in font.getGlyphOrder():
            pen = RecordingPen()
            glyphset[name].draw(pen)
            problems.extend(direction_problems(name, pen.value, outer_ccw=True))
    return capped(problems, MAX_CONTOUR_REPORTS, "contour problems")


def check_sfnt(path):
    """Problems of a compiled font, and its glyph count (None when unknown)."""
    problems = ots_problems(path)
    collector = LogCollector()
    logger = logging.getLogger("fontTools")
    logger.addHandler(collector)
    logger.propagate = False
    try:
        try:
            font = TTFont(path)
            for tag in font.keys():
                font[tag]
            font.ensureDecompiled()
        except Exception as e:  # noqa: BLE001
            return problems + [f"fontTools cannot load it: {e!r}"], None
        glyph_count = font["maxp"].numGlyphs if "maxp" in font else None
        problems += ttx_round_trip_problems(font)

        cff = path.lower().endswith(".otf")
        outline_tables = ["CFF "] if cff else ["glyf", "loca"]
        missing = [t for t in COMMON_TABLES + outline_tables if t not in font]
        if missing:
            problems.append("missing tables: " + ", ".join(t.strip() for t in missing))
        if cff and "glyf" in font:
            problems.append(".otf file with glyf outlines, expected CFF")
        if not cff and "CFF " in font:
            problems.append(".ttf file with CFF outlines, expected glyf")
        truetype = not cff
        have = set(font.keys())

        if "OS/2" in have and font["OS/2"].version < 4:
            problems.append(f"OS/2 version {font['OS/2'].version}, expected 4 or later")
        if {"post", "maxp"} <= have:
            problems += post_problems(font, truetype)
        if "name" in have:
            problems += name_problems(font)
        outlines = "glyf" if truetype else "CFF "
        if {outlines, "head", "hhea", "hmtx"} <= have:
            boxes = glyph_boxes_glyf(font, problems) if truetype else glyph_boxes_cff(font)
            problems += metrics_problems(font, boxes)
        if outlines in have:
            problems += sfnt_direction_problems(font, truetype)
        for record in collector.records:
            if record.levelno >= logging.ERROR:
                problems.append(f"fontTools logs an error: {record.getMessage()}")
        return problems, glyph_count
    except Exception as e:  # noqa: BLE001 - a check that crashes reports instead of stopping
        return problems + [f"check crashed: {e!r}"], None
    finally:
        logger.removeHandler(collector)
        logger.propagate = True


# ---------------------------------------------------------------------------------------------
# UFO sources


def check_ufo(path):
    problems = []
    try:
        font = ufoLib2.Font.open(path)
    except Exception as e:  # noqa: BLE001
        return [f"ufoLib2 cannot open it: {e!r}"], None
    glyph_count = None
    try:
        default = font.layers.defaultLayer
        glyph_count = len(default)
        recordings = {}
        for layer in font.layers:
            for name in layer.keys():
                try:
                    pen = RecordingPen()
                    layer[name].draw(pen)
                except Exception as e:  # noqa: BLE001
                    problems.append(f"layer {layer.name!r} glyph {name!r} does not draw: {e!r}")
                    continue
                if layer is default:
                    recordings[name] = pen.value

        missing = [attr for attr in UFO_INFO if getattr(font.info, attr, None) is None]
        if missing:
            problems.append("fontinfo lacks " + ", ".join(missing))

        order = font.lib.get("public.glyphOrder")
        if order is None:
            problems.append("lib has no public.glyphOrder")
        else:
            unlisted = sorted(set(default.keys()) - set(order))
            if unlisted:
                shown = ", ".join(repr(n) for n in unlisted[:10])
                more = f" and {len(unlisted) - 10} more" if len(unlisted) > 10 else ""
                problems.append(f"public.glyphOrder does not list {shown}{more}")

        contour_problems = []
        for name, recording in recordings.items():
            contour_problems += direction_problems(name, recording, outer_ccw=True)
        problems += capped(contour_problems, MAX_CONTOUR_REPORTS, "contour problems")
    except Exception as e:  # noqa: BLE001
        problems.append(f"check crashed: {e!r}")

    if os.environ.get("KAPPA_FONTMAKE") == "1":
        problems += fontmake_problems(path)
    return problems, glyph_count


def fontmake_problems(path):
    with tempfile.TemporaryDirectory() as tmp:
        command = [sys.executable, "-m", "fontmake", "-u", path, "-o", "ttf", "--output-dir", tmp]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            lines = [line for line in (result.stderr + result.stdout).splitlines() if line.strip()]
            errors = [line for line in lines if "error" in line.lower()] or lines[-5:]
            return [f"fontmake fails (exit {result.returncode}): " + " | ".join(errors[-5:])]
        built = sorted(f for f in os.listdir(tmp) if f.endswith(".ttf"))
        if not built:
            return ["fontmake wrote no .ttf"]
        problems = []
        for name in built:
            sub, _ = check_sfnt(os.path.join(tmp, name))
            problems += [f"fontmake's {name}: {p}" for p in sub]
        return problems


# ---------------------------------------------------------------------------------------------


def find_targets(root):
    targets = []
    for dirpath, dirnames, filenames in os.walk(root):
        for d in list(dirnames):
            if d.lower().endswith(".ufo"):
                targets.append(os.path.join(dirpath, d))
                dirnames.remove(d)
        dirnames.sort()
        for f in filenames:
            if f.lower().endswith((".ttf", ".otf")):
                targets.append(os.path.join(dirpath, f))
    return sorted(targets)


def main(argv):
    if len(argv) != 2:
        print("usage: check_fonts.py DIR", file=sys.stderr)
        return 2
    root = argv[1]
    if not os.path.isdir(root):
        print(f"{root}: not a directory: nothing to check")
        print("0 passed, 0 failed")
        return 1
    targets = find_targets(root)
    if not targets:
        print(f"{root}: no .ttf, .otf or .ufo: nothing to check")
        print("0 passed, 0 failed")
        return 1

    summary = []
    passed = failed = 0
    for path in targets:
        label = os.path.relpath(path, root)
        if path.lower().endswith(".ufo"):
            problems, glyphs = check_ufo(path)
        else:
            problems, glyphs = check_sfnt(path)
        for problem in problems:
            print(f"{label}: {problem}")
        glyph_text = "? glyphs" if glyphs is None else f"{glyphs} glyphs"
        if problems:
            failed += 1
            count = f"{len(problems)} problem" + ("s" if len(problems) > 1 else "")
            summary.append(f"FAIL  {label}  {glyph_text}, {count}")
        else:
            passed += 1
            summary.append(f"ok    {label}  {glyph_text}")
    for line in summary:
        print(line)
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
