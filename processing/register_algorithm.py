"""Processing algorithms that register a raster with one Hamta method each (thin adapters)."""
from __future__ import annotations

import dataclasses
import re

from qgis.core import (
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsProcessingParameterBand,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterDefinition,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterDestination,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
    QgsProcessingParameterVectorDestination,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, QCoreApplication

from ..core import RegisterOptions, UnverifiedResult, run
from ..core.auto import AUTO
from ..core.errors import HamtaError, RegistrationCanceled
from ..core.methods import get_method
from ..core.options import resolve_options
from ..core.outputs.tags import counts_text, pixel_mode_text
from .help import help_url
from .mapping import ENUMS, method_parameter_name, method_values, register_settings

_CONTEXT = "RegisterAlgorithm"  # every string below is translated in this context


def advanced(p):
    """``p`` shown under Advanced."""
    p.setFlags(p.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
    return p


def enum_parameter(name, description, default=None):
    """An enum parameter showing the translated labels of ``ENUMS[name]``, in its value order."""
    choice = ENUMS[name]
    labels = [QCoreApplication.translate(_CONTEXT, choice.labels[v]) for v in choice.values]
    return QgsProcessingParameterEnum(name, description, options=labels,
                                      defaultValue=choice.index(default or choice.default))


def decimals(value) -> int:
    """Decimals a spin box shows for a default ``value``: its own, at least 2 (QGIS shows 6: '3.000000')."""
    text = f"{float(value):.6f}".rstrip("0")
    return min(6, max(2, len(text.split(".")[1])))


LABEL_CHARS = 44  # longer labels make the parameters panel of an 800 px dialog scroll sideways


def short_label(text: str, name: str) -> str:
    """A method parameter's label: the first phrase of its help when that is short, else its name."""
    head = re.split(r" \(|: |; |\. | = |, ", text, maxsplit=1)[0].rstrip(".")
    return head if len(head) <= LABEL_CHARS else name.replace("_", " ").capitalize()


def feedback_progress(feedback):
    """A ``progress(fraction, message)`` callback reporting to Processing ``feedback``; each stage's
    message is logged once, not at every step of it."""
    last = [None]

    def progress(fraction, message):
        feedback.setProgress(100.0 * fraction)
        if message and message != last[0]:
            last[0] = message
            feedback.setProgressText(message)
    return progress


class PlainNumbers:
    """Mixed into an algorithm: its decimal parameters show their defaults as written ('3.00')."""

    def addParameter(self, p, createOutput=True):
        if isinstance(p, QgsProcessingParameterNumber) and p.dataType() == QgsProcessingParameterNumber.Double \
                and p.defaultValue() is not None:
            p.setMetadata({"widget_wrapper": {"decimals": decimals(p.defaultValue())}})
        return super().addParameter(p, createOutput)


class RegisterAlgorithm(PlainNumbers, QgsProcessingAlgorithm):
    """Base class: subclasses set ``METHOD``, ``ALG_NAME``, ``DISPLAY_NAME`` and ``HELP``."""

    METHOD = ""
    ALG_NAME = ""
    DISPLAY_NAME = ""
    HELP = ""

    TARGET, TARGET_BAND = "TARGET", "TARGET_BAND"
    REFERENCE, REFERENCE_BAND = "REFERENCE", "REFERENCE_BAND"
    MODEL, RESAMPLING, GRID = "MODEL", "RESAMPLING", "GRID"
    MAX_WORKING_PIXELS, RANSAC_THRESHOLD, SEED = "MAX_WORKING_PIXELS", "RANSAC_THRESHOLD", "SEED"
    REFINE, MAX_GCPS, TARGET_GEOREF = "REFINE", "MAX_GCPS", "TARGET_GEOREF"
    TOLERANCE, KEEP_UNVERIFIED = "TOLERANCE", "KEEP_UNVERIFIED"
    OUTPUT, GCP_LAYER, GCP_POINTS, GCP_VRT, REPORT = "OUTPUT", "GCP_LAYER", "GCP_POINTS", "GCP_VRT", "REPORT"
    OUTPUT_HTML, OUTPUT_CRS, RESOLUTION, FORMAT = "OUTPUT_HTML", "OUTPUT_CRS", "RESOLUTION", "FORMAT"
    CREATION_OPTIONS, FILL, NODATA = "CREATION_OPTIONS", "FILL", "NODATA"
    LOCAL, LOCAL_WINDOW, LOCAL_SPACING = "LOCAL", "LOCAL_WINDOW", "LOCAL_SPACING"
    PIXEL_MODE = "PIXEL_MODE"

    def method(self):
        """The registered method this algorithm runs (None for 'auto', which chooses among them)."""
        return None if self.METHOD == AUTO else get_method(self.METHOD)

    def tr(self, text):
        return QCoreApplication.translate(_CONTEXT, text)

    def createInstance(self):
        return self.__class__()

    def name(self):
        return self.ALG_NAME

    def displayName(self):
        return self.tr(self.DISPLAY_NAME)

    def group(self):
        return self.tr("Registration")

    def groupId(self):
        return "registration"

    def shortHelpString(self):
        return self.tr(self.HELP)

    def helpUrl(self):
        return help_url(self)

    def tags(self):
        return self.tr("georeference,coregistration,registration,GCP,match,align,warp").split(",")

    def initAlgorithm(self, config=None):
        method = self.method()
        d = RegisterOptions(model="affine") if method is None else resolve_options(RegisterOptions(), method)
        self.addParameter(QgsProcessingParameterRasterLayer(self.TARGET, self.tr("Target raster (to georeference)")))
        self.addParameter(QgsProcessingParameterRasterLayer(self.REFERENCE, self.tr("Reference raster")))
        self.addParameter(enum_parameter(self.MODEL, self.tr("Transformation"), d.model))
        self.addParameter(enum_parameter(self.RESAMPLING, self.tr("Resampling")))
        self.addParameter(QgsProcessingParameterBoolean(
            self.KEEP_UNVERIFIED, self.tr("Keep unverified results"), False))
        self.addParameter(QgsProcessingParameterBoolean(self.LOCAL, self.tr("Local (non-rigid) correction"), False))
        self.addParameter(advanced(QgsProcessingParameterBoolean(
            self.PIXEL_MODE, self.tr("Pixel-to-pixel (reference not georeferenced)"), False)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.LOCAL_WINDOW, self.tr("Local window (reference px; 0: automatic)"),
            QgsProcessingParameterNumber.Integer, d.local_window_px, minValue=0)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.LOCAL_SPACING, self.tr("Local grid spacing (reference px; 0: automatic)"),
            QgsProcessingParameterNumber.Double, d.local_spacing_px, minValue=0.0)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.TOLERANCE, self.tr("Accuracy asked for (reference px)"),
            QgsProcessingParameterNumber.Double, d.tolerance_px, minValue=0.01)))
        self.addParameter(advanced(QgsProcessingParameterBand(
            self.TARGET_BAND, self.tr("Target band to match"),
            parentLayerParameterName=self.TARGET, optional=True)))
        self.addParameter(advanced(QgsProcessingParameterBand(
            self.REFERENCE_BAND, self.tr("Reference band to match"), parentLayerParameterName=self.REFERENCE,
            optional=True)))
        self.addParameter(advanced(enum_parameter(self.TARGET_GEOREF, self.tr("Target's own georeferencing"))))
        self.addParameter(advanced(enum_parameter(self.GRID, self.tr("Output pixel grid"))))
        self.addParameter(advanced(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: the reference's)"), optional=True)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.RESOLUTION, self.tr("Output pixel size (output CRS units)"),
            QgsProcessingParameterNumber.Double, None, optional=True, minValue=0.0)))
        self.addParameter(advanced(enum_parameter(self.FORMAT, self.tr("Output format"))))
        self.addParameter(advanced(QgsProcessingParameterString(
            self.CREATION_OPTIONS, self.tr("GDAL creation options"), "",
            optional=True)))
        self.addParameter(advanced(enum_parameter(self.FILL, self.tr("Pixels outside the target"))))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.NODATA, self.tr("Nodata value"),
            QgsProcessingParameterNumber.Double, None, optional=True)))
        self.addParameter(advanced(enum_parameter(self.REFINE, self.tr("Full-resolution refinement"))))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.MAX_WORKING_PIXELS, self.tr("Working image size (pixels)"), QgsProcessingParameterNumber.Integer,
            d.max_working_pixels, minValue=4096)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.RANSAC_THRESHOLD, self.tr("RANSAC tolerance (working px)"),
            QgsProcessingParameterNumber.Double, d.ransac_threshold_px, optional=method is None, minValue=0.1)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.MAX_GCPS, self.tr("Maximum number of GCPs"), QgsProcessingParameterNumber.Integer, d.max_gcps,
            minValue=4)))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.SEED, self.tr("Random seed"), QgsProcessingParameterNumber.Integer, d.seed, minValue=0)))
        for name, text in self._tooltips().items():
            self.parameterDefinition(name).setHelp(text)
        for f in self._fields():
            p = self._method_parameter(f)
            self.addParameter(p if f.metadata.get("basic") else advanced(p))

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

    def _tooltips(self):
        """The whole wording of parameters whose label is kept short enough for the panel."""
        return {
            self.LOCAL_WINDOW: self.tr('Local correction window (reference pixels; 0: automatic)'),
            self.LOCAL_SPACING: self.tr('Local correction grid spacing (reference pixels; 0: automatic)'),
            self.TOLERANCE: self.tr('Accuracy asked for (reference pixels): verified only within it'),
            self.TARGET_BAND: self.tr('Target band to match (empty: luminance of RGB, else band 1)'),
            self.RESOLUTION: self.tr('Output pixel size in output CRS units (empty: from the pixel grid)'),
            self.CREATION_OPTIONS: self.tr('GDAL creation options (KEY=VALUE, separated by spaces)'),
            self.NODATA: self.tr("Nodata value (with 'Nodata value' above; empty: the target's, else 0)"),
            self.RANSAC_THRESHOLD: self.tr("RANSAC tolerance (working pixels; empty: the method's)"),
        }

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
        layer = self.parameterAsRasterLayer(parameters, name, context)
        if layer is None:
            raise QgsProcessingException(self.invalidRasterError(parameters, name))
        if layer.providerType() != "gdal":
            raise QgsProcessingException(self.tr("{} must be a raster file GDAL can read, not a '{}' layer.")
                                         .format(layer.name(), layer.providerType()))
        return layer.source()

    def _values(self, parameters, context):
        v = {
            self.MODEL: self.parameterAsEnum(parameters, self.MODEL, context),
            self.RESAMPLING: self.parameterAsEnum(parameters, self.RESAMPLING, context),
            self.GRID: self.parameterAsEnum(parameters, self.GRID, context),
            self.REFINE: self.parameterAsEnum(parameters, self.REFINE, context),
            self.TARGET_GEOREF: self.parameterAsEnum(parameters, self.TARGET_GEOREF, context),
            self.TARGET_BAND: self.parameterAsInt(parameters, self.TARGET_BAND, context),
            self.REFERENCE_BAND: self.parameterAsInt(parameters, self.REFERENCE_BAND, context),
            self.MAX_WORKING_PIXELS: self.parameterAsInt(parameters, self.MAX_WORKING_PIXELS, context),
            self.RANSAC_THRESHOLD: self.parameterAsDouble(parameters, self.RANSAC_THRESHOLD, context),
            self.MAX_GCPS: self.parameterAsInt(parameters, self.MAX_GCPS, context),
            self.SEED: self.parameterAsInt(parameters, self.SEED, context),
            self.OUTPUT: self.parameterAsOutputLayer(parameters, self.OUTPUT, context),
            self.GCP_LAYER: self.parameterAsOutputLayer(parameters, self.GCP_LAYER, context),
            self.GCP_POINTS: self.parameterAsFileOutput(parameters, self.GCP_POINTS, context),
            self.GCP_VRT: self.parameterAsFileOutput(parameters, self.GCP_VRT, context),
            self.REPORT: self.parameterAsFileOutput(parameters, self.REPORT, context),
            self.OUTPUT_HTML: self.parameterAsFileOutput(parameters, self.OUTPUT_HTML, context),
            self.OUTPUT_CRS: self._crs(parameters, context),
            self.RESOLUTION: self._optional_number(parameters, self.RESOLUTION, context),
            self.FORMAT: self.parameterAsEnum(parameters, self.FORMAT, context),
            self.CREATION_OPTIONS: self.parameterAsString(parameters, self.CREATION_OPTIONS, context),
            self.FILL: self.parameterAsEnum(parameters, self.FILL, context),
            self.NODATA: self._optional_number(parameters, self.NODATA, context),
            self.TOLERANCE: self.parameterAsDouble(parameters, self.TOLERANCE, context),
            self.KEEP_UNVERIFIED: self.parameterAsBoolean(parameters, self.KEEP_UNVERIFIED, context),
            self.LOCAL: self.parameterAsBoolean(parameters, self.LOCAL, context),
            self.LOCAL_WINDOW: self.parameterAsInt(parameters, self.LOCAL_WINDOW, context),
            self.LOCAL_SPACING: self.parameterAsDouble(parameters, self.LOCAL_SPACING, context),
            self.PIXEL_MODE: self.parameterAsBoolean(parameters, self.PIXEL_MODE, context),
        }
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

    def _crs(self, parameters, context):
        crs = self.parameterAsCrs(parameters, self.OUTPUT_CRS, context)
        if not crs.isValid():
            return None
        return crs.authid() or crs.toWkt()

    def _optional_number(self, parameters, name, context):
        value = parameters.get(name)
        return None if value is None or value == "" else self.parameterAsDouble(parameters, name, context)

    def processAlgorithm(self, parameters, context, feedback):
        method = self.method()
        target = self._raster_path(parameters, self.TARGET, context)
        reference = self._raster_path(parameters, self.REFERENCE, context)
        values = self._values(parameters, context)
        options, paths, output = register_settings(values)
        if paths.gpkg and not paths.gpkg.lower().endswith(".gpkg"):
            raise QgsProcessingException(self.tr("GCP points are written to a GeoPackage: choose a .gpkg file (got "
                                                 "'{}').").format(values[self.GCP_LAYER]))

        progress = feedback_progress(feedback)
        params = {} if method is None else method_values(method, values)
        try:
            result, written = run(target, reference, paths, method=self.METHOD, params=params, options=options,
                                  output=output, accept_unverified=values[self.KEEP_UNVERIFIED], progress=progress,
                                  is_canceled=feedback.isCanceled)
        except RegistrationCanceled:
            raise QgsProcessingException(self.tr("Registration canceled; no outputs were written.")) from None
        except UnverifiedResult as exc:
            self._log(exc.result, feedback)
            raise QgsProcessingException(self.tr(
                "The registration was not verified: {}. No georeferenced output was written; set 'Keep unverified "
                "results' to write it anyway.").format("; ".join(exc.result.verification.reasons))) from None
        except HamtaError as exc:
            raise QgsProcessingException(self.explain(exc)) from None
        except ValueError as exc:
            raise QgsProcessingException(self.tr("Invalid parameter: {}").format(exc)) from None
        except Exception as exc:  # a bug: a clear message, never a raw traceback in the dialog
            message = self.tr("Hamta stopped on an unexpected error ({}: {}); no output was written. Please report it.")
            raise QgsProcessingException(message.format(type(exc).__name__, exc)) from None
        self._log(result, feedback)
        s = result.stats
        layer = written.get("gpkg")
        if layer and paths.gpkg_layer != "gcps":
            layer = f"{layer}|layername={paths.gpkg_layer}"
        results = {self.OUTPUT: written.get("raster"), self.GCP_LAYER: layer,
                   self.GCP_POINTS: written.get("points"), self.GCP_VRT: written.get("vrt"),
                   self.REPORT: written.get("report"), self.OUTPUT_HTML: written.get("html"),
                   "RMSE_PX": s["rmse_px"], "RMS_LOO_PX": s["rms_loo_px"],
                   "N_GCPS": s["n_gcps"], "VERDICT": result.verification.verdict, "METHOD": result.method}
        return {k: v for k, v in results.items() if v is not None}

    def explain(self, exc):
        """The error's message, naming the parameter that lets the user go on as this dialog shows it."""
        names = {"pixel_mode": self.PIXEL_MODE, "accept_unverified": self.KEEP_UNVERIFIED}
        if exc.option not in names:
            return str(exc)
        definition = self.parameterDefinition(names[exc.option])
        return self.tr("{} (set '{}').").format(exc, definition.description())

    def _log(self, result, feedback):
        for a in (result.auto or {}).get("attempts", []):
            feedback.pushInfo(self.tr("Tried {}: {} ({:.1f} s) - {}").format(a["method"], a["outcome"], a["time_s"],
                                                                            a["reason"]))
        for note in result.notes:
            feedback.pushInfo(note)
        v = result.verification
        if v.verified:
            feedback.pushInfo(self.tr("Verified by an independent check: {} of {} sites agree; estimated error within "
                                      "{:.2f} px.").format(v.n_agree, v.n_sites, v.error_bound_px))
        else:
            feedback.reportError(self.tr("NOT VERIFIED ({}): {}").format(v.verdict, "; ".join(v.reasons)))
        if result.pixel_mode:
            feedback.pushWarning(pixel_mode_text())
        s = result.stats
        feedback.pushInfo(self.tr("{}; self-reported RMSE {:.3f} px, leave-one-out RMS {} px (residuals of the fit, "
                                  "not its accuracy).").format(
            counts_text(s), s["rmse_px"], "n/a" if s["rms_loo_px"] is None else f"{s['rms_loo_px']:.3f}"))


