"""Hamta's engine: raster IO, matching, estimation and outputs. Never imports QGIS."""
from .errors import (GeoreferencingError, HamtaError, InputError, InsufficientMatchesError, NoOverlapError,
                     OutputError, RegistrationCanceled)
from .pipeline import RegisterOptions, register
from .result import RegistrationResult

__all__ = ["register", "RegisterOptions", "RegistrationResult", "HamtaError", "InputError", "NoOverlapError",
           "GeoreferencingError", "InsufficientMatchesError", "OutputError", "RegistrationCanceled"]
