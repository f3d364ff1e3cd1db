"""Processing "Batch register": many targets in one run, on Dask (a thin adapter over hamta.core.batch)."""
from __future__ import annotations

from qgis.core import (
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingOutputVectorLayer,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFile,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QCoreApplication

from ..core import RegisterOptions
from ..core.auto import AUTO
from ..core.batch import read_jobs, run_batch
from ..core.batch.jobs import jobs_for_targets
from ..core.batch.runner import unauthenticated_warning
from ..core.batch.table import write_results
from ..core.batch.task import BatchSettings
from ..core.errors import HamtaError
from ..core.methods import all_methods
from .help import help_url
from .mapping import register_settings
from .options import advanced, option_parameters, option_values
from .reference import layer_reference
from .register_algorithm import PlainNumbers, feedback_progress

_CONTEXT = "BatchRegisterAlgorithm"


def batch_methods():
    """The methods offered: auto, then every method in the registry's order."""
    return [AUTO, *all_methods()]


class BatchRegisterAlgorithm(PlainNumbers, QgsProcessingAlgorithm):
    JOBS, TARGETS, REFERENCE, OUTPUT_FOLDER = "JOBS", "TARGETS", "REFERENCE", "OUTPUT_FOLDER"
    METHOD, KEEP_UNVERIFIED = "METHOD", "KEEP_UNVERIFIED"
    SCHEDULER, WORKERS, RESULTS, SHEET_CRS = "SCHEDULER", "WORKERS", "RESULTS", "SHEET_CRS"

    def tr(self, text):
        return QCoreApplication.translate(_CONTEXT, text)

    def createInstance(self):
        return BatchRegisterAlgorithm()

    def name(self):
        return "batchregister"

    def displayName(self):
        return self.tr("Batch register")

    def group(self):
        return self.tr("Registration")

    def groupId(self):
        return "registration"

    def helpUrl(self):
        return help_url(self)

    def shortHelpString(self):
        return self.tr(
            "Registers many targets in one run: the rasters chosen as targets onto one reference, or every row of a "
            "job list (CSV or GeoPackage with columns target, reference, method, model, output). Pairs run in "
            "parallel on Dask: a local cluster of threads inside QGIS (reachable only with TLS credentials made "
            "for the run), or an existing scheduler given as tls://host:port, with the certificates of Dask's "
            "configuration (distributed.comm.tls.*; tcp:// works but is unauthenticated). Each pair writes its "
            "outputs into its own folder under the output folder (a job list's output: a folder inside it); a pair "
            "that fails is recorded and the others go on; running again skips the pairs already done. The result "
            "layer holds every target's footprint with its verdict, error figures, method, time and output paths.\n\n"
            "Scanned sheets of a map series: choose no reference but the CRS of their printed coordinates; each sheet "
            "is georeferenced by its own printed grid (its labels read, or the hints of the Georeferencer's "
            "'<raster>.points' beside it); a job list does the same with its 'crs' and 'hints' columns.\n\n"
            "QGIS's own batch mode over the single-pair algorithms works too.")

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.TARGETS, self.tr("Target rasters"), QgsProcessing.TypeRaster, optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer(
            self.REFERENCE, self.tr("Reference raster (for the targets above)"), optional=True))
        jobs = QgsProcessingParameterFile(self.JOBS, self.tr("Job list instead (CSV or GeoPackage)"), optional=True,
                                          fileFilter=self.tr("Job lists (*.csv *.gpkg)"))
        jobs.setHelp(self.tr("Job list instead (CSV or GeoPackage: target, reference, method, model, crs, hints, "
                             "output)"))
        self.addParameter(jobs)
        sheet_crs = QgsProcessingParameterCrs(self.SHEET_CRS, self.tr("CRS of printed coordinates (sheets)"),
                                              optional=True)
        sheet_crs.setHelp(self.tr("Scanned sheets georeferenced by their own printed grid: what their printed "
                                  "coordinates count in (EPSG:4326 or EPSG:4269 for degrees, the national grid's CRS "
                                  "for its metres, feet or yards)"))
        self.addParameter(sheet_crs)
        self.addParameter(QgsProcessingParameterEnum(self.METHOD, self.tr("Method"), options=batch_methods(),
                                                     defaultValue=0))
        self.addParameter(QgsProcessingParameterBoolean(
            self.KEEP_UNVERIFIED, self.tr("Keep unverified results"), False))
        for p in option_parameters(RegisterOptions(), bands=False):
            self.addParameter(p)
        scheduler = QgsProcessingParameterString(self.SCHEDULER, self.tr("Dask scheduler (tls://host:port)"), "",
                                                 optional=True)
        scheduler.setHelp(self.tr("Dask scheduler (tls://host:port; empty: a local cluster)"))
        self.addParameter(advanced(scheduler))
        self.addParameter(advanced(QgsProcessingParameterNumber(
            self.WORKERS, self.tr("Workers of the local cluster (0: one per CPU)"),
            QgsProcessingParameterNumber.Integer, 0, minValue=0)))
        self.addParameter(QgsProcessingParameterFolderDestination(self.OUTPUT_FOLDER, self.tr("Output folder")))
        self.addOutput(QgsProcessingOutputVectorLayer(self.RESULTS, self.tr("Batch results (footprints)")))
        for name, label in (("VERIFIED", "Pairs verified"), ("UNVERIFIED", "Pairs not verified"),
                            ("FAILED", "Pairs failed")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(label)))

    def _jobs(self, parameters, context, out):
        jobs_file = self.parameterAsFile(parameters, self.JOBS, context)
        crs = self.parameterAsCrs(parameters, self.SHEET_CRS, context)
        sheet_crs = (crs.authid() or crs.toWkt()) if crs.isValid() else None
        if jobs_file:
            return read_jobs(jobs_file, out, sheet_crs=sheet_crs)
        layers = self.parameterAsLayerList(parameters, self.TARGETS, context)
        layer = self.parameterAsRasterLayer(parameters, self.REFERENCE, context)
        if layers and layer is None and sheet_crs:
            return jobs_for_targets([target.source() for target in layers], None, out, sheet_crs)
        if not layers or layer is None:
            raise QgsProcessingException(self.tr("Choose target rasters and a reference raster (or, for scanned "
                                                 "sheets by their printed grid, the CRS of their printed "
                                                 "coordinates), or a job list."))
        reference = layer_reference(layer)
        if reference is None:
            raise QgsProcessingException(self.tr(
                "The reference layer '{}' ({}) cannot be read by every pair of a batch: use a raster file, an XYZ or "
                "WMS layer, or save the layer's area as a GeoTIFF first.").format(layer.name(), layer.providerType()))
        return jobs_for_targets([target.source() for target in layers], reference, out)

    def processAlgorithm(self, parameters, context, feedback):
        out = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        options, _, output = register_settings(option_values(self, parameters, context))
        settings = BatchSettings(method=batch_methods()[self.parameterAsEnum(parameters, self.METHOD, context)],
                                 options=options, output=output,
                                 accept_unverified=self.parameterAsBoolean(parameters, self.KEEP_UNVERIFIED, context))
        scheduler = self.parameterAsString(parameters, self.SCHEDULER, context).strip() or None
        workers = self.parameterAsInt(parameters, self.WORKERS, context) or None

        warning = unauthenticated_warning(scheduler)
        if warning:
            feedback.reportError(warning)
        progress = feedback_progress(feedback)
        try:
            jobs = self._jobs(parameters, context, out)
            result = run_batch(jobs, settings, scheduler=scheduler, workers=workers, processes=False,
                               progress=progress, is_canceled=feedback.isCanceled)
            tables = write_results(out, result.records)
        except HamtaError as exc:
            raise QgsProcessingException(str(exc)) from None
        except Exception as exc:  # a bug or a cluster problem: a clear message, never a raw traceback
            raise QgsProcessingException(self.tr("Batch stopped on an unexpected error ({}: {}).").format(
                type(exc).__name__, exc)) from None
        for r in result.records:
            if r["status"] != "verified":
                feedback.reportError(f"{r['name']}: {r['status']} - {r['message']}")
        for note in result.notes:
            feedback.pushInfo(note)
        feedback.pushInfo(result.summary())
        counts = result.counts()
        return {self.OUTPUT_FOLDER: out, self.RESULTS: tables["gpkg"], "VERIFIED": counts["verified"],
                "UNVERIFIED": counts["unverified"], "FAILED": counts["failed"]}