class RegisterAutoAlgorithm(RegisterAlgorithm):
    METHOD = AUTO
    ALG_NAME = "registerauto"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register raster (automatic)")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers the target raster onto the reference raster and chooses the method itself: the fast SIFT "
        "matcher first, then matchers for images of different modality (SAR, infrared, maps) and for SAR, until "
        "a result passes an independent check. The check compares the two rasters at sites spread over the "
        "overlap, not the matches the model was fitted on, against what wrong alignments of the same rasters "
        "give, and bounds the remaining error. A result that does not verify is not written unless 'Keep "
        "unverified results' is set; the log lists every method tried, its verdict and its time. The other "
        "algorithms of this group run one method each, for experts.")


class RegisterSiftAlgorithm(RegisterAlgorithm):
    METHOD = "sift"
    ALG_NAME = "registersift"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register raster (SIFT baseline)")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers the target raster onto the reference raster automatically: OpenCV SIFT keypoints, Lowe's ratio "
        "test with a mutual check, seeded RANSAC, full-resolution refinement, and the chosen transformation fitted "
        "on well-spread GCPs. Writes the georeferenced raster, the GCPs as a point layer and, on request, a QGIS "
        "Georeferencer .points file, a VRT carrying the GCPs and a JSON report.\n\nReference: D. G. Lowe "
        "(2004), Distinctive image features from scale-invariant keypoints, IJCV 60(2):91-110, "
        "doi:10.1023/B:VISI.0000029664.99615.94")


