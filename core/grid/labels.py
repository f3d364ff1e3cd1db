"""Coordinates printed on a sheet, parsed from the words read in its margins (:mod:`hamta.core.grid.ocr`).

A label is an angle (a graticule's degrees, minutes, seconds or decimal minutes, with a hemisphere letter before
or after: ``48°07'``, ``N 44°27'``, ``156°59'30"W``, ``45N``, ``59.5'``, minutes or seconds alone between full
labels: ``07'``, ``15"``) or a number of a grid's linear unit (metres, feet, yards: ``503000``, ``5 540 000``,
abbreviated ``85`` whose leading digits a full label of the same edge gives). Words printed apart that make one
label (``91°`` beside ``48'``, ``20°`` above ``47'``, ``47'`` above ``15"``) are joined. What the engine may
confuse (a prime read as a double prime, a degree sign as ``o``) is left open: a label's parts say what it
printed, and :mod:`hamta.core.grid.reading` completes and checks them against the others.

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from typing import List, Optional

from .words import Word

HEMISPHERES = "NSEW"


@dataclass(frozen=True)
class Label:
    """A label as printed: ``degrees``, ``minutes``, ``seconds`` (None where not printed); ``hemisphere`` (a
    letter or ''); ``number`` (a linear value as printed) and its ``digits``; ``marked``: angle marks were read
    (a plain number is a linear label, or minutes whose mark the engine lost); ``xy`` its centre, ``side`` the
    edge it was read along, ``glyph_px``, ``confidence``, ``text`` (the words, joined)."""

    text: str
    xy: tuple
    side: str
    glyph_px: float
    confidence: float
    degrees: Optional[int] = None
    minutes: Optional[float] = None
    seconds: Optional[float] = None
    hemisphere: str = ""
    number: Optional[float] = None
    digits: int = 0
    marked: bool = False

    @property
    def angle(self) -> bool:
        return self.degrees is not None or self.minutes is not None or self.seconds is not None

    @property
    def whole(self) -> bool:
        """The label says its whole value itself (degrees printed; a linear number printed in full)."""
        return self.degrees is not None or (self.number is not None and self.digits >= FULL_DIGITS)

    def to_dict(self) -> dict:
        return {"text": self.text, "xy": [float(self.xy[0]), float(self.xy[1])], "side": self.side,
                "glyph_px": self.glyph_px, "confidence": self.confidence, "degrees": self.degrees,
                "minutes": self.minutes, "seconds": self.seconds, "hemisphere": self.hemisphere,
                "number": self.number}


FULL_DIGITS = 5  # a linear label printed in full (503000, 5540000; 10000 yards); fewer digits are abbreviated
NUMBER = r"\d+(?:\.\d+)?"


def normalised(text: str) -> str:
    """The engine's text with its look-alikes folded: primes, degree signs, spaces inside numbers."""
    t = text.strip().strip(",;:()[]|_")
    t = t.replace("’", "'").replace("`", "'").replace("′", "'").replace("″", '"').replace("''", '"')
    t = re.sub(r"(?<=\d)[oO](?=\s*\d|\s*$|\s*[NSEW'\"])", "°", t)  # a degree sign read as a letter o
    t = re.sub(r"[.,]+$", "", t)
    t = re.sub(r"(?<=\d)\s+(?=\d{3}\b)", "", t)  # 5 540 000
    t = re.sub(r"(?<=\d),(?=\d{3}\b)", "", t)  # 5,540,000
    return re.sub(r"\s+", "", t)


TOKEN = re.compile(r"(\d+(?:\.\d+)?)([°'\"]?)|([NSEW])")  # capitals only: a lower-case letter is no hemisphere


