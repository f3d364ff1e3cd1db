"""The background job of 'Auto-georeference…': :func:`hamta.core.run` inside a ``QgsTask``.

``run()`` executes in a worker thread of QGIS's task manager and touches no GUI object: it only
calls the engine, reports progress with ``setProgress`` and stops when ``isCanceled()``. What
happened is kept on the task (:attr:`RegisterTask.outcome`), with the whole run's time
(``elapsed_s``); ``finished()`` runs in the main thread and hands the task to the ``done`` callback,
which shows it. :class:`KeepTask` writes the outputs of a result that did not verify, when the user
keeps it after the run.
"""
from __future__ import annotations

import time
import traceback

from qgis.core import QgsTask
from qgis.PyQt.QtCore import QCoreApplication, QTimer

CANCELED, WRITTEN, UNVERIFIED, REFUSED, FAILED, CRASHED = ("canceled", "written", "unverified", "refused", "failed",
                                                             "crashed")


def tr(text: str) -> str:
    """pylupdate5 files the strings of a module-level ``tr()`` under '@default': they are looked up there."""
    return QCoreApplication.translate("@default", text)


class _Ends:
    """What both tasks share: progress with the stage's message, and the outcome handed to ``done``."""

    def _progress(self, fraction, message=None):
        self.stage = message or self.stage
        self.setProgress(100.0 * fraction)

    def finished(self, result):  # the main thread; also after a cancel before run() started
        """Hand the task to ``done`` on the next turn of the event loop: after the 'Task complete' notice
        QGIS pushes to its message bar when its window is inactive, which would cover the outcome's."""
        if self.isCanceled() and self.outcome != WRITTEN:
            self.outcome = CANCELED
        if self.done is not None:
            QTimer.singleShot(0, lambda done=self.done: done(self))


class RegisterTask(_Ends, QgsTask):
    """Registers ``target`` (a raster file) onto ``reference`` (a reference the core reads, see
    :mod:`hamta.core.reference`; or a :class:`hamta.processing.reference.Rendering` of a layer, written
    here first) and writes the outputs into ``folder``; without a reference, ``grid`` ({hints, sheet_crs}) has a
    scanned sheet georeferenced by its own printed grid (:mod:`hamta.core.grid`).

    After ``finished``: ``outcome`` is one of :data:`WRITTEN` (the outputs: verified, or unverified and
    kept), :data:`UNVERIFIED` (not verified: only the report was written, ``error`` says why),
    :data:`REFUSED` (nothing to register: a :class:`hamta.core.errors.Refused` in ``error``, its report in
    ``written``), :data:`FAILED` (a :class:`hamta.core.HamtaError` in ``error``), :data:`CRASHED` (a bug:
    ``error`` and ``trace``) or :data:`CANCELED`. ``result`` and ``written`` ({output: path}) hold
    what :func:`hamta.core.run` returned.
    """

    def __init__(self, description, target, reference, folder, options, accept_unverified, done=None, grid=None):
        super().__init__(description, QgsTask.CanCancel)
        self.target, self.reference, self.folder, self.grid = target, reference, folder, grid
        self.options, self.accept_unverified = options, accept_unverified
        self.done = done
        self.result, self.written, self.error, self.trace = None, {}, None, ""
        self.outcome = CANCELED
        self.stage = ""  # the engine's latest stage message
        self.feedback = None  # while a layer is read (see _block_feedback)
        self.elapsed_s = None  # the whole run's time, once it ended

    def run(self):  # the worker thread: no GUI here
        start = time.perf_counter()
        try:
            return self._run()
        finally:
            self.elapsed_s = time.perf_counter() - start

    def _run(self):
        from ..core import run
        from ..core.errors import HamtaError, Refused, RegistrationCanceled, UnverifiedResult
        from ..core.outputs import OutputPaths

        try:
            if hasattr(self.reference, "write"):  # a Rendering of a layer QGIS reads
                from ..core.reference import RasterReference

                self._progress(0.0, "reading the reference layer")
                self.reference = RasterReference(self.reference.write(self._block_feedback()))
            grid = {} if self.grid is None else {"method": "grid", "params": self._grid_params()}
            self.result, self.written = run(self.target, self.reference, OutputPaths.in_folder(self.folder),
                                            options=self.options, accept_unverified=self.accept_unverified,
                                            progress=self._progress, is_canceled=self.isCanceled, **grid)
            self.outcome = WRITTEN
        except RegistrationCanceled:
            self.outcome = CANCELED
        except UnverifiedResult as exc:
            self.outcome, self.error, self.result, self.written = UNVERIFIED, exc, exc.result, exc.written
        except Refused as exc:
            self.outcome, self.error, self.written = REFUSED, exc, dict(exc.written)
        except HamtaError as exc:
            self.outcome, self.error = FAILED, exc
        except Exception as exc:  # a bug: shown as one, never lost in the worker thread
            self.outcome, self.error, self.trace = CRASHED, exc, traceback.format_exc()
        if self.isCanceled() and self.outcome != WRITTEN:
            self.outcome = CANCELED
        if self.outcome in (WRITTEN, UNVERIFIED):  # the run ended with a verdict: its bar ends full
            self._progress(1.0, "done")
        return self.outcome in (WRITTEN, UNVERIFIED)  # a run that ended with a verdict did not fail

    def _grid_params(self):
        from ..core.grid.register import GridParams

        return GridParams(self.grid["hints"], self.grid["sheet_crs"])

    def _block_feedback(self):
        """A feedback that :meth:`cancel` cancels: the layer's read stops with the task."""
        from qgis.core import QgsRasterBlockFeedback

        self.feedback = QgsRasterBlockFeedback()
        return self.feedback

    def cancel(self):
        if self.feedback is not None:
            self.feedback.cancel()
        super().cancel()