class RegisterRilbpAlgorithm(RegisterAlgorithm):
    METHOD = "rilbp"
    ALG_NAME = "registerrilbp"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register satellite image (RILBP, rotation-invariant)")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers an optical satellite image onto a reference with any rotation between them: CenSurE octagon "
        "keypoints described by the rotation-invariant LBP descriptor (rings, intensity-order sub-regions, "
        "centre-symmetric LBP in each pixel's radial frame; no orientation step), mutual ratio-test matching, "
        "seeded RANSAC and the chosen transformation fitted on well-spread GCPs. Product defaults add sub-pixel "
        "keypoints and smoothed, radius-2 codes; the CLI method 'rilbp-faithful' is the paper as written."
        "\n\nReference: A. Sedaghat and N. Mohammadi (2019), Rotation invariant local binary pattern "
        "descriptor for remote sensing image matching, Journal of Geospatial Information Technology 7(2):223-239; "
        "M. Agrawal, K. Konolige and M. R. Blas (2008), CenSurE, ECCV.")


class RegisterSibrifAlgorithm(RegisterAlgorithm):
    METHOD = "sibrif"
    ALG_NAME = "registersibrif"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register aerial image onto satellite image (SIBRIF, fast)")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers an aerial (or any optical) image onto a satellite reference quickly: SIFT difference-of-Gaussian "
        "keypoints detected on a thresholded Sobel edge image, rBRIEF binary descriptors steered by the intensity "
        "centroid, removal of self-similar keypoints, mutual Hamming matching and RANSAC with affine samples. Few, "
        "strong keypoints make it several times faster than SIFT. Product defaults describe each keypoint at its "
        "own scale and add a ratio test; the CLI method 'sibrif-faithful' is the paper as written."
        "\n\nReference: M. Safdari, P. Moallem and M. Sattari, Robust and fast aerial and satellite image "
        "matching based on selective scale and rotation (SIBRIF).")


