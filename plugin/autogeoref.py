"""The 'Auto-georeference…' dialog: the settings of registering a raster layer onto another layer of
the project (the basemap on the canvas, by default); :mod:`hamta.plugin.action` runs them.

The dialog proposes everything from what the user is looking at: the target is the selected raster
layer, the reference the visible basemap (an XYZ/WMS layer, else another visible raster layer), the
search area the map canvas extent (in the canvas CRS; it is used for a target without
georeferencing) and a new output folder next to the target.
"""
from __future__ import annotations

import dataclasses
import os
import tempfile
from typing import Optional

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsMapLayer,
    QgsMapLayerProxyModel,
    QgsProject,
    QgsRasterLayer,
    QgsSettings,
)
from qgis.gui import (
    QgsExtentGroupBox,
    QgsFileWidget,
    QgsMapLayerComboBox,
    QgsMessageBar,
    QgsProjectionSelectionWidget,
)
from qgis.PyQt.QtCore import QCoreApplication
from qgis.PyQt.QtWidgets import QCheckBox, QComboBox, QDialog, QDialogButtonBox, QFormLayout, QGroupBox, QVBoxLayout

from ..core.options import MODEL, RegisterOptions
from .task import tr

SETTINGS = "hamta/autogeoreference/"  # the model and local correction last run (not 'keep unverified': a safeguard)


def option_tr(text: str) -> str:
    """An option's label or help from :mod:`hamta.core.options`, translated as the Processing dialogs show it."""
    return QCoreApplication.translate("RegisterAlgorithm", text)


def is_georeferenced(path: str) -> bool:
    """Whether the raster file ``path`` has georeferencing the engine uses (a CRS and a geotransform or GCPs)."""
    try:
        from ..core.io.raster import open_raster

        info = open_raster(path, "target")
    except Exception:  # unreadable or no engine: the run says why
        return False
    return info.georeferenced and info.crs is not None


def default_folder(target: str) -> str:
    """A new folder for the outputs: ``<target name>_georeferenced`` next to the target (``_2``, ``_3``...
    when taken), or under the temporary folder when the target's folder cannot be written."""
    parent, stem = os.path.dirname(os.path.abspath(target)), os.path.splitext(os.path.basename(target))[0]
    if not os.access(parent, os.W_OK):
        parent = os.path.join(tempfile.gettempdir(), "hamta")
    base = os.path.join(parent, f"{stem}_georeferenced")
    folder, n = base, 1
    while os.path.exists(folder):
        n += 1
        folder = f"{base}_{n}"
    return folder


def can_reference(layer) -> bool:
    """Whether a layer can be registered onto: a map service, or a raster file with georeferencing (a scan
    not yet georeferenced cannot)."""
    if layer.providerType() == "wms":
        return True
    return layer.providerType() != "gdal" or is_georeferenced(layer.source())


def basemap(layers, target=None):
    """The layer to register onto among ``layers`` (visible raster layers, top first): the first map
    service ('wms' provider: XYZ, WMS, WMTS), else the first other georeferenced raster layer; never ``target``,
    never a raster without georeferencing."""
    candidates = [layer for layer in layers
                  if isinstance(layer, QgsRasterLayer) and layer is not target and can_reference(layer)]
    services = [layer for layer in candidates if layer.providerType() == "wms"]
    return (services or candidates or [None])[0]


def visible_layers():
    """The project's visible layers, top of the layer tree first."""
    return [node.layer() for node in QgsProject.instance().layerTreeRoot().findLayers()
            if node.isVisible() and node.layer() is not None]


@dataclasses.dataclass(frozen=True)
class Job:
    """One registration as the dialog set it: ``extent`` is the search area text
    ('xmin,ymin,xmax,ymax,EPSG:code', in that CRS) or None; without a ``reference``, ``grid`` holds the
    sheet's own grid's parameters (hints, sheet_crs: see :class:`hamta.core.grid.register.GridParams`)."""

    target: str
    target_name: str
    reference: Optional[QgsMapLayer]
    extent: Optional[str]
    folder: str
    options: RegisterOptions
    accept_unverified: bool
    grid: Optional[dict] = None


