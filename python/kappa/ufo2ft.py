"""A ufo2ft filter that builds glyph outlines from κ sources.

A glyph whose lib holds a κ source under "org.kappa.contours" (a JSON list of path-tool
documents, one per contour, as ``kappa font`` writes it into UFO sources) gets its
contours replaced by the computed outline of those documents; its components, anchors,
width and other data stay. Other glyphs are left alone. Contours run the PostScript way
(outer counter-clockwise), as UFO sources do; ufo2ft reverses them for TrueType.

With fontmake::

    fontmake -u Font.ufo --filter "kappa.ufo2ft::KappaFilter" -o ttf otf

or declared in the UFO's lib, under ``com.github.googlei18n.ufo2ft.filters``:
``[{"namespace": "kappa.filters", "name": "kappa", "pre": true}]`` (then a plain
``fontmake -u Font.ufo`` applies it; "pre" must be given there, as ufo2ft defaults it to
false for filters declared in a lib).

Options (``KappaFilter(nodes="joints")`` on the command line):

- ``nodes``: "anchors" (default: the κ points are the on-curve nodes, as ``kappa font``
  writes UFO outlines; each span between two of them is one cubic where that cubic is
  within ``tolerance / 2``, else cubics within ``accuracy``) or "joints" (the exact curve,
  its nodes the joints between segments: κ quadratics, εκ-cubic cubics, εκ-trig fitted)
  or "compatible" (nodes at the κ points and the joints, in a structure fixed by the
  number of points, the corners and the closed flag: the masters of a variable font whose
  κ sources have the same structure give point-compatible outlines; declare it with
  ``"kwargs": {"nodes": "compatible"}`` in each master's lib).
- ``accuracy``, ``tolerance``: in em (default 1e-4 and 4e-3, ``kappa font``'s drafting
  tolerance: a span is one cubic where that is within 2 units of a 1000-unit em, else
  cubics within 0.1 units).
- ``acceptUnconverged``: draw a piece's best curve when its solve did not converge
  (default: fail the build with NotConvergedError).

The filter runs before ufo2ft's own filters (decomposition, overlap removal, cu2qu).
"""

from __future__ import annotations

from functools import lru_cache

from ufo2ft.filters import BaseFilter

from ._kappa import KAPPA_LIB_KEY, KappaError, contours_from_json, glyph_elements
from .pen import replay

__all__ = ["KappaFilter", "KAPPA_LIB_KEY"]

#: Anchor-node accuracy where a span needs several cubics, in em.
DEFAULT_ACCURACY = 1e-4
#: Anchor-node tolerance: a span is one cubic where that is within half of it, in em.
DEFAULT_TOLERANCE = 4e-3


@lru_cache(maxsize=4096)
def _outline(source: str, nodes: str, accuracy: float, tolerance: float, accept: bool) -> tuple:
    """The computed outline of a κ source, cached: fontmake runs the filter once per output
    format (``-o ttf otf``) on the same sources."""
    contours = contours_from_json(source)
    return tuple(
        glyph_elements(
            contours,
            direction="postscript",
            nodes=nodes,
            accuracy=accuracy,
            tolerance=tolerance,
            accept_unconverged=accept,
        )
    )


class KappaFilter(BaseFilter):
    """Replaces the contours of every glyph that has a κ source with its computed outline."""

    _kwargs = {
        "nodes": "anchors",
        "accuracy": DEFAULT_ACCURACY,
        "tolerance": DEFAULT_TOLERANCE,
        "acceptUnconverged": False,
    }
    _pre = True

    def set_context(self, font, glyphSet):
        ctx = super().set_context(font, glyphSet)
        upem = getattr(getattr(font, "info", None), "unitsPerEm", None) or 1000
        ctx.accuracy = float(self.options.accuracy) * float(upem)
        ctx.tolerance = float(self.options.tolerance) * float(upem)
        return ctx

    def filter(self, glyph) -> bool:
        source = glyph.lib.get(KAPPA_LIB_KEY)
        if not source:
            return False
        try:
            elements = _outline(
                source,
                self.options.nodes,
                self.context.accuracy,
                self.context.tolerance,
                bool(self.options.acceptUnconverged),
            )
        except KappaError as e:
            raise type(e)(f"glyph {glyph.name!r}: {e}") from e
        glyph.clearContours()
        replay(elements, glyph.getPen())
        return True
