"""Variable fonts from κ masters: two master UFOs whose glyphs hold κ sources of the same
structure → fontmake -o variable with the kappa filter in "compatible" node mode → a
variable TTF that OpenType Sanitizer accepts, whose extreme instances are the masters'
computed outlines, and whose middle instance is near the κ-curve of the middle parameters."""

import importlib.util
import math

import pytest

pytest.importorskip("fontmake")
pytest.importorskip("ufoLib2")
ots = pytest.importorskip("ots")

import ufoLib2  # noqa: E402
from fontTools.pens.recordingPen import RecordingPen  # noqa: E402
from fontTools.ttLib import TTFont  # noqa: E402
from fontTools.varLib.instancer import instantiateVariableFont  # noqa: E402

import kappa  # noqa: E402
from kappa.ufo2ft import KappaFilter  # noqa: E402

from conftest import PYTHON_DIR  # noqa: E402
from test_fontmake import hausdorff  # noqa: E402

spec = importlib.util.spec_from_file_location("variable", PYTHON_DIR / "examples" / "variable.py")
variable = importlib.util.module_from_spec(spec)
spec.loader.exec_module(variable)

#: The integer grid (half a unit diagonally) plus cu2qu's error (1 unit) in TrueType.
GRID_AND_CU2QU = 1.0 + 0.5 * math.sqrt(2)


def computed(make, bold):
    """The glyph's outline as the library computes it for boldness `bold` (0…1)."""
    return kappa.glyph_elements(make(bold), "postscript", "compatible")


def kinds(elements):
    return [(op, len(args)) for op, args in elements]


@pytest.fixture(scope="module")
def vf(tmp_path_factory):
    out = tmp_path_factory.mktemp("variable")
    return variable.build_variable(variable.build_designspace(out), out)


def test_variable_font_passes_ots(vf):
    r = ots.sanitize(str(vf), "/dev/null", capture_output=True)
    assert r.returncode == 0, r.stderr
    font = TTFont(vf)
    assert "gvar" in font and "fvar" in font
    assert [a.axisTag for a in font["fvar"].axes] == ["wght"]


def test_masters_have_the_same_structure():
    for _, _, _, make in variable.GLYPHS:
        assert kinds(computed(make, 0.0)) == kinds(computed(make, 1.0))
    # The filter in "compatible" mode writes that outline exactly.
    for style in variable.WEIGHTS:
        font = ufoLib2.Font()
        for name, _, _, make in variable.GLYPHS:
            glyph = font.newGlyph(name)
            glyph.lib[kappa.KAPPA_LIB_KEY] = "[" + ",".join(c.to_json() for c in make(0.5)) + "]"
        KappaFilter(nodes="compatible")(font)
        for name, _, _, make in variable.GLYPHS:
            rec = RecordingPen()
            font[name].draw(rec)
            assert rec.value == computed(make, 0.5), name


@pytest.mark.parametrize("style", ["Light", "Bold"])
def test_extreme_instances_are_the_masters_outlines(vf, style):
    weight = variable.WEIGHTS[style]
    bold = 0.0 if style == "Light" else 1.0
    inst = instantiateVariableFont(TTFont(vf), {"wght": weight})
    glyphs = inst.getGlyphSet()
    for name, _, _, make in variable.GLYPHS:
        rec = RecordingPen()
        glyphs[name].draw(rec)
        d = hausdorff(rec.value, computed(make, bold))
        assert d <= GRID_AND_CU2QU, (style, name, d)


def test_middle_instance_is_near_the_kappa_curve_of_the_middle_parameters(vf):
    # The instance interpolates the masters' outlines point by point; the κ-curve of the
    # interpolated points and shapes is another curve. Measured here, and bounded.
    inst = instantiateVariableFont(TTFont(vf), {"wght": 500})
    glyphs = inst.getGlyphSet()
    worst = 0.0
    for name, _, _, make in variable.GLYPHS:
        rec = RecordingPen()
        glyphs[name].draw(rec)
        d = hausdorff(rec.value, computed(make, 0.5))
        print(f"{name}: middle instance to the κ-curve of the middle parameters: {d:.2f} units")
        worst = max(worst, d)
    assert worst <= 8.0, worst
