"""External check of a UFO written by kappa: open it with ufoLib2 and read every glyph through
fontTools' pen protocol. Exits 77 (skipped) when those Python packages are not installed."""
import sys

try:
    import ufoLib2
    from fontTools.pens.recordingPen import RecordingPen
except ImportError:
    sys.exit(77)

font = ufoLib2.Font.open(sys.argv[1])
count = 0
for glyph in font:
    pen = RecordingPen()
    glyph.draw(pen)
    ops = [op for op, _ in pen.value]
    assert ops.count("closePath") == len(glyph.contours), glyph.name
    assert glyph.unicodes, glyph.name
    count += 1
print("units_per_em", font.info.unitsPerEm)
print("glyphs", count)
