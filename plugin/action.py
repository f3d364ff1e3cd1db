"""What the 'Auto-georeference…' action does: open the dialog, start the registration task, and when it
ends add the results to the project and say in the message bar what happened."""
from __future__ import annotations

import traceback

from qgis.core import Qgis, QgsApplication, QgsMessageLog, QgsProject, QgsRasterLayer, QgsVectorLayer
from qgis.PyQt.QtCore import QUrl
from qgis.PyQt.QtGui import QDesktopServices
from qgis.PyQt.QtWidgets import QAction, QApplication, QMessageBox, QProgressBar, QPushButton

from .task import CANCELED, CRASHED, UNVERIFIED, WRITTEN, RegisterTask, tr

TITLE = "Hamta"
GEOREFERENCER = "mActionShowGeoreferencer"  # the object name of QGIS's Raster > Georeferencer action


class AutoGeoreference:
    """Opens :class:`AutoGeoreferenceDialog` and runs what it sets; ``tasks`` are the running ones
    (kept here: QGIS deletes a finished task, Python must not collect a running one)."""

    def __init__(self, iface):
        self.iface = iface
        self.dialog = None
        self.tasks = []

    def show_dialog(self):
        """A new dialog on the current selection (replacing one left open)."""
        from .autogeoref import AutoGeoreferenceDialog  # imports hamta.core: not when the plugin loads

        if self.dialog is not None:
            self.dialog.close()
            self.dialog.deleteLater()
        self.dialog = AutoGeoreferenceDialog(self.iface, self.iface.mainWindow())
        self.dialog.accepted.connect(lambda dialog=self.dialog: self.start(dialog.job()))
        self.dialog.show()
        self.dialog.raise_()
        return self.dialog

    def start(self, job):
        """Prepare the reference (in the main thread: a layer QGIS must render gets its provider cloned
        here, and is read in the task) and start the task; returns it, or None after saying in the
        message bar why it could not start."""
        try:
            from ..core.errors import HamtaError
            from ..processing.reference import prepare_reference
        except ImportError as exc:  # the engine's packages are missing: the provider's warning says how to fix it
            self.push(tr("Hamta cannot run: {}").format(exc), Qgis.Critical)
            return None
        try:
            reference = prepare_reference(job.reference, job.extent, job.target, job.options.max_working_pixels)
        except HamtaError as exc:
            self.push(str(exc), Qgis.Critical)
            return None
        except Exception as exc:  # a provider QGIS could not read from, or a bug: said, never a Python error dialog
            QgsMessageLog.logMessage(traceback.format_exc(), TITLE, Qgis.Critical)
            self.push(tr("The reference layer '{}' could not be read ({}: {}).").format(
                job.reference.name(), type(exc).__name__, exc), Qgis.Critical)
            return None
        task = RegisterTask(tr("Auto-georeference '{}'").format(job.target_name), job.target, reference, job.folder,
                            job.options, job.accept_unverified, done=self.show_outcome)
        task.job = job
        self.tasks.append(task)
        task.bar_item = self.progress_item(task)
        QgsApplication.taskManager().addTask(task)
        return task

    def progress_item(self, task):
        """A message bar item showing ``task``'s stage ('fetching tiles 42/99', 'locating the target…') and
        progress, with a Cancel button, until it ends; updated in the main thread through the task manager."""
        item = self.iface.messageBar().createMessage(TITLE, tr("Auto-georeference '{}': starting").format(
            task.job.target_name))
        bar = QProgressBar(item)
        bar.setRange(0, 100)
        item.layout().addWidget(bar)
        cancel = QPushButton(tr("Cancel"), item)
        cancel.clicked.connect(task.cancel)
        item.layout().addWidget(cancel)
        self.iface.messageBar().pushWidget(item, Qgis.Info, 0)

        def update(task_id, progress, task=task):
            if task in self.tasks and QgsApplication.taskManager().taskId(task) == task_id:
                bar.setValue(int(progress))
                item.setText(tr("Auto-georeference '{}': {}").format(task.job.target_name, tr(task.stage)))

        QgsApplication.taskManager().progressChanged.connect(update)
        item.disconnect_update = lambda: QgsApplication.taskManager().progressChanged.disconnect(update)
        return item

    def show_outcome(self, task):
        """In the main thread, once ``task`` has ended."""
        if task in self.tasks:
            self.tasks.remove(task)
        self.close_progress(task)
        job, written = task.job, task.written
        if task.outcome == CANCELED:
            self.push(tr("Auto-georeference of '{}' canceled; nothing was added.").format(job.target_name), Qgis.Info,
                      duration=10)
        elif task.outcome == WRITTEN:
            self.add_layers(job, written)
            buttons = [(tr("Details"), lambda: self.show_details(job, task.result))] + self.report_button(written) + [
                (tr("Open the GCPs in the Georeferencer"), lambda: self.open_georeferencer(job, written["points"]))]
            self.push(self.success_text(job, task.result), Qgis.Success if task.result.verified else Qgis.Warning,
                      buttons)
        elif task.outcome == UNVERIFIED:
            reasons = "; ".join(task.result.verification.reasons)
            self.push(tr("'{}' was registered, but the independent check did not confirm it ({}). No georeferenced "
                         "raster was written; see the report, or tick 'Keep unverified result' to write it anyway.")
                      .format(job.target_name, reasons), Qgis.Warning, self.report_button(written))
        elif task.outcome == CRASHED:
            QgsMessageLog.logMessage(task.trace, TITLE, Qgis.Critical)
            self.push(tr("Hamta stopped on an unexpected error ({}: {}); nothing was added. Please report it (the "
                         "details are in the message log).").format(type(task.error).__name__, task.error),
                      Qgis.Critical)
        else:
            self.push(str(task.error), Qgis.Critical)

    def add_layers(self, job, written):
        """The warped raster, then its GCPs above it (their style is in the GeoPackage)."""
        project = QgsProject.instance()
        raster = QgsRasterLayer(written["raster"], tr("{} (georeferenced)").format(job.target_name))
        gcps = QgsVectorLayer(f"{written['gpkg']}|layername=gcps", tr("{} GCPs").format(job.target_name), "ogr")
        for layer in (raster, gcps):
            if layer.isValid():
                project.addMapLayer(layer)
            else:
                self.push(tr("The output '{}' could not be loaded.").format(layer.source()), Qgis.Warning)

    def close_progress(self, task):
        item = getattr(task, "bar_item", None)
        if item is not None:
            item.disconnect_update()
            self.iface.messageBar().popWidget(item)
            task.bar_item = None

    @staticmethod
    def success_text(job, result):
        """One line: what happened and how good it is; the rest is behind 'Details'."""
        v = result.verification
        if result.verified:
            bound = "" if v.error_bound_px is None else tr(" (error within {:.1f} px)").format(v.error_bound_px)
            return tr("'{}' is georeferenced and verified{}.").format(job.target_name, bound)
        return tr("'{}' is georeferenced but NOT VERIFIED; check it before use.").format(job.target_name)

    def show_details(self, job, result):
        QMessageBox.information(self.iface.mainWindow(), TITLE, details_text(job, result))

    def report_button(self, written):
        html = written.get("html")
        return [(tr("Open report"), lambda: QDesktopServices.openUrl(QUrl.fromLocalFile(html)))] if html else []

    def open_georeferencer(self, job, points):
        """QGIS 3.22's Georeferencer cannot be given GCPs from Python: open it and say which file to load
        (its path is put on the clipboard)."""
        QApplication.clipboard().setText(points)
        action = self.iface.mainWindow().findChild(QAction, GEOREFERENCER)
        if action is not None:
            action.trigger()
        where = tr("In the Georeferencer") if action is not None else tr("In Raster ▸ Georeferencer")
        self.push(tr("{}, open the raster '{}' (File ▸ Open Raster…), then File ▸ Load GCP Points… and paste the "
                     "path of the GCP file, now on the clipboard: {}").format(where, job.target, points), Qgis.Info)

    def push(self, text, level, buttons=(), duration=0):
        """A message in QGIS's message bar, with (label, slot) ``buttons``."""
        bar = self.iface.messageBar()
        item = bar.createMessage(TITLE, text)
        for label, slot in buttons:
            button = QPushButton(label, item)
            button.clicked.connect(slot)
            item.layout().addWidget(button)
        bar.pushWidget(item, level, duration)
        return item

    def cancel_all(self):
        """Cancel the running tasks and show nothing when they end (the plugin is unloading); they stay
        referenced here until then."""
        for task in self.tasks:
            task.done = None
            task.cancel()



def details_text(job, result) -> str:
    """What a user may want after the one line: the check's figures, the method, the GCPs, where the
    target was found and how long it took."""
    v = result.verification
    lines = [tr("'{}' onto '{}'").format(job.target_name, job.reference.name())]
    if v is not None:
        bound = "–" if v.error_bound_px is None else f"{v.error_bound_px:.2f}"
        lines.append(tr("Independent check: {}; {} of {} sites agree; error bound {} px (tolerance {:g} px)").format(
            tr(v.verdict), v.n_agree, v.n_sites, bound, v.tolerance_px))
        lines += [f"  – {reason}" for reason in v.reasons]
    lines.append(tr("Method: {}; {} GCPs; transformation: {}").format(result.method, result.stats.n_gcps,
                                                                       result.options.get("model") or "–"))
    lines += [f"  – {note}" for note in result.notes]
    lines.append(tr("Time: {:.1f} s").format(result.timings.total))
    return "\n".join(lines)
