"""Processing parameters of the registration and output options, generated from their one definition
in :mod:`hamta.core.options` (name, type, default, bounds, advanced flag, help), and read back
generically; :func:`hamta.processing.mapping.register_settings` turns the values into settings."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingParameterBand,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterDefinition,
    QgsProcessingParameterEnum,
    QgsProcessingParameterExtent,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QCoreApplication

from ..core.options import OutputOptions, RegisterOptions, option_fields, option_type, processing_key
from .reference import extent_text

CONTEXT = "RegisterAlgorithm"  # Hamta's strings shown by the registration algorithms (core's included)
OPTION_CLASSES = (RegisterOptions, OutputOptions)
KEYS = {f.name: processing_key(f, spec) for cls in OPTION_CLASSES for f, spec in option_fields(cls)}  # field -> name


def tr(text: str) -> str:
    return QCoreApplication.translate(CONTEXT, text)


def advanced(p):
    """``p`` shown under Advanced."""
    p.setFlags(p.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
    return p


def enum_parameter(name, description, choice, default):
    """An enum parameter showing the translated labels of ``choice``, in its value order; ``default``
    None makes it optional (empty: the method's)."""
    labels = [tr(choice.labels[v]) for v in choice.values]
    index = None if default is None else choice.index(default)
    return QgsProcessingParameterEnum(name, description, options=labels, defaultValue=index, optional=index is None)


EXTENT_HELP = ("where to look for a target without usable georeferencing: an extent as QGIS writes it, "
               "xmin,xmax,ymin,ymax [EPSG:code] (with qgis_process, e.g. EXTENT='1180000,1200000,7050000,7065000 "
               "[EPSG:3857]'), or drawn on the canvas")


def option_parameters(defaults: RegisterOptions, output_defaults: OutputOptions = OutputOptions(), *,
                      bands: bool = True):
    """One parameter per option (basic first, then advanced, each in declaration order), with
    ``defaults``' values as defaults (a method's resolved defaults, say). ``bands=False`` asks for
    band numbers as plain integers (no single raster to list the bands of)."""
    made = []
    for cls, values in zip(OPTION_CLASSES, (defaults, output_defaults)):
        for f, spec in option_fields(cls):
            p = _parameter(f, spec, option_type(cls, f.name), getattr(values, f.name), bands)
            optional = bool(p.flags() & QgsProcessingParameterDefinition.FlagOptional)
            empty = QCoreApplication.translate("RegisterAlgorithm", "empty")
            text = tr(EXTENT_HELP if spec.kind == "extent" else spec.help)
            text += f" ({empty}: {tr(spec.unset)})" if spec.unset and optional else ""
            p.setHelp(text[:1].upper() + text[1:])  # the CLI's help, as a sentence
            made.append(p if not spec.advanced else advanced(p))
    return sorted(made, key=lambda p: bool(p.flags() & QgsProcessingParameterDefinition.FlagAdvanced))


def _parameter(f, spec, kind: type, default, bands: bool):
    name, label = processing_key(f, spec), tr(spec.label)
    number = QgsProcessingParameterNumber
    if spec.choice is not None:
        return enum_parameter(name, label, spec.choice, spec.choice.open_value if default is None else default)
    if spec.kind.startswith("band:") and bands:
        return QgsProcessingParameterBand(name, label, parentLayerParameterName=spec.kind[5:], optional=True)
    if spec.kind == "crs":
        return QgsProcessingParameterCrs(name, label, optional=True)
    if spec.kind == "list":
        return QgsProcessingParameterString(name, label, "", optional=True)
    if spec.kind == "extent":
        return QgsProcessingParameterExtent(name, label, optional=True)
    if kind is bool:
        return QgsProcessingParameterBoolean(name, label, default)
    p = number(name, label, number.Integer if kind is int else number.Double, default, optional=default is None)
    if spec.minimum is not None:
        p.setMinimum(spec.minimum)
    return p


def option_values(alg, parameters, context) -> dict:
    """Each option's value keyed by its Processing name: an enum index, a number, a flag, text, a CRS as
    text; None where the user left an optional parameter empty; nothing for an option ``alg`` does not offer."""
    values = {}
    for cls in OPTION_CLASSES:
        for f, spec in option_fields(cls):
            key = processing_key(f, spec)
            definition = alg.parameterDefinition(key)
            if definition is None:  # an option this algorithm does not offer: its default
                continue
            raw = parameters.get(key)
            if (raw is None or raw == "") and definition.defaultValue() is None:
                values[key] = None
            elif spec.choice is not None:
                values[key] = alg.parameterAsEnum(parameters, key, context)
            elif spec.kind == "crs":
                crs = alg.parameterAsCrs(parameters, key, context)
                values[key] = (crs.authid() or crs.toWkt()) if crs.isValid() else None
            elif spec.kind == "list":
                values[key] = alg.parameterAsString(parameters, key, context)
            elif spec.kind == "extent":
                values[key] = extent_text(alg.parameterAsExtent(parameters, key, context),
                                          alg.parameterAsExtentCrs(parameters, key, context))
            elif option_type(cls, f.name) is bool:
                values[key] = alg.parameterAsBoolean(parameters, key, context)
            elif option_type(cls, f.name) is int:
                values[key] = alg.parameterAsInt(parameters, key, context)
            else:
                values[key] = alg.parameterAsDouble(parameters, key, context)
    return values
