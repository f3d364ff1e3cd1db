"""What the 'Auto-georeference…' action does: open the dialog, start the registration task, and when it
ends add the results to the project and say in the message bar what happened."""
from __future__ import annotations

import dataclasses
import traceback
from typing import Optional

from qgis.core import Qgis, QgsApplication, QgsMessageLog, QgsProject, QgsRasterLayer, QgsVectorLayer
from qgis.PyQt.QtCore import QUrl
from qgis.PyQt.QtGui import QDesktopServices
from qgis.PyQt.QtWidgets import QAction, QApplication, QMessageBox, QProgressBar, QPushButton

from .task import CANCELED, CRASHED, REFUSED, UNVERIFIED, WRITTEN, KeepTask, RegisterTask, tr

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
            reference = None if job.reference is None else prepare_reference(job.reference, job.extent, job.target,
                                                                               job.options.max_working_pixels)
        except HamtaError as exc:
            self.push(str(exc), Qgis.Critical)
            return None
        except Exception as exc:  # a provider QGIS could not read from, or a bug: said, never a Python error dialog
            QgsMessageLog.logMessage(traceback.format_exc(), TITLE, Qgis.Critical)
            self.push(tr("The reference layer '{}' could not be read ({}: {}).").format(
                job.reference.name(), type(exc).__name__, exc), Qgis.Critical)
            return None
        task = RegisterTask(tr("Auto-georeference '{}'").format(job.target_name), job.target, reference, job.folder,
                            job.options, job.accept_unverified, done=self.show_outcome, grid=job.grid)
        task.job = job
        self.tasks.append(task)
        task.bar_item = self.progress_item(task)
        QgsApplication.taskManager().addTask(task)
        return task

    def progress_item(self, task, line=None):
        """A message bar item showing ``task``'s stage ('fetching tiles 42/99', 'locating the target…') on one
        line and its progress, with a Cancel button, until it ends; updated in the main thread through the task
        manager. ``line`` ('Auto-georeference '{}': {}') puts the target's name and the stage together."""
        line = line or tr("Auto-georeference '{}': {}")
        item = self.iface.messageBar().createMessage(TITLE, line.format(task.job.target_name, tr("starting")))
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
                item.setText(line.format(task.job.target_name, tr(task.stage)))

        QgsApplication.taskManager().progressChanged.connect(update)
        item.disconnect_update = lambda: QgsApplication.taskManager().progressChanged.disconnect(update)
        return item

    def show_outcome(self, task):
        """In the main thread, once ``task`` has ended: one short line in plain words, the rest one click
        away (Details)."""
        if task in self.tasks:
            self.tasks.remove(task)
        self.close_progress(task)
        job, written, ended = task.job, task.written, Ended.of(task)  # QGIS deletes the task soon: keep what it says
        if task.outcome == CANCELED:
            self.push(tr("Auto-georeference of '{}' canceled; nothing was added.").format(job.target_name), Qgis.Info,
                      duration=10)
        elif task.outcome == WRITTEN:
            self.add_layers(job, written, task.result.verified)
            buttons = [(tr("Details"), lambda: self.show_details(ended))] + self.report_button(written) + [
                (tr("Open the GCPs in the Georeferencer"), lambda: self.open_georeferencer(job, written["points"]))]
            self.push(self.success_text(job, task.result), Qgis.Success if task.result.verified else Qgis.Warning,
                      buttons)
        elif task.outcome == UNVERIFIED:
            item = None
            buttons = [(tr("Details"), lambda: self.show_details(ended)),
                       (tr("Keep anyway"), lambda: self.keep(ended, item))] + self.report_button(written)
            item = self.push(tr("'{}' not verified; nothing added.").format(job.target_name), Qgis.Warning, buttons)
        elif task.outcome == REFUSED:
            text = str(task.error)
            buttons = [(tr("Details"), lambda: QMessageBox.information(self.iface.mainWindow(), TITLE, text))]
            self.push(tr("'{}' not georeferenced; nothing added.").format(job.target_name), Qgis.Warning,
                      buttons + self.report_button(written))
        elif task.outcome == CRASHED:
            QgsMessageLog.logMessage(task.trace, TITLE, Qgis.Critical)
            self.push(tr("Hamta stopped on an unexpected error ({}: {}); nothing was added. Please report it (the "
                         "details are in the message log).").format(type(task.error).__name__, task.error),
                      Qgis.Critical)
        else:
            self.push(str(task.error), Qgis.Critical)

    def keep(self, ended, item=None):
        """Write the outputs of an unverified result (``ended``: an :class:`Ended` run) after all, without
        searching again, marked NOT VERIFIED, and add them like a run's; its message (``item``) goes.
        Returns the :class:`KeepTask`."""
        if item is not None:
            self.iface.messageBar().popWidget(item)
        job = ended.job
        keeping = KeepTask(tr("Keep '{}' (not verified)").format(job.target_name), ended.result, job.folder,
                           job.options, run_s=ended.elapsed_s, done=self.show_outcome)
        keeping.job = job
        self.tasks.append(keeping)
        keeping.bar_item = self.progress_item(keeping, tr("Keeping '{}': {}"))
        QgsApplication.taskManager().addTask(keeping)
        return keeping

    def add_layers(self, job, written, verified=True):
        """The warped raster, then its GCPs above it (their style is in the GeoPackage); a result the check
        did not verify says so in its name."""
        project = QgsProject.instance()
        name = tr("{} (georeferenced)") if verified else tr("NOT VERIFIED {} (georeferenced)")
        raster = QgsRasterLayer(written["raster"], name.format(job.target_name))
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
        """One line: what happened and how good it is, the error on the ground and in the target's own
        pixels; the rest is behind 'Details'."""
        v = result.verification
        if result.verified:
            bound = error_text(job, result, v.error_bound_px, short=True)
            return tr("'{}' verified{}.").format(job.target_name, tr(", within {}").format(bound) if bound else "")
        return tr("'{}' NOT VERIFIED; check it before use.").format(job.target_name)

    def show_details(self, ended):
        QMessageBox.information(self.iface.mainWindow(), TITLE, details_text(ended))

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



