"""The verdict of the independent check, as every output carries it (tags, descriptions)."""
from __future__ import annotations

from .scale import length_text


def verdict_tags(result) -> dict:
    """Metadata items (GeoTIFF tags, VRT metadata) naming the method and the verdict."""
    v = result.verification
    tags = {"HAMTA_METHOD": result.method, "HAMTA_MODEL": result.model.kind,
            "HAMTA_VERDICT": "unchecked" if v is None else v.verdict}
    if result.run_id:
        tags["HAMTA_RUN_ID"] = result.run_id
    if result.pixel_mode:
        tags["HAMTA_PIXEL_MODE"] = pixel_mode_text()
    if v is not None:
        if v.error_bound_px is not None:
            tags["HAMTA_ERROR_BOUND_PX"] = f"{v.error_bound_px:.3f}"
        if v.reasons:
            tags["HAMTA_VERDICT_REASONS"] = "; ".join(v.reasons)
    return tags


def verdict_text(result) -> str:
    """One line: the verdict and, when not verified, why."""
    v = result.verification
    if v is None:
        return "not checked"
    if v.verified:
        bound = "" if v.error_bound_px is None else f", estimated error within {length_text(result, v.error_bound_px)}"
        return f"verified by an independent check{bound}"
    return f"NOT VERIFIED ({v.verdict}): " + "; ".join(v.reasons)


def counts_text(stats) -> str:
    """Where the GCPs came from, in words that add up: refinement measures its own points at full
    resolution, so a refined run can keep more GCPs than it had matches."""
    if stats.refined:
        return (f"{stats.n_gcps} GCPs kept of {stats.n_refined} points measured at full resolution "
                f"(seeded by {stats.n_inliers} agreeing matches of {stats.n_matches})")
    return f"{stats.n_gcps} GCPs kept of {stats.n_inliers} agreeing matches (of {stats.n_matches} found)"


def unknown_crs_text(result) -> str:
    return (f"the reference '{result.reference.path}' has a geotransform but no CRS: the outputs carry its "
            "geotransform, in map units whose CRS is unknown; give the reference its CRS (in QGIS, or gdal_edit.py "
            "-a_srs) to place them on a map")


def pixel_mode_text() -> str:
    return ("pixel-to-pixel registration: the reference has no georeferencing, so coordinates are the reference's "
            "pixels and the outputs carry no CRS")
