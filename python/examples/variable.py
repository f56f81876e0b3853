"""Builds a variable font from κ masters: two UFOs (Light and Bold) whose glyphs hold only
κ contours of the same structure, a designspace with a weight axis, then fontmake with the
kappa filter in "compatible" node mode → a variable TTF.

    python examples/variable.py [OUT_DIR]

Needs ufoLib2, fontTools and fontmake (``pip install ufoLib2 fontmake``) besides kappa.

The two masters of each glyph have the same points in the same order, with the same
corners, tangent flags and closed flags; only positions, shapes and tangent directions
differ. ``nodes="compatible"`` then gives both the same outline structure (nodes at every κ
point and every joint), so fontmake can interpolate them.
"""

import json
import subprocess
import sys
from pathlib import Path

import ufoLib2
from fontTools.designspaceLib import AxisDescriptor, DesignSpaceDocument, SourceDescriptor

import kappa

#: The weight axis: the Light master at its minimum (the default), Bold at its maximum.
WEIGHTS = {"Light": 300, "Bold": 700}

#: The filter, declared in each master's lib so that a plain fontmake run applies it.
FILTERS = [{"namespace": "kappa.filters", "name": "kappa", "pre": True, "kwargs": {"nodes": "compatible"}}]


def glyph_o(bold: float):
    """An "o" at boldness 0…1: an εκ-cubic outer contour held at its extrema and a κ counter
    that narrows as the weight grows."""
    w = 240 + 20 * bold
    outer = kappa.Contour(
        [(300, -12), (300 + w, 250), (300, 512), (300 - w, 250)],
        True,
        "ek-cubic",
        shapes=0.78 + 0.08 * bold,
        tangents=[(1, 0), (0, 1), (-1, 0), (0, -1)],
    )
    cw, ch = 150 - 70 * bold, 174 - 24 * bold
    inner = kappa.Contour(
        [(300, 250 - ch), (300 + cw, 250), (300, 250 + ch), (300 - cw, 250)], True, "kappa"
    )
    return [outer, inner]


def glyph_d(bold: float):
    """A "D" at boldness 0…1: a stem between corners and a bowl of five points; the counter
    shrinks as the stem and the bowl thicken."""
    stem, bowl = 60 + 90 * bold, 60 + 80 * bold

    def contour(left, right, bottom, top):
        cy, ry = (bottom + top) / 2, (top - bottom) / 2
        return kappa.Contour(
            [(left, bottom), (left, top), (left + 0.55 * (right - left), top),
             (right, cy + 0.45 * ry), (right, cy - 0.45 * ry), (left + 0.55 * (right - left), bottom)],
            True,
            "ek-cubic",
            shapes=0.75,
            corners=[True, True, False, False, False, False],
        )

    return [contour(80, 580, 0, 700), contour(80 + stem, 580 - bowl, 0 + 0.7 * stem, 700 - 0.7 * stem)]


GLYPHS = [("o", 0x6F, 600, glyph_o), ("D", 0x44, 640, glyph_d)]


def build_master(path: Path, style: str) -> Path:
    """One master UFO: every glyph holds only its κ contours (in its lib)."""
    bold = (WEIGHTS[style] - WEIGHTS["Light"]) / (WEIGHTS["Bold"] - WEIGHTS["Light"])
    ufo = ufoLib2.Font()
    info = ufo.info
    info.familyName, info.styleName = "Kappa Variable", style
    info.unitsPerEm, info.ascender, info.descender = 1000, 750, -250
    info.xHeight, info.capHeight = 500, 700
    for name, code, width, make in GLYPHS:
        glyph = ufo.newGlyph(name)
        glyph.unicodes = [code]
        glyph.width = width
        glyph.lib[kappa.KAPPA_LIB_KEY] = json.dumps([json.loads(c.to_json()) for c in make(bold)])
    ufo.lib["public.glyphOrder"] = [g[0] for g in GLYPHS]
    ufo.lib["com.github.googlei18n.ufo2ft.filters"] = FILTERS
    ufo.save(path, overwrite=True)
    return path


def build_designspace(out: Path) -> Path:
    """The two masters and a designspace with one weight axis."""
    doc = DesignSpaceDocument()
    axis = AxisDescriptor()
    axis.tag, axis.name = "wght", "Weight"
    axis.minimum, axis.default, axis.maximum = WEIGHTS["Light"], WEIGHTS["Light"], WEIGHTS["Bold"]
    doc.addAxis(axis)
    for style, weight in WEIGHTS.items():
        source = SourceDescriptor()
        source.path = str(build_master(out / f"KappaVariable-{style}.ufo", style))
        source.familyName, source.styleName = "Kappa Variable", style
        source.location = {"Weight": weight}
        doc.addSource(source)
    path = out / "KappaVariable.designspace"
    doc.write(path)
    return path


def build_variable(designspace: Path, out_dir: Path) -> Path:
    """fontmake → a variable TTF in ``out_dir``."""
    subprocess.run(
        [sys.executable, "-m", "fontmake", "-m", str(designspace), "-o", "variable", "--output-dir", str(out_dir)],
        check=True,
    )
    (font,) = out_dir.glob("*.ttf")
    return font


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "kappa-variable")
    out.mkdir(parents=True, exist_ok=True)
    print(build_variable(build_designspace(out), out))
