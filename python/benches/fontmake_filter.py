"""What the kappa filter adds to a fontmake build: the same font built from a UFO whose
glyphs hold only κ sources (filter declared in its lib) and from a UFO holding the outlines
the filter computes (no κ source, no filter).

    python python/benches/fontmake_filter.py [--font tests/fonts/DejaVuSans.ttf] [--rounds 3]

The glyphs are the alphabet (A–Z, a–z, 0–9, &@ß) drafted from the font with
``kappa.draft_glyph``; both UFOs have the same glyphs, widths and font info. Each build is
``fontmake -u UFO -o ttf otf`` in a fresh process; the two builds alternate for
``--rounds`` pairs, and the median of the pairs' ratios is quoted (the machine's speed may
drift between pairs).
"""

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import ufoLib2
from fontTools.ttLib import TTFont

import kappa
from kappa.pen import draw_contours

ROOT = Path(__file__).resolve().parents[2]
ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789&@ß"
FILTERS = [{"namespace": "kappa.filters", "name": "kappa", "pre": True}]


def build_ufos(font_path: Path, out: Path):
    font = TTFont(font_path)
    glyphs = font.getGlyphSet()
    cmap = font.getBestCmap()
    upem = font["head"].unitsPerEm
    plain, source = ufoLib2.Font(), ufoLib2.Font()
    for ufo in (plain, source):
        ufo.info.familyName, ufo.info.styleName = "Kappa Bench", "Regular"
        ufo.info.unitsPerEm = upem
        ufo.info.ascender, ufo.info.descender = font["hhea"].ascent, font["hhea"].descent
    source.lib["com.github.googlei18n.ufo2ft.filters"] = FILTERS
    start = time.perf_counter()
    for ch in ALPHABET:
        name = cmap.get(ord(ch))
        if name is None:
            continue
        d = kappa.draft_glyph(glyphs[name], glyphs, units_per_em=upem)
        width = font["hmtx"][name][0]
        g = plain.newGlyph(name)
        g.unicodes, g.width = [ord(ch)], width
        # The outline the filter writes (its defaults: anchor nodes, tolerance in em).
        draw_contours(d.contours, g.getPointPen(), accuracy=1e-4 * upem, tolerance=4e-3 * upem)
        g = source.newGlyph(name)
        g.unicodes, g.width = [ord(ch)], width
        g.lib[kappa.KAPPA_LIB_KEY] = d.to_json()
    drafting = time.perf_counter() - start
    order = list(plain.keys())
    for ufo in (plain, source):
        ufo.lib["public.glyphOrder"] = order
    plain.save(out / "plain.ufo", overwrite=True)
    source.save(out / "kappa.ufo", overwrite=True)
    return len(order), drafting


def build(ufo: Path, out: Path) -> float:
    t = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "fontmake", "-u", str(ufo), "-o", "ttf", "otf", "--output-dir", str(out)],
        check=True, capture_output=True,
    )
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--font", type=Path, default=ROOT / "tests" / "fonts" / "DejaVuSans.ttf")
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        n, drafting = build_ufos(args.font, tmp)
        build(tmp / "plain.ufo", tmp / "plain")  # warm-up: imports, caches
        pairs = []
        for _ in range(args.rounds):
            pairs.append((build(tmp / "plain.ufo", tmp / "plain"), build(tmp / "kappa.ufo", tmp / "kappa")))
        plain = statistics.median(p for p, _ in pairs)
        source = statistics.median(k for _, k in pairs)
        ratio = statistics.median(k / p for p, k in pairs)
        print(f"{n} glyphs drafted from {args.font.name} in {drafting:.2f} s")
        print(f"fontmake -o ttf otf, median of {args.rounds}: outlines {plain:.2f} s, "
              f"κ sources + filter {source:.2f} s; the filter adds {(ratio - 1) * 100:+.1f} %")


if __name__ == "__main__":
    main()
