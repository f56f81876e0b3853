"""End to end: a UFO whose two glyphs hold only κ sources → fontmake with the kappa filter →
a TTF and an OTF that OpenType Sanitizer accepts, with the outlines the library computes."""

import importlib.util
import math
import subprocess
import sys

import pytest

pytest.importorskip("fontmake")
pytest.importorskip("ufoLib2")
ots = pytest.importorskip("ots")

import ufoLib2  # noqa: E402
from fontTools.pens.areaPen import AreaPen  # noqa: E402
from fontTools.pens.recordingPen import RecordingPen  # noqa: E402
from fontTools.ttLib import TTFont  # noqa: E402

import kappa  # noqa: E402
from kappa.ufo2ft import DEFAULT_ACCURACY, DEFAULT_TOLERANCE, KappaFilter  # noqa: E402

from conftest import PYTHON_DIR  # noqa: E402

spec = importlib.util.spec_from_file_location("two_glyphs", PYTHON_DIR / "examples" / "two_glyphs.py")
two_glyphs = importlib.util.module_from_spec(spec)
spec.loader.exec_module(two_glyphs)

UPEM = 1000


def expected(name, nodes="anchors"):
    """The glyph's outline as the library computes it from its κ source."""
    contours = {"o": two_glyphs.glyph_o, "D": two_glyphs.glyph_d}[name]()
    return kappa.glyph_elements(
        contours, "postscript", nodes,
        accuracy=DEFAULT_ACCURACY * UPEM, tolerance=DEFAULT_TOLERANCE * UPEM,
    )


def samples(elements, per_segment=48):
    """Points along the outline, `per_segment` per segment (qCurveTo runs split as
    TrueType implies)."""
    pts, cur, start = [], None, None
    for op, args in elements:
        if op == "moveTo":
            cur = start = args[0]
            if pts:
                pts.append(None)  # no chord between contours
        elif op == "lineTo":
            pts += _bez([cur, args[0]], per_segment)
            cur = args[0]
        elif op == "curveTo":
            pts += _bez([cur, *args], per_segment)
            cur = args[-1]
        elif op == "qCurveTo":
            offs, end = list(args[:-1]), args[-1]
            if end is None:  # all off-curve contour
                end = offs[0]
            for i, off in enumerate(offs):
                on = end if i == len(offs) - 1 else ((off[0] + offs[i + 1][0]) / 2, (off[1] + offs[i + 1][1]) / 2)
                pts += _bez([cur, off, on], per_segment)
                cur = on
        elif op == "closePath" and cur != start:
            pts += _bez([cur, start], per_segment)
            cur = start
    return pts


def _bez(ctrl, n):
    out = []
    for i in range(n + 1):
        t = i / n
        c = list(ctrl)
        while len(c) > 1:
            c = [((1 - t) * a[0] + t * b[0], (1 - t) * a[1] + t * b[1]) for a, b in zip(c, c[1:])]
        out.append(c[0])
    return out


def hausdorff(a, b):
    """Hausdorff distance between two outlines (elements): samples of each against the
    polyline through the other's samples (chords of 1/48 of a segment: their sagitta is far
    below the bounds tested)."""
    pa, pb = samples(a), samples(b)

    def to_polyline(x, q):
        best = math.inf
        for p0, p1 in zip(q, q[1:]):
            if p0 is None or p1 is None:
                continue
            dx, dy = p1[0] - p0[0], p1[1] - p0[1]
            n = dx * dx + dy * dy
            t = 0.0 if n == 0 else max(0.0, min(1.0, ((x[0] - p0[0]) * dx + (x[1] - p0[1]) * dy) / n))
            best = min(best, math.hypot(x[0] - p0[0] - t * dx, x[1] - p0[1] - t * dy))
        return best

    return max(
        max(to_polyline(x, pb) for x in pa if x is not None),
        max(to_polyline(x, pa) for x in pb if x is not None),
    )


@pytest.fixture(scope="module")
def fonts(tmp_path_factory):
    out = tmp_path_factory.mktemp("two")
    ufo = two_glyphs.build_ufo(out / "KappaTwo-Regular.ufo")
    built = two_glyphs.build_fonts(ufo, out)
    return ufo, {p.suffix: p for p in built}


def test_ufo_holds_only_kappa_sources(fonts):
    ufo, _ = fonts
    font = ufoLib2.Font.open(ufo)
    for name in ("o", "D"):
        assert len(font[name].contours) == 0
        assert kappa.KAPPA_LIB_KEY in font[name].lib


def test_fonts_pass_ots(fonts):
    _, built = fonts
    assert set(built) == {".ttf", ".otf"}
    for path in built.values():
        r = ots.sanitize(str(path), "/dev/null", capture_output=True)
        assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("suffix,bound", [(".otf", 0.5 * math.sqrt(2) + 1e-6), (".ttf", 1.0 + 0.5 * math.sqrt(2))])
def test_font_outlines_are_the_computed_ones(fonts, suffix, bound):
    # OTF: only the integer grid (half a unit diagonally); TTF: cu2qu's 1 unit besides.
    _, built = fonts
    font = TTFont(built[suffix])
    glyphs = font.getGlyphSet()
    for name in ("o", "D"):
        rec = RecordingPen()
        glyphs[name].draw(rec)
        assert hausdorff(rec.value, expected(name)) <= bound, name
        area = AreaPen(glyphs)
        glyphs[name].draw(area)
        # Outer contours counter-clockwise in CFF, clockwise in TrueType (y up).
        assert (area.value > 0) == (suffix == ".otf"), (name, area.value)


def test_filter_output_is_the_library_output_exactly(fonts):
    ufo, _ = fonts
    font = ufoLib2.Font.open(ufo)
    for nodes in ("anchors", "joints"):
        f = ufoLib2.Font.open(ufo)
        modified = KappaFilter(nodes=nodes)(f)
        assert modified == {"o", "D"}
        for name in ("o", "D"):
            rec = RecordingPen()
            f[name].draw(rec)
            assert rec.value == expected(name, nodes), (nodes, name)
    # Glyphs without a κ source are left alone.
    assert KappaFilter()(font, {"x": ufoLib2.objects.Glyph("x")}) == set()


def test_filter_declared_in_the_ufo_lib(fonts, tmp_path):
    ufo, built = fonts
    font = ufoLib2.Font.open(ufo)
    font.lib["com.github.googlei18n.ufo2ft.filters"] = [
        {"namespace": "kappa.filters", "name": "kappa", "pre": True}
    ]
    path = tmp_path / "Declared.ufo"
    font.save(path)
    subprocess.run(
        [sys.executable, "-m", "fontmake", "-u", str(path), "-o", "otf", "--output-dir", str(tmp_path)],
        check=True, capture_output=True,
    )
    (otf,) = tmp_path.glob("*.otf")
    a, b = RecordingPen(), RecordingPen()
    TTFont(otf).getGlyphSet()["D"].draw(a)
    TTFont(built[".otf"]).getGlyphSet()["D"].draw(b)
    assert a.value == b.value


def test_unconverged_source_fails_the_build_with_its_glyph_named():
    font = ufoLib2.Font()
    glyph = font.newGlyph("bad")
    c = kappa.Contour([(0, 0), (50, 0), (50, 0), (0, 50)], True, corners=[True, False, False, True])
    glyph.lib[kappa.KAPPA_LIB_KEY] = "[" + c.to_json() + "]"
    with pytest.raises(kappa.RepeatedPointError, match="glyph 'bad': points 1 and 2 coincide"):
        KappaFilter()(font)
