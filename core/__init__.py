"""Hamta's engine: raster IO, matching, estimation, verification and outputs. Never imports QGIS or
anything outside ``core``."""
from .errors import (
                     GeoreferencingError,
                     HamtaError,
                     InputError,
                     InsufficientMatchesError,
                     NoOverlapError,
                     OutputError,
                     RegistrationCanceled,
                     UnverifiedResult,
)
from .options import OutputOptions, RegisterOptions
from .pipeline import register
from .result import RegistrationResult
from .run import run
from .version import __version__

__all__ = ["register", "run", "RegisterOptions", "OutputOptions", "RegistrationResult", "HamtaError", "InputError",
           "NoOverlapError", "GeoreferencingError", "InsufficientMatchesError", "OutputError", "RegistrationCanceled",
           "UnverifiedResult", "__version__"]
