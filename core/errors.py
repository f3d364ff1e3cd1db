"""Errors Hamta raises on bad input or an impossible registration.

Every error a user can cause derives from :class:`HamtaError`; its message names the file and the
problem. Front ends translate it once: the CLI prints it, Processing raises ``QgsProcessingException``.
A bug inside a method is not one of them: it is :class:`MethodCrashed`, naming the method.
"""
from contextlib import contextmanager


class HamtaError(Exception):
    """Root of every error Hamta raises for bad input or a registration that cannot be done.

    ``option`` names the setting (a :class:`hamta.core.options.RegisterOptions` field or a
    ``run`` argument) that lets the user go on; each front end says how to set it in its own words.
    """

    option = None


class UsageError(ValueError):
    """A value of the command line or of a run's parameters that cannot be used (an unknown method or option, a
    number out of range, a malformed search area), found while they are checked, before any work. Any other
    exception during a run is an internal error (a bug), not the user's."""


class InputError(HamtaError, ValueError):
    """An input raster is missing, unreadable, empty, constant or of an unsupported type."""


class NoOverlapError(HamtaError):
    """The georeferenced footprints of target and reference do not intersect."""


class GeoreferencingError(HamtaError):
    """A map is required but neither raster carries georeferencing."""


class ReferenceNotGeoreferenced(GeoreferencingError):
    """The reference has no georeferencing and pixel-to-pixel registration was not asked for."""

    option = "pixel_mode"


class InsufficientMatchesError(HamtaError):
    """Too few correspondences survived matching or robust estimation to fit the model."""

    def __init__(self, message: str, found: int, needed: int):
        super().__init__(message)
        self.found = found
        self.needed = needed
        self.correspondences = None  # what the method did return, for diagnostics


class NoConsensusError(InsufficientMatchesError, ValueError):
    """RANSAC had fewer correspondences than a minimal sample, or no hypothesis that enough of them
    agree on. Also a ValueError, which RANSAC raised before this had a class of its own."""


class Refused(HamtaError):
    """A method looked and found nothing it could register (a sheet whose printed grid or labels were not
    found). ``findings`` (JSON-able) says what was read and tried, for a report; ``written`` the report files
    written for it."""

    def __init__(self, message: str, findings: dict):
        super().__init__(message)
        self.findings = findings
        self.written = {}


class MethodCrashed(Exception):
    """A method's attempt raised something other than a :class:`HamtaError`: a bug in Hamta, not bad
    input nor a pair too hard for the method, so it ends the run (``auto`` does not go on). Not a
    HamtaError on purpose. ``method`` names the method; the original exception is ``__cause__``."""

    def __init__(self, method: str, cause: BaseException):
        super().__init__(f"internal error in method '{method}' ({type(cause).__name__}: {cause})")
        self.method = method


@contextmanager
def method_crashes(method: str):
    """Inside, any exception but a :class:`HamtaError`, a lack of memory or an operating-system (I/O)
    error (resources, not bugs; a KeyboardInterrupt neither) is re-raised as :class:`MethodCrashed`
    naming ``method``, from the original."""
    try:
        yield
    except (HamtaError, MethodCrashed, MemoryError, OSError):
        raise
    except Exception as exc:
        raise MethodCrashed(method, exc) from exc


class OutputError(HamtaError, OSError):
    """An output cannot be written (folder not writable, disk full, ...)."""


class ForeignFiles(OutputError):
    """A run folder holds files Hamta did not write there; they are replaced only when asked."""

    option = "overwrite"


class RegistrationCanceled(HamtaError):
    """The caller asked to stop; nothing was written."""


class DeadlineReached(HamtaError):
    """A step ran past the time it was given (``auto``'s budget); ``auto`` stops it and goes on."""


class UnverifiedResult(HamtaError):
    """A model was found, but the independent check did not confirm it, so no georeferenced output
    was written (only the report, when one was asked for). ``result`` holds everything found;
    ``written`` what was written."""

    option = "accept_unverified"

    def __init__(self, message: str, result, written=None):
        super().__init__(message)
        self.result = result
        self.written = dict(written or {})
