"""The words found in a scan's margins (:mod:`hamta.core.grid.words`) read by an OCR engine: what
:mod:`hamta.core.grid.labels` parses as coordinates.

Every word is cut out, scaled so that its glyphs are :data:`GLYPH_PX` high (the height the engine
reads best, whatever the scan's resolution), and the words are set one under another on a sheet of paper
read in one go by the engine (Tesseract, the ``tesseract`` program: Debian's ``tesseract-ocr``; its English
model ships in the package, nothing is downloaded), restricted to the characters coordinates are written
in. Each line the engine returns is the word set at that height.

Pixels: the scan's (corner convention).
"""
from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from dataclasses import replace
from typing import Callable, List, Optional, Tuple

import numpy as np

from .words import Found, Word

TESSERACT_ENV = "HAMTA_TESSERACT"  # the tesseract program, where it is not on the PATH (Windows, macOS)
GLYPH_PX = 36  # the height words are scaled to for the engine (Tesseract reads best at 30-40 px capitals)
WHITELIST = "0123456789°'\"′″’`.,-NSEWnsewOo"
PAGE_WORDS = 80  # words set on one sheet for the engine


def tesseract() -> Optional[str]:
    """The tesseract program to run, or None where it is not installed."""
    given = os.environ.get(TESSERACT_ENV)
    if given:
        return given if os.path.isfile(given) else shutil.which(given)
    found = shutil.which("tesseract")
    if found:
        return found
    for path in (r"C:\Program Files\Tesseract-OCR\tesseract.exe", r"C:\Program Files (x86)\Tesseract-OCR\tesseract.exe",
                 "/opt/homebrew/bin/tesseract", "/usr/local/bin/tesseract", "/opt/local/bin/tesseract"):
        if os.path.isfile(path):
            return path
    return None


ENGINE_ENV = "HAMTA_OCR"  # 'rapidocr' or 'tesseract': one engine alone, where both are installed


def engines() -> Tuple[str, ...]:
    """The OCR engines labels are read with, in the order they read: Tesseract (the ``tesseract`` program) first,
    as it reads a word in a fifth of the time, then RapidOCR's recogniser (the package ``rapidocr_onnxruntime``,
    its models in its wheel), which reads the words with a digit in them again: it read the development sheets'
    labels better (docs/benchmarks.md). Either alone where only one is installed, or where ``HAMTA_OCR`` names
    it; empty without either."""
    have = tuple(name for name, ok in (("tesseract", tesseract() is not None), ("rapidocr", _rapid() is not None))
                 if ok)
    asked = os.environ.get(ENGINE_ENV, "").strip().lower()
    return (asked,) if asked in have else have


def engine() -> Optional[str]:
    """The engine whose reading is kept (the last of :func:`engines`), or None without one."""
    found = engines()
    return found[-1] if found else None


INSTALL = ("Reading the sheet's printed labels needs an OCR engine: the Tesseract program (Debian, Ubuntu: 'sudo apt "
           "install tesseract-ocr'; Windows: the installer from UB Mannheim; macOS: 'brew install tesseract'; or set "
           "HAMTA_TESSERACT to the program), or RapidOCR with pip into the Python QGIS or Hamta runs in ('pip install "
           "onnxruntime pyclipper pyyaml six tqdm', then 'pip install --no-deps rapidocr_onnxruntime'); "
           "docs/scanned-maps.md says how. Without one, give two or three crossings with their coordinates "
           "as hints (a QGIS Georeferencer .points file).")


def read_words(found: List[Found], offset=(0.0, 0.0), name: Optional[str] = None,
               check: Callable[[], None] = lambda: None) -> List[Word]:
    """Read ``found`` (boxes offset by ``offset`` scan px) with the engine ``name`` (the first of :func:`engines`
    by default); every word is kept, read or not (another engine may read it, :func:`reread`). Raises
    :class:`hamta.core.errors.InputError` without an engine."""
    from ..errors import InputError

    names = engines()
    if not names:
        raise InputError(INSTALL)
    name = name or names[0]
    out = []
    for start in range(0, len(found), PAGE_WORDS):
        check()
        page = found[start:start + PAGE_WORDS]
        crops = [_scaled(f.crop) for f in page]
        for item, crop, (text, conf) in zip(page, crops, _read(name, crops)):
            x0, y0, x1, y1 = item.box
            out.append(Word(text, (x0 + offset[0], y0 + offset[1], x1 + offset[0], y1 + offset[1]), item.turn,
                            item.glyph_px, conf, item.light, crop))
    return out