def error_text(job, result, value_px, short=False) -> str:
    """A length in reference px as a person reads it: '1.4 m on the ground, 0.6 px of 'scan'' (each
    part when known; ``short``: '1.4 m (0.6 px)', for the message bar), else in the reference's pixels;
    '' when missing."""
    from ..core.outputs.scale import ground_metres, reference_px_name, target_px

    if value_px is None or value_px != value_px:
        return ""
    parts = []
    metres, pixels = ground_metres(result, value_px), target_px(result, value_px)
    if short and metres is not None:
        return (f"{metres:.1f} m" if metres >= 0.95 else f"{metres:.2f} m") + (
            f" ({pixels:.1f} px)" if pixels is not None else "")
    if metres is not None:
        parts.append(tr("{:.1f} m on the ground").format(metres) if metres >= 0.95 else
                     tr("{:.2f} m on the ground").format(metres))
    if pixels is not None:
        parts.append(tr("{:.1f} px of '{}'").format(pixels, job.target_name))
    if not parts:
        parts.append(f"{value_px:.1f} {reference_px_name(result)}")
    return ", ".join(parts)


@dataclasses.dataclass(frozen=True)
class Ended:
    """What a task that ended says, kept from it (QGIS deletes a finished task): its ``job``, ``result``,
    ``written`` files, the whole run's time ``elapsed_s`` and, for a result kept after its run, the
    time its outputs took to write (``write_s``)."""

    job: object
    result: object
    written: dict
    elapsed_s: Optional[float] = None
    write_s: Optional[float] = None

    @classmethod
    def of(cls, task) -> "Ended":
        return cls(task.job, task.result, dict(task.written), getattr(task, "elapsed_s", None),
                   getattr(task, "write_s", None))


def details_text(ended: Ended) -> str:
    """What a user may want after the one line: the verdict and why, the check's figures, what may help,
    the method, the GCPs, where the target was found and how long the whole run took."""
    job, result = ended.job, ended.result
    v = result.verification
    lines = [tr("'{}' onto '{}'").format(job.target_name, job.reference.name()) if job.reference is not None
             else tr("'{}' by its own printed grid").format(job.target_name)]
    if v is not None:
        lines.append(tr("Independent check: {}; {}; error within {} (tolerance {})").format(
            tr(v.verdict), v.summary(), error_text(job, result, v.error_bound_px) or "–",
            error_text(job, result, v.tolerance_px)))
        lines += [f"  – {reason}" for reason in v.reasons]
    if not result.verified and ended.write_s is None:  # once kept, what may help is past
        from ..core.advice import advice  # the engine: not when the plugin loads

        lines.append(tr("What may help:"))
        lines += [f"  – {tip_text(tip)}" for tip in advice(result)]
    lines.append(tr("Method: {}; {} GCPs; transformation: {}").format(result.method, result.stats.n_gcps,
                                                                       result.options.get("model") or "–"))
    lines += [f"  – {note}" for note in result.notes]
    run_s = result.timings.total if ended.elapsed_s is None else ended.elapsed_s  # the whole run, when timed
    lines.append(tr("Time: {:.1f} s").format(run_s))
    if ended.write_s is not None:
        lines.append(tr("Kept after the run: the outputs were written in {:.1f} s.").format(ended.write_s))
    return "\n".join(lines)


def tip_text(tip) -> str:
    """An :class:`hamta.core.advice.Advice` as this dialog and message bar name it."""
    from ..core.advice import KEEP_UNVERIFIED
    from ..core.options import RegisterOptions, option_fields
    from .autogeoref import option_tr

    if tip.option == "accept_unverified":
        return tr("'Keep anyway' here, or '{}' in the dialog: {}").format(tr(KEEP_UNVERIFIED), tip.why)
    labels = {f.name: spec.label for f, spec in option_fields(RegisterOptions)}
    if tip.option == "extent":
        label = tr("Search area")
    else:
        label = option_tr(labels.get(tip.option, tip.option))
    value = "" if tip.value is True or tip.option == "extent" else f" = {tip.value}"
    return f"'{label}'{value}: {tip.why}"
