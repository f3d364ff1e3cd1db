"""The Processing algorithm that registers a raster with 'auto' or one method (a thin adapter; one
instance per method with a Toolbox entry, see :mod:`hamta.processing.provider`)."""
from __future__ import annotations

import dataclasses
import re

from qgis.core import (
    Qgis,
    QgsMessageLog,
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMapLayer,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterDestination,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
    QgsProcessingParameterVectorDestination,
)
from qgis.PyQt.QtCore import QCoreApplication

from ..core import RegisterOptions, UnverifiedResult, run
from ..core.advice import advice
from ..core.auto import AUTO
from ..core.errors import HamtaError, MethodCrashed, Refused, RegistrationCanceled, UsageError
from ..core.methods import get_method
from ..core.options import LABEL_CHARS, option_fields, resolve_options
from ..core.outcome import attempt_lines
from ..core.outputs.scale import length_text
from ..core.outputs.tags import counts_text, pixel_mode_text, unknown_crs_text
from ..core.progress import stage_name
from .catalogue import AUTO_ALGORITHM
from .help import help_url
from .mapping import method_parameter_name, method_values, register_settings
from .options import CONTEXT, KEYS, advanced, option_parameters, option_values
from .reference import reference_source


def decimals(value) -> int:
    """Decimals a spin box shows for a default ``value``: its own, at least 2 (QGIS shows 6: '3.000000')."""
    text = f"{float(value):.6f}".rstrip("0")
    return min(6, max(2, len(text.split(".")[1])))


def short_label(text: str, name: str) -> str:
    """A method parameter's label: the first phrase of its help when that is short, else its name."""
    head = re.split(r" \(|: |; |\. | = |, ", text, maxsplit=1)[0].rstrip(".")
    return head if len(head) <= LABEL_CHARS else name.replace("_", " ").capitalize()


def feedback_progress(feedback):
    """A ``progress(fraction, message)`` callback reporting to Processing ``feedback``; each stage is
    logged once, not at every step of it: 'fetching tiles 3/16' and 'fetching tiles 4/16' are one line,
    'fetching tiles' (see :func:`hamta.core.progress.stage_name`)."""
    last = [None]

    def progress(fraction, message):
        feedback.setProgress(100.0 * fraction)
        stage = stage_name(message)
        if stage and stage != last[0]:
            last[0] = stage
            feedback.setProgressText(stage)
    return progress


class PlainNumbers:
    """Mixed into an algorithm: its decimal parameters show their defaults as written ('3.00')."""

    def addParameter(self, p, createOutput=True):
        if isinstance(p, QgsProcessingParameterNumber) and p.dataType() == QgsProcessingParameterNumber.Double \
                and p.defaultValue() is not None:
            p.setMetadata({"widget_wrapper": {"decimals": decimals(p.defaultValue())}})
        return super().addParameter(p, createOutput)