def parse(word: Word, side: str) -> Optional[Label]:
    """The label ``word`` (read along ``side``) prints, or None where it is not a coordinate. Numbers and the marks
    after them are read in turn: degrees (°), minutes (' or, where the engine doubled it, "), seconds ("); a
    hemisphere letter before or after; a number without marks is a grid's value (or minutes whose mark was lost:
    ``marked`` False)."""
    t = normalised(word.text)
    base = dict(text=word.text, xy=word.xy, side=side, glyph_px=word.glyph_px, confidence=word.confidence)
    tokens, at = [], 0
    for m in TOKEN.finditer(t):
        if m.start() != at:
            return None  # characters no coordinate is written with
        at = m.end()
        tokens.append((m.group(1), m.group(2), m.group(3)))
    if at != len(t) or not tokens:
        return None
    letters = [c for _, _, c in tokens if c]
    numbers = [(n, mark) for n, mark, c in tokens if n]
    if len(letters) > 1 or not numbers or (letters and tokens[0][2] is None and tokens[-1][2] is None):
        return None  # a letter between numbers, or two letters: not a coordinate
    hemisphere = letters[0] if letters else ""
    if len(numbers) == 1 and not numbers[0][1]:
        digits = numbers[0][0]
        if "." in digits:
            return None
        if hemisphere:  # 45N, W95: whole degrees
            return Label(**base, degrees=int(digits), hemisphere=hemisphere, marked=True) if int(digits) <= 180 \
                else None
        return Label(**base, number=float(digits), digits=len(digits.lstrip("0")) or 1)
    parts = _angle_parts(numbers)
    if parts is None:
        return None
    degrees, minutes, seconds = parts
    if (degrees is not None and degrees > 180) or (minutes is not None and minutes >= 60) or \
            (seconds is not None and seconds >= 60):
        return None
    return Label(**base, degrees=None if degrees is None else int(degrees), minutes=minutes, seconds=seconds,
                 hemisphere=hemisphere, marked=True)


def _angle_parts(numbers):
    """(degrees, minutes, seconds) of numbers with their marks, or None where they are no angle: a number with no
    mark after a marked one takes the next unit; a double prime after degrees alone is minutes (the engine doubles
    primes; no label prints seconds without minutes)."""
    units = []
    for n, mark in numbers:
        if mark == "°":
            unit = 0
        elif mark == "'":
            unit = 1
        elif mark == '"':
            unit = 1 if units == [0] or (units and units[-1] == 0) else 2
        else:
            unit = units[-1] + 1 if units else None
        if unit is None or unit > 2 or (units and unit <= units[-1]) or (unit == 0 and "." in n):
            return None
        units.append(unit)
    out = [None, None, None]
    for (n, _), unit in zip(numbers, units):
        out[unit] = float(n)
    if out[0] is not None and out[1] is None and out[2] is not None:
        return None
    return out[0], out[1], out[2]


def _num(text: Optional[str]) -> Optional[float]:
    return None if text is None else float(text)


def joined(labels: List[Label]) -> List[Label]:
    """``labels`` with the parts of one label printed apart joined (see the module docstring): a degree label and
    minutes beside or below it, minutes and seconds below them."""
    out = list(labels)
    changed = True
    while changed:
        changed = False
        for i, a in enumerate(out):
            for j, b in enumerate(out):
                if i == j or a.side != b.side:
                    continue
                whole = _join(a, b)
                if whole is not None:
                    out = [lab for k, lab in enumerate(out) if k not in (i, j)] + [whole]
                    changed = True
                    break
            if changed:
                break
    return out


def _join(a: Label, b: Label) -> Optional[Label]:
    """``a`` and ``b`` as one label where ``b`` continues ``a`` (right beside it, or just below), else None."""
    size = max(a.glyph_px, b.glyph_px)
    dx, dy = b.xy[0] - a.xy[0], b.xy[1] - a.xy[1]
    beside = 0 < dx <= 5.0 * size and abs(dy) <= 0.6 * size
    below = 0.6 * size <= dy <= 1.8 * size and abs(dx) <= 2.5 * size
    if not (beside or below) or abs(math.log(max(a.glyph_px, 1) / max(b.glyph_px, 1))) > math.log(2.0):
        return None
    text, first, second = f"{a.text} {b.text}", "".join(a.text.split()), "".join(b.text.split())
    if beside and a.number is not None and b.number is not None and first.isdigit() and second.isdigit() and \
            len(second) == 3 and dx <= 0.6 * size * (len(first) + 4):  # 1742 500: the thousands printed apart
        digits = first + second
        return replace(a, text=text, number=float(digits), digits=len(digits.lstrip("0")) or 1, xy=_centre(a, b),
                       confidence=min(a.confidence, b.confidence))
    if a.degrees is not None and a.minutes is None and b.degrees is None and b.minutes is not None:
        hemisphere = a.hemisphere or b.hemisphere
        return replace(a, text=text, minutes=b.minutes, seconds=b.seconds, hemisphere=hemisphere,
                       xy=_centre(a, b), confidence=min(a.confidence, b.confidence))
    seconds_only = b.degrees is None and b.minutes is None and b.seconds is not None
    if a.minutes is not None and a.seconds is None and seconds_only:
        return replace(a, text=text, seconds=b.seconds, xy=_centre(a, b), confidence=min(a.confidence, b.confidence))
    return None


def _centre(a: Label, b: Label) -> tuple:
    return (a.xy[0] + b.xy[0]) / 2, (a.xy[1] + b.xy[1]) / 2