def reread(words: List[Word], name: str, check: Callable[[], None] = lambda: None) -> List[Word]:
    """``words`` read again by the engine ``name``."""
    out = []
    for start in range(0, len(words), PAGE_WORDS):
        check()
        page = words[start:start + PAGE_WORDS]
        out += [replace(w, text=text, confidence=conf) for w, (text, conf) in zip(page, _read(name, [w.crop
                                                                                                    for w in page]))]
    return out


def _read(name: str, crops: List[np.ndarray]) -> List[Tuple[str, float]]:
    return _read_rapid(crops) if name == "rapidocr" else _read_page(tesseract(), crops)


def _scaled(crop: np.ndarray) -> np.ndarray:
    """A word's crop with its glyphs :data:`GLYPH_PX` high, stretched from its ink to its paper."""
    import cv2

    h = max(crop.shape[0], 1)
    f = GLYPH_PX / max(h / 1.7, 1.0)  # the crop is the glyphs and 0.35 of a glyph above and below
    scaled = cv2.resize(crop, (max(int(round(crop.shape[1] * f)), 1), max(int(round(h * f)), 1)),
                        interpolation=cv2.INTER_CUBIC if f > 1 else cv2.INTER_AREA)
    return _normalised(scaled)


_RAPID = {}


def _rapid():
    """RapidOCR's text recogniser (``rapidocr_onnxruntime``, its model from its own wheel), or None."""
    if "rec" not in _RAPID:
        try:
            import rapidocr_onnxruntime
            from rapidocr_onnxruntime.ch_ppocr_rec import TextRecognizer
        except ImportError:
            _RAPID["rec"] = None
        else:
            folder = os.path.dirname(rapidocr_onnxruntime.__file__)
            _RAPID["rec"] = TextRecognizer({"model_path": os.path.join(folder, "models", "ch_PP-OCRv4_rec_infer.onnx"),
                                            "rec_img_shape": [3, 48, 320], "rec_batch_num": 6, "use_cuda": False,
                                            "use_dml": False, "intra_op_num_threads": 1, "inter_op_num_threads": 1})
    return _RAPID["rec"]


def _read_rapid(crops: List[np.ndarray]) -> List[Tuple[str, float]]:
    """(text, confidence 0-100) of each crop by RapidOCR's recogniser."""
    import cv2

    results, _ = _rapid()([cv2.cvtColor(c, cv2.COLOR_GRAY2BGR) for c in crops])
    return [(text.strip(), 100.0 * float(conf)) for text, conf in results]


def _read_page(program: str, crops: List[np.ndarray]) -> List[Tuple[str, float]]:
    """(text, confidence) of each crop (scaled already), set one under another on one page and read in one go by
    Tesseract."""
    import cv2

    gap = GLYPH_PX
    width = max(s.shape[1] for s in crops) + 2 * gap
    rows, y = [], gap
    for s in crops:
        rows.append((y, y + s.shape[0]))
        y += s.shape[0] + gap
    sheet = np.full((y, width), 255, np.uint8)
    for s, (y0, y1) in zip(crops, rows):
        sheet[y0:y1, gap:gap + s.shape[1]] = s
    with tempfile.TemporaryDirectory(prefix="hamta-ocr-") as folder:
        path = os.path.join(folder, "words.png")
        cv2.imwrite(path, sheet)
        try:
            tsv = subprocess.run([program, path, "stdout", "--psm", "6", "-c", f"tessedit_char_whitelist={WHITELIST}",
                                  "tsv"], capture_output=True, text=True, timeout=120, check=False,
                                 env=dict(os.environ, OMP_THREAD_LIMIT="1")).stdout
        except (OSError, subprocess.TimeoutExpired):
            return [("", 0.0)] * len(crops)
    texts = [[] for _ in crops]
    confs = [[] for _ in crops]
    centres = np.array([(a + b) / 2 for a, b in rows])
    for line in tsv.splitlines()[1:]:
        cells = line.split("\t")
        if len(cells) < 12 or not cells[11].strip():
            continue
        try:
            left, top, w, h, conf = (float(c) for c in cells[6:11])
        except ValueError:
            continue
        k = int(np.argmin(np.abs(centres - (top + h / 2))))
        if rows[k][0] - gap / 2 <= top + h / 2 <= rows[k][1] + gap / 2:
            texts[k].append((left, cells[11].strip()))
            confs[k].append(conf)
    return [(" ".join(t for _, t in sorted(words)), float(np.mean(c)) if c else 0.0)
            for words, c in zip(texts, confs)]


def _normalised(crop: np.ndarray) -> np.ndarray:
    """A word's crop stretched from its ink to its paper (what the engine binarises well)."""
    lo, hi = np.percentile(crop, 2), np.percentile(crop, 90)
    if hi - lo < 1:
        return crop
    return np.clip((crop.astype(np.float32) - lo) * 255.0 / (hi - lo), 0, 255).astype(np.uint8)