class RegisterNdsiftAlgorithm(RegisterAlgorithm):
    METHOD = "ndsift-pc"
    ALG_NAME = "registerndsift"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm",
                                     "Register SAR image onto SAR image (ND-SIFT + phase congruency)")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers a SAR image onto a SAR reference (another date, band or polarisation) despite speckle: a "
        "nonlinear diffusion scale space whose conductance uses the speckle-robust ROEWA gradient, SIFT keypoints "
        "and descriptors on it, keypoints kept only where phase congruency shows real structure, ratio-test "
        "matching, seeded RANSAC, then correlation refinement on a grid at full resolution. Set what the rasters "
        "hold (amplitude, intensity or dB; complex data is read as amplitude). Product defaults pre-smooth and use "
        "a one-way ratio test; the CLI method 'ndsift-pc-faithful' is the paper as written."
        "\n\nReference: J. Fan, Y. Wu, F. Wang, Q. Zhang, G. Liao and M. Li (2015), SAR image registration "
        "using phase congruency and nonlinear diffusion-based SIFT, IEEE Geoscience and Remote Sensing Letters "
        "12(3):562-566, doi:10.1109/LGRS.2014.2351396")


class RegisterSarOpticalAlgorithm(RegisterAlgorithm):
    METHOD = "cfog"
    ALG_NAME = "registersaroptical"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register SAR image onto optical image")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers a SAR image (the target) onto an optical reference, where intensities do not correspond and "
        "contrast is often inverted: an exhaustive search over rotation (up to 30 degrees either way), scale "
        "(up to 2 times either way) and shift on CFOG structural descriptors (gradient orientations, blind to "
        "the sign of contrast), then CFOG template matching on a regular grid, seeded RANSAC, the chosen "
        "transformation on well-spread GCPs, and full-resolution refinement of decimated images with the same "
        "similarity. Widen the rotation range for targets that are not roughly north-up. The CLI method "
        "'lines-spectral-faithful' is the thesis's line-intersection matcher as written (Radon lines, eigenvector "
        "and Voronoi/Hausdorff spectral matching), which rarely finds enough correct matches to register."
        "\n\nReferences: S. Gholami (2018), Automatic registration of SAR images onto optical images, M.Sc. "
        "thesis, Shahrood University of Technology; Y. Ye, L. Bruzzone, J. Shan, F. Bovolo and Q. Zhu (2019), "
        "Fast and robust matching for multimodal remote sensing image registration, IEEE Transactions on "
        "Geoscience and Remote Sensing 57(11):9059-9070, doi:10.1109/TGRS.2019.2924684")


