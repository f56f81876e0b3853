#!/usr/bin/env python3
"""The font-quality targets on the alphabet `kappa font` drafted in DIR (the test
`the_alphabet_is_drafted_for_the_quality_check` writes dejavu.ttf/.ufo and garamond.ttf/.ufo
there), measured by `tools/font_report.py`, independently of kappa:

- at least 97 % of the glyphs within 0.004 em of the source;
- at least 90 % of the source's axis-aligned extremum nodes kept as nodes on their axis;
- no more segments missing an extremum than the source has;
- no curve segment shorter than 2 units;
- smooth source joins written smooth: at most 3 % of those matched by an output node turn
  by more than 0.5 degrees (the integer grid of a .ttf turns some joins with short handles;
  before its smooth-node pass, 5 % of Garamond's turned).

    python tests/check_font_quality.py DIR
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))

import font_report  # noqa: E402

SOURCES = {
    "dejavu": os.path.join(HERE, "fonts", "DejaVuSans.ttf"),
    "garamond": os.path.join(HERE, "fonts", "EBGaramond12-Regular-subset.otf"),
}
ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789&@ß"


def check(source, output):
    src, out = font_report.Source(source), font_report.Source(output)
    within = kept = nodes = missing_src = missing_out = short = glyphs = 0
    smooth = kinked = 0
    for ch in ALPHABET:
        name = src.cmap.get(ord(ch))
        if name is None:
            continue
        a = font_report.Outline(src.contours(name))
        b = font_report.Outline(out.contours(name))
        row = font_report.compare(a, b, src.upem)
        glyphs += 1
        within += row["within"]
        nodes += row["extremum_nodes"]
        kept += row["extremum_kept"]
        missing_src += row["missing_extrema"]["source"]
        missing_out += row["missing_extrema"]["output"]
        short += row["short_segments"]["output"]
        smooth += row["smooth_joins"]["matched"]
        kinked += row["smooth_joins"]["over"]
    problems = []
    if within < 0.97 * glyphs:
        problems.append(f"{within}/{glyphs} glyphs within 0.004 em (< 97 %)")
    if kept < 0.9 * nodes:
        problems.append(f"{kept}/{nodes} extremum nodes kept (< 90 %)")
    if missing_out > missing_src:
        problems.append(f"{missing_out} segments miss an extremum (source {missing_src})")
    if short:
        problems.append(f"{short} curve segments shorter than 2 units")
    if kinked > 0.03 * smooth:
        problems.append(f"{kinked}/{smooth} smooth joins turn by more than 0.5 degrees (> 3 %)")
    summary = (f"{within}/{glyphs} within, extremum nodes {kept}/{nodes}, missing extrema "
               f"{missing_src} -> {missing_out}, short segments {short}, "
               f"kinked smooth joins {kinked}/{smooth}")
    return problems, summary


def main(argv):
    if len(argv) != 2:
        print("usage: check_font_quality.py DIR", file=sys.stderr)
        return 2
    failed = 0
    for name, source in SOURCES.items():
        for ext in (".ttf", ".ufo"):
            output = os.path.join(argv[1], name + ext)
            if not os.path.exists(output):
                print(f"FAIL  {name}{ext}: not written")
                failed += 1
                continue
            problems, summary = check(source, output)
            for p in problems:
                print(f"{name}{ext}: {p}")
            print(("FAIL  " if problems else "ok    ") + f"{name}{ext}  {summary}")
            failed += bool(problems)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
