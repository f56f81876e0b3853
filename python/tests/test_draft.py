"""Drafting κ contours from fontTools glyphs (`kappa.draft_glyph`): the same κ sources as
`kappa font` writes, bit for bit, within the tolerance of the original outline, and SVG
input (`kappa.contours_from_svg`)."""

import math

import pytest

pytest.importorskip("ufoLib2")

import ufoLib2  # noqa: E402
from fontTools.pens.recordingPen import DecomposingRecordingPen, RecordingPen  # noqa: E402
from fontTools.ttLib import TTFont  # noqa: E402

import kappa  # noqa: E402

from conftest import ROOT  # noqa: E402
from test_fontmake import samples  # noqa: E402

DEJAVU = ROOT / "tests" / "fonts" / "DejaVuSans.ttf"
GARAMOND = ROOT / "tests" / "fonts" / "EBGaramond12-Regular-subset.otf"
CHARS = "oa&S"


def hausdorff(a, b, cell=8.0):
    """Hausdorff distance of two outlines (elements), as far as it is below `cell`: samples
    of each (8 per segment, more on long ones) against the chords through the other's
    samples, found through a grid of `cell`-sized buckets; inf beyond."""

    def chords_and_points(elements):
        dense = samples(elements, 8)
        out = [dense[0]]
        for p0, p1 in zip(dense, dense[1:]):
            if p0 is None or p1 is None:
                out.append(p1)
                continue
            n = max(1, math.ceil(math.dist(p0, p1) / 2.0))
            out += [(p0[0] + (p1[0] - p0[0]) * k / n, p0[1] + (p1[1] - p0[1]) * k / n) for k in range(1, n + 1)]
        return out

    def one_way(pa, pb):
        grid = {}
        for p0, p1 in zip(pb, pb[1:]):
            if p0 is None or p1 is None:
                continue
            for key in {(math.floor(p[0] / cell), math.floor(p[1] / cell)) for p in (p0, p1)}:
                grid.setdefault(key, []).append((p0, p1))
        worst = 0.0
        for x in pa:
            if x is None:
                continue
            cx, cy = math.floor(x[0] / cell), math.floor(x[1] / cell)
            best = math.inf
            for i in (-1, 0, 1):
                for j in (-1, 0, 1):
                    for p0, p1 in grid.get((cx + i, cy + j), ()):
                        dx, dy = p1[0] - p0[0], p1[1] - p0[1]
                        n = dx * dx + dy * dy
                        t = 0.0 if n == 0 else max(0.0, min(1.0, ((x[0] - p0[0]) * dx + (x[1] - p0[1]) * dy) / n))
                        best = min(best, math.hypot(x[0] - p0[0] - t * dx, x[1] - p0[1] - t * dy))
            worst = max(worst, best if best <= cell else math.inf)
        return worst

    pa, pb = chords_and_points(a), chords_and_points(b)
    return max(one_way(pa, pb), one_way(pb, pa))


def glyph_names(font, chars):
    cmap = font.getBestCmap()
    return [cmap[ord(c)] for c in chars if ord(c) in cmap]


@pytest.mark.parametrize("path", [DEJAVU, GARAMOND], ids=["truetype", "cff"])
def test_same_sources_as_kappa_font(kappa_cli, tmp_path, path):
    font = TTFont(path)
    names = glyph_names(font, CHARS)
    assert names
    ufo = tmp_path / "out.ufo"
    r = kappa_cli("font", "--font", str(path), "--chars", CHARS, "--out", str(ufo))
    assert r.returncode == 0, r.stderr
    written = ufoLib2.Font.open(ufo)
    glyphs = font.getGlyphSet()
    upem = font["head"].unitsPerEm
    for name in names:
        d = kappa.draft_glyph(glyphs[name], glyphs, units_per_em=upem)
        assert d.to_json() == written[name].lib[kappa.KAPPA_LIB_KEY], name