class RegisterCrossModalAlgorithm(RegisterAlgorithm):
    METHOD = "xmodal"
    ALG_NAME = "registercrossmodal"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RegisterAlgorithm", "Register across modalities at any rotation and scale")
    HELP = QT_TRANSLATE_NOOP(
        "RegisterAlgorithm",
        "Registers a target of another modality than the reference (SAR, infrared, a depth rendering, a web map, "
        "night lights onto optical imagery) at any rotation and at scales from 1/2 to 2: phase-congruency (RIFT) "
        "features vote for rotation and scale, each hypothesis is checked densely with CFOG structural "
        "descriptors, the best are refined by matching RIFT descriptors near their predicted positions, and the "
        "result is refined at full resolution with CFOG and checked independently. Its baseline, the published "
        "RIFT2 matcher, is the CLI method 'rift'.\n\nReferences: J. Li, Q. Hu and M. Ai (2020), RIFT, IEEE "
        "Transactions on Image Processing 29:3296-3310; J. Li, Q. Hu and Y. Zhang (2023), Multimodal image "
        "matching: a scale-invariant algorithm and an open dataset, ISPRS Journal of Photogrammetry and Remote "
        "Sensing 204:77-88; Y. Ye et al. (2019), CFOG, IEEE TGRS 57(11):9059-9070.")

