"""The Processing algorithm that georeferences a scanned sheet by its own printed grid (a thin adapter over
:func:`hamta.core.runner.run` with the method 'grid', see :mod:`hamta.core.grid`)."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
)

from ..core import RegisterOptions
from ..core.grid.register import GridParams
from ..core.options import OutputOptions, option_fields, processing_key
from .catalogue import GRID_ALGORITHM
from .options import advanced, option_parameters
from .register_algorithm import RegisterAlgorithm

SHEET_OPTIONS = ("model", "tolerance_px", "target_band", "resampling", "pixel_grid", "crs", "resolution", "format",
                 "creation_options", "fill")  # the options that mean something for a sheet without a reference


class GridAlgorithm(RegisterAlgorithm):
    """'Georeference a scanned map by its grid': the target, the CRS of its printed coordinates and the hints (a
    ``.points`` file); the outputs of any registration (in the output CRS where one is chosen)."""

    SHEET_CRS, HINTS, STEP = "SHEET_CRS", "HINTS", "STEP"

    def __init__(self):
        super().__init__("grid")

    def createInstance(self):
        return GridAlgorithm()

    def method(self):
        return None

    def name(self):
        return GRID_ALGORITHM.id

    def displayName(self):
        return self.tr(GRID_ALGORITHM.title)

    def shortHelpString(self):
        return self.tr(GRID_ALGORITHM.help)

    def tags(self):
        return self.tr("georeference,scanned map,grid,graticule,sheet,GCP,crossings").split(",")

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterRasterLayer(self.TARGET, self.tr("Scanned map (to georeference)")))
        sheet_crs = QgsProcessingParameterCrs(self.SHEET_CRS, self.tr("CRS of the printed coordinates"))
        sheet_crs.setHelp(self.tr("What the coordinates printed on the sheet count in: EPSG:4326 or EPSG:4269 for "
                                  "degrees of a graticule (whatever projection it is drawn in: it is found), the "
                                  "national grid's CRS for its metres, feet or yards"))
        self.addParameter(sheet_crs)
        hints = QgsProcessingParameterFile(self.HINTS, self.tr("Hints: crossings placed (.points)"),
                                           extension="points", optional=True)
        hints.setHelp(self.tr("Two or three crossings of the printed lines placed roughly in the QGIS Georeferencer, "
                              "with their coordinates as printed (degrees, or the grid's units), saved as GCP points "
                              "(empty: the labels printed in the sheet's margins are read by OCR)"))
        self.addParameter(hints)
        self.addParameter(QgsProcessingParameterBoolean(self.KEEP_UNVERIFIED, self.tr("Keep unverified results"),
                                                        False))
        kept = {processing_key(f, spec) for cls in (RegisterOptions, OutputOptions) for f, spec in option_fields(cls)
                if f.name in SHEET_OPTIONS}
        for p in option_parameters(RegisterOptions()):
            if p.name() in kept:
                self.addParameter(p)
        number = QgsProcessingParameterNumber
        step = number(self.STEP, self.tr("Grid step (printed units)"), number.Double, None, optional=True)
        step.setMinimum(0.0)
        step.setHelp(self.tr("The step of the printed grid, in its coordinates (empty: the largest usual step the "
                             "hints or labels fit whose lines are printed)"))
        self.addParameter(advanced(step))
        self._add_outputs()

    def processAlgorithm(self, parameters, context, feedback):
        crs = self.parameterAsCrs(parameters, self.SHEET_CRS, context)
        if not crs.isValid():
            raise QgsProcessingException(self.tr("Choose the CRS of the printed coordinates."))
        step = parameters.get(self.STEP)
        self._grid = {"hints": self.parameterAsFile(parameters, self.HINTS, context) or None,
                      "step": None if step in (None, "") else self.parameterAsDouble(parameters, self.STEP, context),
                      "sheet_crs": crs.authid() or crs.toWkt()}
        return super().processAlgorithm(parameters, context, feedback)

    def _reference(self, parameters, context, options, target):
        return None

    def _run_arguments(self, values, output):
        return GridParams.make(self._grid, output)