class KeepTask(_Ends, QgsTask):
    """Writes the outputs of ``result``, a registration the independent check did not verify, into
    ``folder`` after all: the user kept it from the message of its run (``run_s``: that run's time),
    without registering again. The writer is :func:`hamta.core.outputs.write_outputs`, as
    :func:`hamta.core.run` calls it for a run that accepts unverified results, so the files, and the
    report marking the result NOT VERIFIED, are the same as from such a run.

    After ``finished``: ``outcome`` is :data:`WRITTEN`, :data:`FAILED`, :data:`CRASHED` or
    :data:`CANCELED`, ``written`` ({output: path}) what was written and ``write_s`` how long it took.
    """

    def __init__(self, description, result, folder, options, run_s=None, done=None):
        super().__init__(description, QgsTask.CanCancel)
        self.result, self.folder, self.options, self.done = result, folder, options, done
        self.written, self.error, self.trace = {}, None, ""
        self.outcome = CANCELED
        self.stage = ""
        self.elapsed_s, self.write_s = run_s, None

    def run(self):  # the worker thread: no GUI here
        from ..core.auto import AUTO
        from ..core.errors import HamtaError, RegistrationCanceled
        from ..core.outputs import OutputPaths, write_outputs
        from ..core.runner import run_request

        start = time.perf_counter()
        try:
            self.written = write_outputs(self.result, OutputPaths.in_folder(self.folder),
                                         request=run_request(AUTO, None, self.options, True),
                                         progress=self._progress, is_canceled=self.isCanceled)
            self.outcome = WRITTEN
        except RegistrationCanceled:
            self.outcome = CANCELED
        except HamtaError as exc:
            self.outcome, self.error = FAILED, exc
        except Exception as exc:  # a bug: shown as one, never lost in the worker thread
            self.outcome, self.error, self.trace = CRASHED, exc, traceback.format_exc()
        self.write_s = time.perf_counter() - start
        if self.outcome == WRITTEN:
            self._progress(1.0, "done")
        return self.outcome == WRITTEN