class RegisterAlgorithm(PlainNumbers, QgsProcessingAlgorithm):
    """Registers with one method: 'auto', or a registered method with a Toolbox entry (its id, title,
    help and parameters come from the registry)."""

    TARGET, REFERENCE, KEEP_UNVERIFIED = "TARGET", "REFERENCE", "KEEP_UNVERIFIED"
    OUTPUT, GCP_LAYER, GCP_POINTS, GCP_VRT, REPORT = "OUTPUT", "GCP_LAYER", "GCP_POINTS", "GCP_VRT", "REPORT"
    OUTPUT_HTML = "OUTPUT_HTML"

    def __init__(self, method_name: str = AUTO):
        super().__init__()
        self.method_name = method_name

    def method(self):
        """The registered method this algorithm runs (None for 'auto', which chooses among them)."""
        return None if self.method_name == AUTO else get_method(self.method_name)

    def tr(self, text):
        return QCoreApplication.translate(CONTEXT, text)

    def createInstance(self):
        return RegisterAlgorithm(self.method_name)

    def name(self):
        method = self.method()
        return AUTO_ALGORITHM.id if method is None else method.toolbox.id

    def displayName(self):
        method = self.method()
        return self.tr(AUTO_ALGORITHM.title if method is None else method.toolbox.title)

    def group(self):
        return self.tr("Registration")

    def groupId(self):
        return "registration"

    def shortHelpString(self):
        method = self.method()
        if method is None:
            return self.tr(AUTO_ALGORITHM.help)
        return self.tr(method.summary) + "\n\n" + self.tr("References: {}").format(method.citation)

    def helpUrl(self):
        return help_url(self)

    def tags(self):
        return self.tr("georeference,coregistration,registration,GCP,match,align,warp").split(",")

    def initAlgorithm(self, config=None):
        method = self.method()
        # The model stays open (automatic: the method's, or the order the check chooses) unless the user picks one.
        d = RegisterOptions() if method is None else dataclasses.replace(resolve_options(RegisterOptions(), method),
                                                                         model=None)
        self.addParameter(QgsProcessingParameterRasterLayer(self.TARGET, self.tr("Target raster (to georeference)")))
        self.addParameter(QgsProcessingParameterMapLayer(
            self.REFERENCE, self.tr("Reference layer (raster, XYZ, WMS, areas or lines)"),
            types=[QgsProcessing.TypeRaster, QgsProcessing.TypeVectorPolygon, QgsProcessing.TypeVectorLine]))
        self.addParameter(QgsProcessingParameterBoolean(
            self.KEEP_UNVERIFIED, self.tr("Keep unverified results"), False))
        for p in option_parameters(d):
            self.addParameter(p)
        for f in self._fields():
            p = self._method_parameter(f)
            self.addParameter(p if f.metadata.get("basic") else advanced(p))
        self._add_outputs()

    def _add_outputs(self):
        """The outputs of every registration: the raster, the GCPs (layer, .points, VRT), the reports, the figures."""
        self.addParameter(QgsProcessingParameterRasterDestination(self.OUTPUT, self.tr("Georeferenced raster")))
        self.addParameter(QgsProcessingParameterVectorDestination(
            self.GCP_LAYER, self.tr("GCP points"), QgsProcessing.TypeVectorPoint, optional=True, createByDefault=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.GCP_POINTS, self.tr("GCP file for the QGIS Georeferencer"), self.tr("GCP points (*.points)"),
            optional=True, createByDefault=False))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.GCP_VRT, self.tr("Target with GCPs, not resampled (VRT)"), self.tr("VRT (*.vrt)"), optional=True,
            createByDefault=False))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.REPORT, self.tr("Report"), self.tr("JSON (*.json)"), optional=True, createByDefault=False))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_HTML, self.tr("Quality report (HTML)"),
            self.tr("HTML files (*.html)"), optional=True, createByDefault=True))
        self.addOutput(QgsProcessingOutputString("VERDICT", self.tr("Verdict of the independent check")))
        self.addOutput(QgsProcessingOutputString("METHOD", self.tr("Method that produced the result")))
        self.addOutput(QgsProcessingOutputNumber("RMSE_PX", self.tr("RMSE of the GCPs (reference pixels)")))
        self.addOutput(QgsProcessingOutputNumber("RMS_LOO_PX", self.tr("Leave-one-out RMS (reference pixels)")))
        self.addOutput(QgsProcessingOutputNumber("N_GCPS", self.tr("Number of GCPs")))

    def _fields(self):
        method = self.method()
        return () if method is None else dataclasses.fields(method.params_type)

    def _method_parameter(self, f):
        name, text = method_parameter_name(f.name), self.tr(f.metadata.get("help", f.name))
        label = short_label(text, f.name)
        choices = f.metadata.get("choices")
        number = QgsProcessingParameterNumber
        if choices:
            p = QgsProcessingParameterEnum(name, label, options=[str(c) for c in choices],
                                           defaultValue=list(choices).index(f.default))
        elif isinstance(f.default, bool):
            p = QgsProcessingParameterBoolean(name, label, f.default)
        elif isinstance(f.default, (int, float)):
            p = number(name, label, number.Integer if isinstance(f.default, int) else number.Double, f.default)
            if f.metadata.get("minimum") is not None:
                p.setMinimum(f.metadata["minimum"])
            if f.metadata.get("maximum") is not None:
                p.setMaximum(f.metadata["maximum"])
        else:
            p = QgsProcessingParameterString(name, label, str(f.default))
        p.setHelp(text)
        return p

    def _raster_path(self, parameters, name, context):
        layer = self._layer(parameters, name, context)
        if layer.providerType() != "gdal":
            raise QgsProcessingException(self.tr("{} must be a raster file GDAL can read, not a '{}' layer.")
                                         .format(layer.name(), layer.providerType()))
        return layer.source()

    def _layer(self, parameters, name, context):
        layer = self.parameterAsRasterLayer(parameters, name, context)
        if layer is None:
            raise QgsProcessingException(self.invalidRasterError(parameters, name))
        return layer

    def _values(self, parameters, context):
        v = option_values(self, parameters, context)
        v.update({
            self.OUTPUT: self.parameterAsOutputLayer(parameters, self.OUTPUT, context),
            self.GCP_LAYER: self.parameterAsOutputLayer(parameters, self.GCP_LAYER, context),
            self.GCP_POINTS: self.parameterAsFileOutput(parameters, self.GCP_POINTS, context),
            self.GCP_VRT: self.parameterAsFileOutput(parameters, self.GCP_VRT, context),
            self.REPORT: self.parameterAsFileOutput(parameters, self.REPORT, context),
            self.OUTPUT_HTML: self.parameterAsFileOutput(parameters, self.OUTPUT_HTML, context),
            self.KEEP_UNVERIFIED: self.parameterAsBoolean(parameters, self.KEEP_UNVERIFIED, context),
        })
        for f in self._fields():
            key = method_parameter_name(f.name)
            if f.metadata.get("choices"):
                v[key] = self.parameterAsEnum(parameters, key, context)
            elif isinstance(f.default, bool):
                v[key] = self.parameterAsBoolean(parameters, key, context)
            elif isinstance(f.default, int):
                v[key] = self.parameterAsInt(parameters, key, context)
            elif isinstance(f.default, float):
                v[key] = self.parameterAsDouble(parameters, key, context)
            else:
                v[key] = self.parameterAsString(parameters, key, context)
        return v

    def _unexpected(self, exc: Exception) -> QgsProcessingException:
        """A bug, said as one: a clear message naming it (the method, where a method raised), its traceback in
        the log, never a raw traceback in the dialog."""
        import traceback

        QgsMessageLog.logMessage("".join(traceback.format_exception(type(exc), exc, exc.__traceback__)), "Hamta",
                                 Qgis.Critical)
        kind, cause = type(exc).__name__, exc
        if isinstance(exc, MethodCrashed):
            cause = exc.__cause__
            kind = f"{type(cause).__name__} in method '{exc.method}'"
        message = self.tr("Hamta stopped on an unexpected error ({}: {}); no output was written. Please report it "
                          "(the traceback is in the log, tab Hamta).")
        return QgsProcessingException(message.format(kind, cause))

    def processAlgorithm(self, parameters, context, feedback):
        target = self._raster_path(parameters, self.TARGET, context)
        values = self._values(parameters, context)
        options, paths, output = register_settings(values)
        try:
            reference = self._reference(parameters, context, options, target)
            params = self._run_arguments(values, output)
        except (HamtaError, UsageError) as exc:
            raise QgsProcessingException(self.explain(exc) if isinstance(exc, HamtaError) else str(exc)) from None
        except Exception as exc:
            raise self._unexpected(exc) from None
        if paths.gpkg and not paths.gpkg.lower().endswith(".gpkg"):
            raise QgsProcessingException(self.tr("GCP points are written to a GeoPackage: choose a .gpkg file (got "
                                                 "'{}').").format(values[self.GCP_LAYER]))

        progress = feedback_progress(feedback)
        try:
            result, written = run(target, reference, paths, method=self.method_name, params=params, options=options,
                                  output=output, accept_unverified=values[self.KEEP_UNVERIFIED], progress=progress,
                                  is_canceled=feedback.isCanceled)
        except RegistrationCanceled:
            raise QgsProcessingException(self.tr("Registration canceled; no outputs were written.")) from None
        except Refused as exc:
            report = exc.written.get("html") or exc.written.get("report")
            raise QgsProcessingException(self.explain(exc) + (self.tr(" What was read and tried: {}").format(report)
                                                              if report else "")) from None
        except UnverifiedResult as exc:
            self._log(exc.result, feedback)
            raise QgsProcessingException(self.tr(
                "The registration was not verified: {}. No georeferenced output was written; set 'Keep unverified "
                "results' to write it anyway.").format("; ".join(exc.result.verification.reasons))) from None
        except HamtaError as exc:
            raise QgsProcessingException(self.explain(exc)) from None
        except UsageError as exc:
            raise QgsProcessingException(self.tr("Invalid parameter: {}").format(exc)) from None
        except Exception as exc:
            raise self._unexpected(exc) from None
        self._log(result, feedback)
        s = result.stats
        layer = written.get("gpkg")
        if layer and paths.gpkg_layer != "gcps":
            layer = f"{layer}|layername={paths.gpkg_layer}"
        results = {self.OUTPUT: written.get("raster"), self.GCP_LAYER: layer,
                   self.GCP_POINTS: written.get("points"), self.GCP_VRT: written.get("vrt"),
                   self.REPORT: written.get("report"), self.OUTPUT_HTML: written.get("html"),
                   "RMSE_PX": s.rmse_px, "RMS_LOO_PX": s.rms_loo_px,
                   "N_GCPS": s.n_gcps, "VERDICT": result.verification.verdict, "METHOD": result.method}
        return {k: v for k, v in results.items() if v is not None}

    def _reference(self, parameters, context, options, target):
        """What the target is registered onto (see :func:`hamta.processing.reference.reference_source`)."""
        layer = self.parameterAsLayer(parameters, self.REFERENCE, context)
        if layer is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, self.REFERENCE))
        return reference_source(layer, options.extent, target, options.max_working_pixels)

    def _run_arguments(self, values, output):
        """The method parameters :func:`hamta.core.runner.run` is given."""
        method = self.method()
        return {} if method is None else method_values(method, values)

    def explain(self, exc):
        """The error's message, naming the parameter that lets the user go on as this dialog shows it."""
        definition = self.parameterDefinition(dict(KEYS, accept_unverified=self.KEEP_UNVERIFIED).get(exc.option, ""))
        if definition is None:
            return str(exc)
        return self.tr("{} (set '{}').").format(exc, definition.description())

    def _setting(self, tip):
        """An :class:`~hamta.core.advice.Advice` as this dialog shows it: 'label' = value."""
        definition = self.parameterDefinition(KEYS.get(tip.option, self.KEEP_UNVERIFIED))
        if definition is None:
            return tip.option
        value = tip.value
        if tip.value is True:
            value = self.tr("on")
        elif isinstance(definition, QgsProcessingParameterEnum):
            choice = dict((f.name, spec.choice) for f, spec in option_fields(RegisterOptions))[tip.option]
            value = definition.options()[choice.index(tip.value)]
        return "'{}' = {}".format(definition.description(), value)

    def _log(self, result, feedback):
        for line in attempt_lines(result.auto):
            feedback.pushInfo(line)
        for note in result.notes:
            feedback.pushInfo(note)
        v = result.verification
        if v.verified:
            feedback.pushInfo(self.tr("Verified by an independent check: {}; estimated error within {}.").format(
                v.summary(), length_text(result, v.error_bound_px)))
        else:
            feedback.reportError(self.tr("NOT VERIFIED ({}): {}").format(v.verdict, "; ".join(v.reasons)))
            for tip in advice(result):
                feedback.pushInfo(self.tr("May help: {} ({}).").format(self._setting(tip), tip.why))
        if result.pixel_mode:
            feedback.pushWarning(pixel_mode_text())
        elif result.reference.crs is None:
            feedback.pushWarning(unknown_crs_text(result))
        s = result.stats
        feedback.pushInfo(self.tr("{}; self-reported RMSE {:.3f} px, leave-one-out RMS {} px (residuals of the fit, "
                                  "not its accuracy).").format(
            counts_text(s), s.rmse_px, "n/a" if s.rms_loo_px is None else f"{s.rms_loo_px:.3f}"))
