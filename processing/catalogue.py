"""What the provider lists, readable without importing the engine (so that it can list its algorithms
as unavailable when QGIS's Python lacks a requirement): 'auto' and the batch, written here, and every
method's Toolbox entry, read from the ``toolbox=Toolbox(id, title)`` of the method modules' source."""
from __future__ import annotations

import ast
import os
from typing import NamedTuple, Tuple

from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

METHODS_DIR = os.path.join(os.path.dirname(os.path.dirname(__file__)), "core", "methods")


class Entry(NamedTuple):
    id: str
    title: str
    help: str = ""


AUTO_ALGORITHM = Entry(
    "registerauto", QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register raster (automatic)"),
    QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers the target raster onto the reference raster and chooses the method itself: the fast SIFT "
        "matcher first, then matchers for images of different modality (SAR, infrared, maps) and for SAR, until "
        "a result passes an independent check. The check compares the two rasters at sites spread over the "
        "overlap, not the matches the model was fitted on, against what wrong alignments of the same rasters "
        "give, and bounds the remaining error. A result that does not verify is not written unless 'Keep "
        "unverified results' is set; the log lists every method tried, its verdict and its time. The other "
        "algorithms of this group run one method each, for experts."))
BATCH_ALGORITHM = Entry("batchregister", QT_TRANSLATE_NOOP("BatchRegisterAlgorithm", "Batch register"))
GRID_ALGORITHM = Entry(
    "georeferencebygrid", QT_TRANSLATE_NOOP("RegisterAlgorithm", "Georeference a scanned map by its grid"),
    QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Georeferences a scanned map sheet by the grid or graticule printed on it, without a reference layer. "
        "Choose the sheet's CRS. The coordinates printed in its margins are read (Tesseract); where they cannot be, "
        "place two or three crossings of the printed lines roughly in the QGIS Georeferencer, type their coordinates "
        "as printed (degrees, or metres of the national grid) and save the GCP points (.points) as hints. Hamta "
        "finds the printed lattice as a whole, then every crossing of the sheet to a fraction of a pixel; each "
        "crossing becomes a GCP. The model (affine, a polynomial where the projection bends the lines, a thin "
        "plate spline where the paper is warped) is checked by predicting each grid line from the others: a result "
        "is verified only when that check is within the accuracy asked for, in scan pixels. A sheet whose grid "
        "cannot be found is refused, saying why."))


def method_entries() -> Tuple[Entry, ...]:
    """``Entry(id, title)`` of every method with a Toolbox algorithm, from the method modules' source."""
    entries = []
    for name in sorted(os.listdir(METHODS_DIR)):
        if not name.endswith(".py"):
            continue
        with open(os.path.join(METHODS_DIR, name), encoding="utf-8") as f:
            tree = ast.parse(f.read(), name)
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "Toolbox":
                values = [ast.literal_eval(a) for a in node.args]
                entries.append(Entry(*values, **{k.arg: ast.literal_eval(k.value) for k in node.keywords}))
    return tuple(sorted(entries, key=lambda e: e.title))  # as the Toolbox lists them


def algorithm_entries() -> Tuple[Entry, ...]:
    return (AUTO_ALGORITHM, *method_entries(), GRID_ALGORITHM, BATCH_ALGORITHM)
