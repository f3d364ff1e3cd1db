"""The Processing dialog of every Hamta algorithm, built offscreen with QGIS's own AlgorithmDialog."""
import pathlib

import pytest
from qgis.core import QgsApplication
from qgis.gui import QgsCollapsibleGroupBox
from qgis.PyQt import sip
from qgis.PyQt.QtCore import QUrl
from qgis.PyQt.QtWidgets import QDialogButtonBox, QDoubleSpinBox, QGroupBox, QScrollArea

from hamta.processing.catalogue import algorithm_entries


@pytest.fixture
def dialog(provider, request):
    from processing.gui.AlgorithmDialog import AlgorithmDialog

    alg = QgsApplication.processingRegistry().createAlgorithmById(f"hamta:{request.param}")
    dlg = AlgorithmDialog(alg, False, None)
    dlg.resize(800, 700)
    dlg.show()
    for group in dlg.findChildren(QGroupBox):  # QGIS builds it in C++: sip sees a plain QGroupBox
        if group.metaObject().className() == "QgsCollapsibleGroupBox":
            sip.cast(group, QgsCollapsibleGroupBox).setCollapsed(False)  # the advanced parameters too
    for _ in range(5):
        QgsApplication.processEvents()
    yield dlg
    dlg.close()


@pytest.mark.parametrize("dialog", [e.id for e in algorithm_entries()], indirect=True)
def test_the_dialog_fits_has_help_and_plain_defaults(dialog):
    panels = [area for area in dialog.findChildren(QScrollArea) if area.isVisible()]
    assert panels and all(area.horizontalScrollBar().maximum() == 0 for area in panels), "a panel scrolls sideways"
    assert dialog.findChild(QDialogButtonBox).button(QDialogButtonBox.Help) is not None
    alg = dialog.algorithm()
    page = pathlib.Path(QUrl(alg.helpUrl()).toLocalFile()).read_text()
    assert alg.displayName() in page and all(p.name() in page for p in alg.parameterDefinitions())
    shown = [box.text() for box in dialog.findChildren(QDoubleSpinBox) if box.isVisible()]
    assert shown and not [t for t in shown if t.endswith("0000")], shown


def test_each_stage_is_logged_once():
    from hamta.processing.register_algorithm import feedback_progress

    class Feedback:
        def __init__(self):
            self.texts, self.values = [], []

        def setProgress(self, value):
            self.values.append(value)

        def setProgressText(self, text):
            self.texts.append(text)

    feedback = Feedback()
    progress = feedback_progress(feedback)
    for i in range(25):
        progress(i / 50, "refining")
    progress(0.6, "checking")
    assert feedback.texts == ["refining", "checking"] and len(feedback.values) == 26
    for i in range(1, 17):  # a counter is a step of its stage: one line, not sixteen
        progress(0.6 + i / 100, f"fetching tiles {i}/16")
    assert feedback.texts == ["refining", "checking", "fetching tiles"]