@pytest.mark.parametrize("scheme,shape", [("kappa", None), ("ek-cubic", "auto"), ("ek-trig", 0.7)])
def test_draft_is_within_tolerance_of_the_original(scheme, shape):
    font = TTFont(DEJAVU)
    glyphs = font.getGlyphSet()
    upem = font["head"].unitsPerEm
    for name in glyph_names(font, CHARS):
        d = kappa.draft_glyph(glyphs[name], glyphs, units_per_em=upem, scheme=scheme, shape=shape)
        assert len(d) == len(d.contours) >= 1
        assert d.fallbacks == 0 and d.within_tolerance, (name, d)
        assert 0 < d.hausdorff <= 0.004 * upem
        assert 0 < d.anchors and d.original_on_curve > 0
        for c in d.contours:
            assert c.scheme == scheme and not c.errors
        original = RecordingPen()
        glyphs[name].draw(original)
        drafted = kappa.glyph_elements(d.contours, None, "joints")
        # Measured independently (sampled both ways); the contours' pieces keep their
        # corners, so the whole outline is as near as its worst piece.
        assert hausdorff(original.value, drafted, 0.004 * upem * 1.5) <= 0.004 * upem * 1.01, name
        # The κ source reads back as the same contours.
        again = kappa.contours_from_json(d.to_json())
        assert [c.to_json() for c in again] == [c.to_json() for c in d.contours]


def test_inputs_elements_ufo_glyphs_and_components(tmp_path):
    font = TTFont(DEJAVU)
    glyphs = font.getGlyphSet()
    upem = font["head"].unitsPerEm
    rec = RecordingPen()
    glyphs["o"].draw(rec)
    by_glyph = kappa.draft_glyph(glyphs["o"], units_per_em=upem)
    by_elements = kappa.draft_glyph(rec.value, units_per_em=upem)
    assert by_glyph.to_json() == by_elements.to_json()
    # A composite (Aacute: A and acute) is decomposed through the glyph set.
    name = font.getBestCmap()[0xC1]
    assert font["glyf"][name].isComposite()
    flat = DecomposingRecordingPen(glyphs)
    glyphs[name].draw(flat)
    d = kappa.draft_glyph(glyphs[name], glyphs, units_per_em=upem)
    assert d.to_json() == kappa.draft_glyph(flat.value, units_per_em=upem).to_json()
    assert len(d.contours) == 3
    # A ufoLib2 glyph with cubics.
    ufo = ufoLib2.Font()
    g = ufo.newGlyph("c")
    pen = g.getPen()
    r, k = 300, 300 * 0.5523
    pen.moveTo((r, 0))
    pen.curveTo((r, k), (k, r), (0, r))
    pen.curveTo((-k, r), (-r, k), (-r, 0))
    pen.curveTo((-r, -k), (-k, -r), (0, -r))
    pen.curveTo((k, -r), (r, -k), (r, 0))
    pen.closePath()
    d = kappa.draft_glyph(g, ufo, units_per_em=1000)
    assert d.within_tolerance and d.hausdorff <= 4.0
    for x, y in d.contours[0].points:
        assert abs(math.hypot(x, y) - r) < 0.5


def test_bad_outlines():
    with pytest.raises(ValueError, match="element 1"):
        kappa.draft_elements([("moveTo", ((0, 0),)), ("curveTo", ((1, 1),)), ("closePath", ())])
    with pytest.raises(ValueError):
        kappa.draft_elements([("lineTo", ((0, 0),))])
    with pytest.raises(TypeError):
        kappa.draft_elements([("moveTo", 5)])
    with pytest.raises(kappa.NonFinitePointError):
        kappa.draft_elements([("moveTo", ((0, 0),)), ("lineTo", ((math.nan, 1),)), ("lineTo", ((5, 9),)),
                              ("closePath", ())])
    with pytest.raises(ValueError, match="κ-curves have none"):
        kappa.draft_elements([("moveTo", ((0, 0),))], 1000.0, "kappa", 0.8)
    with pytest.raises(ValueError):
        kappa.draft_elements([("moveTo", ((0, 0),))], 1000.0, "ek-cubic", "sharp")
    # An empty outline drafts to no contour.
    assert len(kappa.draft_elements([])) == 0


def test_contours_from_svg():
    svg = """<svg xmlns="http://www.w3.org/2000/svg">
      <g transform="translate(100 0)"><path d="M0 0 C 30 -10 60 10 90 0 L 90 50 Z"/></g>
      <polyline points="0,0 10,5 20,0 30,5"/></svg>"""
    closed, wave = kappa.contours_from_svg(svg, "ek-cubic")
    assert closed.closed and not wave.closed
    assert closed.points == [(100, 0), (190, 0), (190, 50)]
    assert closed.corners[1] and closed.scheme == "ek-cubic"
    assert wave.points == [(0, 0), (10, 5), (20, 0), (30, 5)]
    assert not wave.errors