class AutoGeoreferenceDialog(QDialog):
    """The settings of one run; ``job()`` reads them once the user pressed Run (the dialog accepted)."""

    def __init__(self, iface, parent=None):
        super().__init__(parent)
        self.iface = iface
        self.setWindowTitle(tr("Auto-georeference"))
        self.bar = QgsMessageBar(self)
        form = QFormLayout()

        self.target = QgsMapLayerComboBox(self)
        self.target.setFilters(QgsMapLayerProxyModel.RasterLayer)
        files = [layer for layer in QgsProject.instance().mapLayers().values() if isinstance(layer, QgsRasterLayer)]
        self.target.setExceptedLayerList([layer for layer in files if layer.providerType() != "gdal"])
        active = iface.activeLayer()
        if isinstance(active, QgsRasterLayer) and active.providerType() == "gdal":
            self.target.setLayer(active)
        self.target.setToolTip(tr("The raster file to georeference (a raster layer read by GDAL)."))
        form.addRow(tr("Target raster"), self.target)

        self.reference = QgsMapLayerComboBox(self)
        self.reference.setFilters(QgsMapLayerProxyModel.RasterLayer | QgsMapLayerProxyModel.PolygonLayer
                                  | QgsMapLayerProxyModel.LineLayer)
        self.reference.setAllowEmptyLayer(True)
        self.reference.setLayer(basemap(visible_layers(), self.target.currentLayer()))
        self.reference.setToolTip(tr("The georeferenced layer to match the target on: a basemap (XYZ tiles, WMS, "
                                     "WMTS...), a raster, or a layer of areas or lines (water, buildings, roads: "
                                     "for a scanned map). The results are in its CRS. None: a scanned map is "
                                     "georeferenced by the grid printed on it."))
        form.addRow(tr("Reference layer"), self.reference)

        self.model = QComboBox(self)
        for value in MODEL.values:
            self.model.addItem(option_tr(MODEL.labels[value]), value)
        self.model.setCurrentIndex(max(0, self.model.findData(QgsSettings().value(SETTINGS + "model", MODEL.default))))
        form.addRow(option_tr("Transformation"), self.model)
        local = next(f for f in dataclasses.fields(RegisterOptions) if f.name == "local").metadata["option"]
        self.local = QCheckBox(option_tr(local.label), self)
        self.local.setToolTip(option_tr(local.help))
        self.local.setChecked(QgsSettings().value(SETTINGS + "local", False, type=bool))
        form.addRow("", self.local)

        self.area = QgsExtentGroupBox(self)
        self.area.setCheckable(True)
        self.area.setToolTip(tr("On by default for a target without georeferencing (the map canvas extent). On for "
                                "a georeferenced target, Hamta ignores the target's georeferencing and searches here."))
        canvas, output_crs = iface.mapCanvas(), QgsCoordinateReferenceSystem("EPSG:4326")
        if canvas is not None:
            crs = canvas.mapSettings().destinationCrs()
            output_crs = crs if crs.authid() else output_crs  # the text form names the CRS by its code
            self.area.setOutputCrs(output_crs)
            self.area.setCurrentExtent(canvas.extent(), crs)
            self.area.setOutputExtentFromCurrent()
            self.area.setMapCanvas(canvas)
        self.area.setTitleBase(tr("Search area, {} (where to look for the target)").format(output_crs.authid()))

        self.folder = QgsFileWidget(self)
        self.folder.setStorageMode(QgsFileWidget.GetDirectory)
        self.folder.setToolTip(tr("A folder for the warped raster, the GCPs (GeoPackage and .points) and the "
                                  "reports; files of an earlier run there are replaced."))
        self.keep = QCheckBox(tr("Keep unverified results"), self)
        self.keep.setToolTip(tr("Write the georeferenced raster even when the independent check does not confirm "
                                "the result (it is then marked NOT VERIFIED)."))
        form.addRow(tr("Output folder"), self.folder)
        form.addRow("", self.keep)

        self.buttons = QDialogButtonBox(QDialogButtonBox.Close, self)
        self.run_button = self.buttons.addButton(tr("Run"), QDialogButtonBox.AcceptRole)
        self.buttons.accepted.connect(self.check_and_accept)
        self.buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(self.bar)
        layout.addLayout(form)
        layout.addWidget(self.sheet_box())
        layout.addWidget(self.area)
        layout.addStretch(1)
        layout.addWidget(self.buttons)

        self._folder_for = None  # the target whose default folder the folder field shows
        self.target.layerChanged.connect(self.target_changed)
        self.reference.layerChanged.connect(self.reference_changed)
        self.target_changed(self.target.currentLayer())
        self.reference_changed(self.reference.currentLayer())
        self.resize(620, 0)

    def sheet_box(self):
        """The settings of a sheet georeferenced by its own grid (shown without a reference layer)."""
        self.sheet = QGroupBox(tr("By the sheet's own grid (no reference layer)"), self)
        form = QFormLayout(self.sheet)
        self.sheet_crs = QgsProjectionSelectionWidget(self.sheet)
        self.sheet_crs.setOptionVisible(QgsProjectionSelectionWidget.CrsNotSet, True)
        self.sheet_crs.setNotSetText(tr("choose the sheet's projection"))
        self.sheet_crs.setCrs(QgsCoordinateReferenceSystem())
        self.sheet_crs.setToolTip(tr("The sheet's projection: the results are in it (sheets rarely print it)."))
        form.addRow(tr("CRS of the sheet"), self.sheet_crs)
        self.hints = QgsFileWidget(self.sheet)
        self.hints.setFilter(tr("GCP points (*.points)"))
        self.hints.lineEdit().setPlaceholderText(tr("empty: the coordinates printed in the margins are read"))
        self.hints.setToolTip(tr("Two or three crossings of the printed lines placed roughly in the Georeferencer "
                                 "with their coordinates as printed, saved as GCP points; empty: the labels printed "
                                 "in the sheet's margins are read."))
        form.addRow(tr("Hints (.points)"), self.hints)
        return self.sheet

    def reference_changed(self, layer):
        """The sheet's settings without a reference layer; its hints default to the Georeferencer's file of the
        target (``<raster>.points``) where there is one."""
        self.sheet.setVisible(layer is None)
        self.area.setVisible(layer is not None)
        self.local.setVisible(layer is not None)  # a sheet's paper is followed by the model the check chooses
        target = self.target.currentLayer()
        if layer is None and target is not None and not self.hints.filePath():
            saved = target.source() + ".points"
            if os.path.isfile(saved):
                self.hints.setFilePath(saved)

    def target_changed(self, layer):
        """Search area on for a target without georeferencing; the default folder follows the target."""
        path = layer.source() if layer is not None else ""
        if layer is not None:
            self.area.setChecked(not is_georeferenced(path))
            if self.reference.currentLayer() in (None, layer):
                self.reference.setLayer(basemap(visible_layers(), layer))
        if self._folder_for is None or self.folder.filePath() == default_folder(self._folder_for):
            self.folder.setFilePath(default_folder(path) if path else "")
            self._folder_for = path or None

    def extent(self):
        """The search area text ('xmin,ymin,xmax,ymax,EPSG:code', in the box's output CRS), or None
        when it is off or empty."""
        if not self.area.isChecked():
            return None
        from ..processing.reference import extent_text

        return extent_text(self.area.outputExtent(), self.area.outputCrs())

    def problem(self):
        """Why the settings cannot run (a sentence), or None."""
        target, reference = self.target.currentLayer(), self.reference.currentLayer()
        if target is None:
            return tr("Choose the raster to georeference (add it to the project first).")
        if reference is None:
            if not self.sheet_crs.crs().isValid():
                return tr("Choose the CRS of the sheet, or a reference layer.")
            if self.hints.filePath() and not os.path.isfile(self.hints.filePath()):
                return tr("The hints file does not exist: choose the GCP points (.points) saved in the Georeferencer, "
                          "or leave it empty to have the sheet's printed labels read.")
        elif reference is target:
            return tr("Choose a reference layer other than the target: a basemap or a georeferenced raster.")
        elif isinstance(reference, QgsRasterLayer) and not can_reference(reference):
            return tr("'{}' has no georeferencing, so it cannot be the reference: choose a basemap or a "
                      "georeferenced raster, or no reference layer to georeference '{}' by its printed grid."
                      ).format(reference.name(), target.name())
        if not self.folder.filePath().strip():
            return tr("Choose an output folder.")
        if isinstance(reference, QgsRasterLayer) and self.extent() is None and not is_georeferenced(target.source()) \
                and reference.providerType() != "gdal":
            return tr("'{}' has no georeferencing: turn on the search area (the map canvas extent by default) so "
                      "that Hamta knows where to look in '{}'.").format(target.name(), reference.name())
        return None

    def check_and_accept(self):
        message = self.problem()
        if message:
            self.bar.clearWidgets()
            self.bar.pushWarning(tr("Auto-georeference"), message)
            return
        settings = QgsSettings()
        settings.setValue(SETTINGS + "model", self.model.currentData())
        settings.setValue(SETTINGS + "local", self.local.isChecked())
        self.accept()

    def job(self) -> Job:
        target, reference = self.target.currentLayer(), self.reference.currentLayer()
        extent = self.extent() if reference is not None else None
        ignore = extent is not None and is_georeferenced(target.source())  # the user chose where to look
        local = self.local.isChecked() and reference is not None
        options = RegisterOptions(model=self.model.currentData(), local=local, extent=extent,
                                  target_georef="ignore" if ignore else "auto")
        grid = None
        if reference is None:
            crs = self.sheet_crs.crs()
            grid = {"hints": self.hints.filePath() or None, "sheet_crs": crs.authid() or crs.toWkt()}
        return Job(target.source(), target.name(), reference, options.extent, self.folder.filePath().strip(), options,
                   self.keep.isChecked(), grid)
