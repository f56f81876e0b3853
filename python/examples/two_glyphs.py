"""Builds a two-glyph font from κ sources: a UFO whose glyphs hold only κ contours in their
lib (under "org.kappa.contours"), then fontmake with the kappa filter → TTF and OTF.

    python examples/two_glyphs.py [OUT_DIR]

Needs ufoLib2 and fontmake (``pip install ufoLib2 fontmake``) besides kappa.
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import ufoLib2

import kappa


def glyph_o():
    """An "o": an εκ-cubic outer contour and a κ counter (two closed contours, no corners)."""
    outer = kappa.Contour(
        [(300, -12), (540, 250), (300, 512), (60, 250)],
        True,
        "ek-cubic",
        shapes=0.8,
        tangents=[(1, 0), (0, 1), (-1, 0), (0, -1)],
    )
    inner = kappa.Contour([(300, 76), (450, 250), (300, 424), (150, 250)], True, "kappa")
    return [outer, inner]


def glyph_d():
    """A "D": a stem and two bars between corners, and a bowl that leaves the bars
    tangentially (smooth joins: corners with the tangent on the curve's side along the bar)
    with its right extremum held vertical."""

    def contour(left, right, bottom, top, bowl):
        # The bowl: a half ellipse from the top bar to the bottom one, a point every 30°.
        cy, rx, ry = (bottom + top) / 2, right - bowl, (top - bottom) / 2
        arc = [
            (round(bowl + rx * math.cos(math.radians(a)), 2), round(cy + ry * math.sin(math.radians(a)), 2))
            for a in (90, 60, 30, 0, -30, -60, -90)
        ]
        n = 2 + len(arc)
        tangents = [None] * n
        tangents[2] = (1, 0)  # leaves the top bar along it
        tangents[5] = (0, -1)  # the right extremum, vertical
        tangents_in = [None] * n
        tangents_in[n - 1] = (-1, 0)  # arrives at the bottom bar along it
        return kappa.Contour(
            [(left, bottom), (left, top)] + arc,
            True,
            "ek-cubic",
            shapes=0.75,
            corners=[True, True, True] + [False] * (len(arc) - 2) + [True],
            tangents=tangents,
            tangents_in=tangents_in,
        )

    return [contour(80, 580, 0, 700, 300), contour(170, 490, 90, 610, 290)]


def build_ufo(path: Path) -> Path:
    """Writes the κ-source UFO: glyphs "o" and "D" with κ contours in their lib only."""
    ufo = ufoLib2.Font()
    info = ufo.info
    info.familyName, info.styleName = "Kappa Two", "Regular"
    info.unitsPerEm, info.ascender, info.descender = 1000, 750, -250
    info.xHeight, info.capHeight = 500, 700
    for name, code, width, contours in [
        ("o", 0x6F, 600, glyph_o()),
        ("D", 0x44, 640, glyph_d()),
    ]:
        glyph = ufo.newGlyph(name)
        glyph.unicodes = [code]
        glyph.width = width
        docs = [json.loads(c.to_json()) for c in contours]
        glyph.lib[kappa.KAPPA_LIB_KEY] = json.dumps(docs)
    ufo.lib["public.glyphOrder"] = ["o", "D"]
    ufo.save(path, overwrite=True)
    return path


def build_fonts(ufo: Path, out_dir: Path) -> list:
    """fontmake with the kappa filter: a TTF and an OTF in ``out_dir``."""
    subprocess.run(
        [
            sys.executable, "-m", "fontmake",
            "-u", str(ufo),
            "--filter", "kappa.ufo2ft::KappaFilter",
            "-o", "ttf", "otf",
            "--output-dir", str(out_dir),
        ],
        check=True,
    )
    return sorted(out_dir.glob("*.[ot]tf"))


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "kappa-two")
    out.mkdir(parents=True, exist_ok=True)
    ufo = build_ufo(out / "KappaTwo-Regular.ufo")
    for font in build_fonts(ufo, out):
        print(font)
