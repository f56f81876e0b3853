"""ufo2ft filters by the names a UFO's lib declares them with (see ``kappa.ufo2ft``)."""
