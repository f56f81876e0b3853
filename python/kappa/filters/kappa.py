"""``KappaFilter`` where ufo2ft looks for it when a UFO's lib declares
``{"namespace": "kappa.filters", "name": "kappa", "pre": true}``."""

from ..ufo2ft import KappaFilter

__all__ = ["KappaFilter"]
